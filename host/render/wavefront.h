// The wavefront integrator (RenderSettings::integrator = Integrator::Wavefront,
// `--integrator wavefront`): one sample of a tile as stages (shaders/wavefront.comp)
// around the trace kernel (shaders/trace.comp), which traverses each bounce's
// rays over a list of the live paths, with its work queue on CPU devices. The
// same estimator as pathtrace.comp; docs/design-notes.md has the measurements.
#pragma once
#include <cstdint>
#include <memory>

#include "render/device_scene.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/kernel.h"
#include "vk/timer.h"

namespace strata {

class WavefrontIntegrator {
public:
    // Lists for tiles of up to maxPaths pixels. `frame`, `filterTable`,
    // `accum` and `counters` are the renderer's buffers, bound as
    // pathtrace.comp binds them.
    WavefrontIntegrator(const vk::Context& ctx, const DeviceScene& dev, const GpuScene& scene,
                        const RenderSettings& s, std::uint32_t maxPaths, const vk::Buffer& frame,
                        const vk::Buffer& filterTable, const vk::Buffer& accum, const vk::Buffer& counters);
    ~WavefrontIntegrator();

    // Sample `sampleIndex` of the tile (x, y, w, h), added to the accumulation
    // buffer. Submits and waits for each stage (the host reads two counts a
    // bounce); returns the device time of its dispatches.
    double sample(std::uint32_t x, std::uint32_t y, std::uint32_t w, std::uint32_t h, std::uint32_t sampleIndex);

    std::uint64_t closestRays() const { return closestRays_; }
    std::uint64_t shadowRays() const { return shadowRays_; }
    std::uint64_t dispatches() const { return dispatches_; }
    void resetCounts() { closestRays_ = shadowRays_ = dispatches_ = 0; }
    double pipelineMs() const;  // pipeline creation of its kernels (0 for those reused)
    bool reusedProgram() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::uint64_t closestRays_ = 0, shadowRays_ = 0, dispatches_ = 0;
};

}  // namespace strata
