// The SPIR-V of a module (spirv/features.h), compiled once per process and
// kept in a persistent cache between processes.
//
// The cache is a folder of files NAME-KEY.spv, KEY a hash of the embedded
// sources, the module's source and defines, and the compiler's version: a
// new build of strata, or an edit to any shader file, uses new entries.
// Entries are written under a unique temporary name and renamed, so
// concurrent processes (a farm's jobs on one shared folder) may fill it at
// once. An entry that is corrupt, or holds another key, is compiled again
// and replaced, with one warning line. The folder: --shader-cache DIR (or
// `off`: compile in memory only), else $XDG_CACHE_HOME/strata/shaders, else
// $HOME/.cache/strata/shaders. A folder that cannot be written is one
// warning line; the modules are then compiled in memory.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "spirv/features.h"

namespace strata::spirv {

// What this process did to get its modules (--stats).
struct ShaderCacheStats {
    std::uint32_t compiled = 0;    // compiled by glslang (not in the cache, or the cache off)
    std::uint32_t loaded = 0;      // read from the cache folder
    std::uint32_t rejected = 0;    // cache entries found corrupt or foreign (compiled again)
    double compileMs = 0.0;        // host milliseconds in glslang
    double loadMs = 0.0;           // host milliseconds reading entries
};
// --shader-cache: a folder, or "off". Call before the first module (main's
// parse); later calls apply to the modules not yet made.
void setShaderCache(const std::string& dirOrOff);
// The folder in use, or "" when the cache is off.
std::string shaderCacheDir();

// The module's words, valid for the process's lifetime: from this
// process's memory, else from the cache, else compiled (and stored).
std::span<const std::uint32_t> moduleFor(const Variant& v);

// The module from the cache folder `dir` ("": none), else compiled and
// stored there, counted in `stats`. A folder that cannot be written sets
// *unwritable (without it: one warning line).
std::vector<std::uint32_t> cachedModule(const Variant& v, const std::string& dir, ShaderCacheStats& stats,
                                        bool* unwritable = nullptr);

// The cache key of a module (hex): its entry is NAME-KEY.spv.
std::string moduleKey(const Variant& v);

ShaderCacheStats shaderCacheStats();

}  // namespace strata::spirv
