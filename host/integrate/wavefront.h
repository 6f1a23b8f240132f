// The wavefront integrator (RenderSettings::integrator = IntegratorKind::Wavefront,
// `--integrator wavefront`): one sample of a tile as stages (shaders/wavefront.comp)
// around the trace kernel (shaders/trace.comp), which traverses each bounce's
// rays over a list of the live paths, with its work queue on CPU devices. The
// same estimator as pathtrace.comp, and the same bits.
#pragma once
#include <cstdint>
#include <memory>

#include "integrate/integrator.h"
#include "upload/device_scene.h"
#include "vk/context.h"

namespace strata {

class WavefrontIntegrator final : public Integrator {
public:
    // Lists for tiles of up to maxPaths pixels.
    WavefrontIntegrator(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                        const RenderTuning& t, std::uint32_t maxPaths, const FilmBuffers& film);
    ~WavefrontIntegrator() override;

    // Submits and waits for each stage (the host reads two counts a bounce);
    // `cmd` is not used. Returns the device time of its dispatches.
    double addSample(VkCommandBuffer cmd, const gpu::DispatchParams& p) override;

    // Counted on the host, from the lists' lengths.
    RayCounts rays(const gpu::RenderCounters& device) const override;
    std::uint64_t dispatches() const override { return dispatches_; }
    void resetCounts() override { closestRays_ = shadowRays_ = dispatches_ = 0; }
    double pipelineMs() const override;
    bool reusedProgram() const override;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    bool countRays_ = true;
    bool adaptive_ = false;  // SPEC_ADAPTIVE: the camera stage appends the active blocks' paths alone
    std::uint64_t closestRays_ = 0, shadowRays_ = 0, dispatches_ = 0;
};

}  // namespace strata
