// The image-space denoiser: NFOR-class first-order regression (Bitterli et
// al. 2016) or an SVGF-style a-trous filter (Schied et al. 2017), run as
// compute kernels (shaders/denoise) on the colour and feature layers of a
// render.
#pragma once
#include <vector>

#include "vk/context.h"

namespace strata {

// All images row-major, row 0 at the top, interleaved channels, width*height pixels.
struct DenoiseInput {
    int width = 0, height = 0;
    std::vector<float> color;     // 3/pixel: the noisy mean radiance (all samples)
    std::vector<float> halfA;     // 3/pixel: mean of the even-indexed samples
    std::vector<float> halfB;     // 3/pixel: mean of the odd-indexed samples
    std::vector<float> variance;  // 3/pixel: variance of the pixel's mean (sample variance / n)
    std::vector<float> albedo;    // 3/pixel: in [0,1], first non-delta vertex's albedo
    std::vector<float> normal;    // 3/pixel: shading normal, camera space (0,0,0 where the camera ray escaped)
    std::vector<float> depth;     // 1/pixel: distance to the first hit; 0 where the camera ray escaped
    // 1/pixel: fraction of the pixel's samples that saw an emitter or the
    // background directly: out = e * color + (1 - e) * denoised.
    std::vector<float> emitter;
    // Optional (may be empty): variance of the mean of each feature, for the feature prefilter.
    std::vector<float> albedoVariance;  // 3/pixel
    std::vector<float> normalVariance;  // 3/pixel
    std::vector<float> depthVariance;   // 1/pixel
};

enum class DenoiseMethod { Nfor, Fast };

struct DenoiseResult {
    std::vector<float> rgb;      // 3/pixel
    double seconds = 0.0;        // host wall time of denoise() including upload and readback, excluding pipeline creation
    double deviceSeconds = 0.0;  // device timestamps of the dispatches (== seconds where unsupported)
    double pipelineMs = 0.0;
};

// Throws strata::Error("strata: error: ...") on inconsistent sizes (a vector
// of the wrong length names the layer).
DenoiseResult denoise(const vk::Context& ctx, const DenoiseInput& in, DenoiseMethod method);

}  // namespace strata
