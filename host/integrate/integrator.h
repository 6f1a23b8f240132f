// How one sample of a tile is taken. The progressive loop (render/renderer.h)
// owns the film's buffers, tiles the image, batches samples into
// submissions and folds the sums; an integrator only adds samples to the
// accumulation buffer. Two integrators, the same estimator and the same
// bits (lib/path.glsl shades a vertex for both): the megakernel
// (shaders/pathtrace.comp, one invocation per path) and the wavefront
// integrator (integrate/wavefront.h: stages around the trace kernel).
#pragma once
#include <cstdint>
#include <memory>

#include "../../shaders/shared/types.h"
#include "integrate/kernels.h"
#include "settings/settings.h"
#include "upload/device_scene.h"
#include "vk/context.h"

namespace strata {

struct RayCounts {
    std::uint64_t closest = 0;  // closest-hit rays (path segments)
    std::uint64_t shadow = 0;   // any-hit (shadow) rays
};

class Integrator {
public:
    virtual ~Integrator() = default;

    // Adds sample p.sampleIndex of the tile p describes to the accumulation
    // buffer: recorded into `cmd` (returns 0), or submitted and waited for
    // on its own (returns the device seconds of those submissions).
    virtual double addSample(VkCommandBuffer cmd, const gpu::DispatchParams& p) = 0;
    // The most samples one addSample may take (p.sampleCount), at least 1 (1: it reads p.sampleIndex alone).
    virtual std::uint32_t samplesPerDispatch() const { return 1; }

    // Rays traced since the last resetCounts; `device` is what the kernels
    // counted into the film's RenderCounters (SPEC_COUNT_RAYS). 0 without
    // tuning.countRays.
    virtual RayCounts rays(const gpu::RenderCounters& device) const = 0;
    virtual std::uint64_t dispatches() const = 0;
    virtual void resetCounts() = 0;  // after the warm-up, whose work is not the render's

    virtual double pipelineMs() const = 0;    // pipeline creation of its kernels (0 for reused ones)
    virtual bool reusedProgram() const = 0;   // its path-tracing program came from an earlier render
};

// The integrator the settings name, for tiles of up to maxTilePixels pixels.
std::unique_ptr<Integrator> makeIntegrator(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                           const RenderTuning& t, std::uint32_t maxTilePixels,
                                           const FilmBuffers& film);

}  // namespace strata
