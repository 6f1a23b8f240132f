// Draws the samples of one pixel, or of a block of pixels, from the
// GLSL samplers (sample_test.comp, routine kSamplePixel): for sample i, the
// pixel pair (x, y in [0,1)^2 within the pixel) and the first path vertex's
// light-choice pair (z, w).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "../../shaders/shared/sample_test.h"
#include "../../shaders/shared/types.h"
#include "settings/filter.h"
#include "pack/gpu_scene.h"
#include "vk/context.h"

namespace strata {

struct PixelSampleRequest {
    std::uint32_t sampler = 0;  // gpu::kSampler*
    std::uint32_t spp = 64;     // samples of the pixel (all drawn)
    std::uint32_t seed = 0;
    std::uint32_t pixelX = 0, pixelY = 0;
    std::uint32_t width = 1, height = 1;  // the image the pixel belongs to
    // Pixels [pixelX, pixelX + blockWidth) x [pixelY, pixelY + blockHeight),
    // all drawn by one dispatch: spp samples of each, pixel by pixel, row by
    // row (at most kMaxPixelSamples in all).
    std::uint32_t blockWidth = 1, blockHeight = 1;
};

// The most samples one drawPixelSamples call draws (32 MiB of output).
inline constexpr std::uint64_t kMaxPixelSamples = std::uint64_t(1) << 21;

// Throws strata::Error when spp does not suit the sampler (sampler_kind.h),
// and std::invalid_argument when the block is empty, leaves the image or
// holds more than kMaxPixelSamples samples.
std::vector<glm::vec4> drawPixelSamples(const vk::Context& ctx, const PixelSampleRequest& request);

// Runs sample_test.comp once: params.count samples of routine params.routine
// (types.h, kSample*), with the sampler compiled in as `sampler`, the given
// emitters (kSampleEmitterChoice) and pixel filter (kSampleFilter). With
// `lights` (kSampleLight, kSampleEnvironmentPdf), its emitters, environment
// and feature bits are used instead of `emitters`, as the path tracer sees them.
// `features` (kFeature*) are added to SPEC_FEATURES: the BSDF's layers are
// compiled in only under their bits.
std::vector<glm::vec4> runSampleKernel(const vk::Context& ctx, const gpu::SampleTestParams& params,
                                       std::uint32_t sampler, const std::vector<gpu::Emitter>& emitters = {},
                                       const PixelFilter& filter = {}, const GpuScene* lights = nullptr,
                                       std::uint32_t features = 0);

}  // namespace strata
