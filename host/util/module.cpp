#include "util/module.h"

#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <vector>

#include <dlfcn.h>

namespace strata {

const void* loadModuleApi(const ModuleSpec& spec, std::string& error) {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv(spec.env)) {
        candidates.push_back(env);
    } else if (std::string_view(spec.built).empty()) {
        error = spec.missing;
        return nullptr;
    } else {
        candidates.push_back(spec.built);
        std::error_code ec;
        const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) candidates.push_back((exe.parent_path() / spec.fileName).string());
    }
    for (const std::string& path : candidates) {
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            if (error.empty()) error = why ? why : path + ": cannot be loaded";
            continue;
        }
        auto entry = reinterpret_cast<const void* (*)()>(dlsym(handle, spec.symbol));
        const void* api = entry ? entry() : nullptr;
        if (api && *static_cast<const int*>(api) == spec.version) return api;  // stays loaded
        dlclose(handle);
        error = path + ": not this build's " + spec.what;
    }
    return nullptr;
}

}  // namespace strata
