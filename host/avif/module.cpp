#include "avif/module.h"

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string_view>
#include <vector>

#include <dlfcn.h>

namespace strata::avif {

namespace {

struct Loaded {
    const Api* api = nullptr;
    std::string error;
};

Loaded load() {
    Loaded out;
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("STRATA_AVIF_MODULE")) {
        candidates.push_back(env);
    } else if (std::string_view(STRATA_AVIF_MODULE).empty()) {
        out.error = "strata was built without the AVIF decoder (libavif)";
        return out;
    } else {
        candidates.push_back(STRATA_AVIF_MODULE);
        std::error_code ec;
        const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) candidates.push_back((exe.parent_path() / "libstrata_avif.so").string());
    }
    for (const std::string& path : candidates) {
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            if (out.error.empty()) out.error = why ? why : path + ": cannot be loaded";
            continue;
        }
        auto entry = reinterpret_cast<const Api* (*)()>(dlsym(handle, "strata_avif_api"));
        const Api* api = entry ? entry() : nullptr;
        if (api && api->version == kApiVersion) {
            out.api = api;  // stays loaded
            return out;
        }
        dlclose(handle);
        out.error = path + ": not this build's AVIF module";
    }
    return out;
}

}  // namespace

const Api* module(std::string& error) {
    static std::once_flag once;
    static Loaded loaded;
    std::call_once(once, [] { loaded = load(); });
    if (!loaded.api) error = loaded.error;
    return loaded.api;
}

}  // namespace strata::avif
