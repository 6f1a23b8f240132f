#include "spirv/sources.h"

#include <string>

#include "util/hash.h"

namespace strata::spirv {

const std::string_view* findSource(std::string_view path) {
    for (std::size_t i = 0; i < kEmbeddedSourceCount; ++i)
        if (path == kEmbeddedSources[i].path) return &kEmbeddedSources[i].text;
    return nullptr;
}

std::uint64_t sourcesHash() {
    static const std::uint64_t hash = [] {
        Hash64 h;
        for (std::size_t i = 0; i < kEmbeddedSourceCount; ++i) {
            h.addString(kEmbeddedSources[i].path);
            h.addString(std::string(kEmbeddedSources[i].text));
        }
        return h.digest();
    }();
    return hash;
}

}  // namespace strata::spirv
