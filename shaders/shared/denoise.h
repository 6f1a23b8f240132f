// The denoiser's push constants and bindings (host/denoise,
// shaders/denoise), shared by C++ and GLSL. Every image is width x height
// RGBA32F texels, row-major, row 0 at the top.
#ifndef STRATA_SHARED_DENOISE_H
#define STRATA_SHARED_DENOISE_H

#ifdef __cplusplus
#include <cstdint>
namespace strata::gpu {
using uint = std::uint32_t;
#define STRATA_DN_CONST(type, name, value) inline constexpr type name = value
#else
#define STRATA_DN_CONST(type, name, value) const type name = value
#endif

struct DenoiseParams {
    uint width;
    uint height;
    uint step;    // a-trous: the tap spacing in pixels
    uint radius;  // window radius in pixels
    float invK1;  // 1 / k^2 of the first NL-means bandwidth
    float invK2;  // 1 / k^2 of the second
    float sigma;  // a-trous: luminance edge-stop scale; prefilter: 1 / k^2
    float ridge;  // regression: ridge on the feature terms, relative to the weight sum
};

// Texel-view inputs (uniform samplerBuffer, RGBA32F) and storage outputs
// (vec4[] per pixel) of the denoise kernels.
STRATA_DN_CONST(uint, DN_IN0, 0u);
STRATA_DN_CONST(uint, DN_IN1, 1u);
STRATA_DN_CONST(uint, DN_IN2, 2u);
STRATA_DN_CONST(uint, DN_IN3, 3u);
STRATA_DN_CONST(uint, DN_IN4, 4u);
STRATA_DN_CONST(uint, DN_IN5, 5u);
STRATA_DN_CONST(uint, DN_OUT0, 8u);
STRATA_DN_CONST(uint, DN_OUT1, 9u);
STRATA_DN_CONST(uint, DN_OUT2, 10u);
STRATA_DN_CONST(uint, DN_OUT3, 11u);
STRATA_DN_CONST(uint, kDenoiseGroup, 8u);  // workgroups are 8 x 8 pixels

#ifdef __cplusplus
static_assert(sizeof(DenoiseParams) == 32);
}  // namespace strata::gpu
#endif
#undef STRATA_DN_CONST
#endif
