// The megakernel: shaders/pathtrace.comp, one pixel per invocation, its
// paths for up to tuning.samplesPerDispatch samples one after another, both
// traversals inlined; every dispatch is recorded into the loop's command
// buffer.
#include <algorithm>
#include <memory>

#include "../../shaders/shared/bindings.h"
#include "integrate/megakernel.h"
#include "vk/kernel.h"

namespace strata {
namespace {

// lavapipe ends every loop of an invocation, silently, once 65535 loop
// passes are spent in all (docs/experiments/lavapipe.md): a CPU device's
// invocation runs at most this many paths. With 63 a dispatch the heaviest
// lane of the materials board, the glass Cornell box and a 994k-triangle
// field, all at depth 64, spent up to 8,143 traversal passes: about 1,000
// at 8, and a subgroup's sum of them (the work queue's bound) about 8,000
// (docs/experiments/integrators.md, "Samples one after another").
constexpr std::uint32_t kCpuSamplesPerDispatch = 8;

class Megakernel final : public Integrator {
public:
    Megakernel(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s, const RenderTuning& t,
               const FilmBuffers& film)
        : samplesPerDispatch_(std::max(1u, ctx.info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU
                                               ? std::min(kCpuSamplesPerDispatch, t.samplesPerDispatch)
                                               : t.samplesPerDispatch)) {
        using namespace gpu;
        std::vector<std::uint32_t> spec = pathSpec(dev, s);
        spec[SPEC_COUNT_RAYS] = t.countRays ? 1u : 0u;
        spec[SPEC_WORK_QUEUE] = useWorkQueue(ctx, t.workQueue) ? 1u : 0u;
        kernel_ = std::make_unique<vk::Kernel>(ctx, traversalShader(dev, true, s.aov, s.cameraEffects()), pathBindings(),
                                               sizeof(DispatchParams), spec, t.reusePipeline);
        bindPathInputs(*kernel_, dev, film);
    }

    std::uint32_t samplesPerDispatch() const override { return samplesPerDispatch_; }
    double addSample(VkCommandBuffer cmd, const gpu::DispatchParams& p) override {
        kernel_->dispatch(cmd, &p, (p.tileW + 7) / 8, (p.tileH + 7) / 8);
        ++dispatches_;
        return 0.0;
    }
    RayCounts rays(const gpu::RenderCounters& c) const override {
        return {(static_cast<std::uint64_t>(c.closestHi) << 32) | c.closestLo,
                (static_cast<std::uint64_t>(c.shadowHi) << 32) | c.shadowLo};
    }
    std::uint64_t dispatches() const override { return dispatches_; }
    void resetCounts() override { dispatches_ = 0; }  // the device's counters are cleared by the loop
    double pipelineMs() const override { return kernel_->pipelineMs(); }
    bool reusedProgram() const override { return kernel_->reusedProgram(); }

private:
    std::unique_ptr<vk::Kernel> kernel_;
    std::uint64_t dispatches_ = 0;
    std::uint32_t samplesPerDispatch_;
};

}  // namespace

std::unique_ptr<Integrator> makeMegakernel(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                           const RenderTuning& t, const FilmBuffers& film) {
    return std::make_unique<Megakernel>(ctx, dev, s, t, film);
}

}  // namespace strata
