// The GLSL the kernels are compiled from at run time: every file under
// shaders/ (and the build's generated headers, named by their file name),
// embedded in the binary at build time (cmake/EmbedShaders.cmake).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace strata::spirv {

struct EmbeddedSource {
    const char* path;  // relative to shaders/: "lib/bsdf.glsl", "shared/types.h", "sheen_albedo.h"
    std::string_view text;
};
extern const EmbeddedSource kEmbeddedSources[];
extern const std::size_t kEmbeddedSourceCount;

// The text of `path` (relative to shaders/), or nullptr when there is none.
const std::string_view* findSource(std::string_view path);

// A hash of every embedded file's path and text: a part of every cache key.
std::uint64_t sourcesHash();

}  // namespace strata::spirv
