// GLSL to SPIR-V at run time, through glslang's library, with the options
// glslangValidator's `--target-env vulkan1.1` uses (Vulkan 1.1, SPIR-V 1.3,
// no optimizer, no debug information): the words are the ones the build
// used to embed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace strata::spirv {

// Compiles the embedded compute shader `source` (a path under shaders/)
// with `#define NAME` for each of `defines`. A source that does not compile
// is strata's own bug: std::logic_error with glslang's log.
std::vector<std::uint32_t> compileGlsl(const std::string& source, const std::vector<std::string>& defines);

// "glslang 12.0.0": the compiler's version, a part of every cache key.
std::string compilerVersion();

}  // namespace strata::spirv
