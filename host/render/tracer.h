// Runs the trace-only kernel (shaders/trace.comp) over batches of rays: the
// shader's BVH traversal on its own, for tests and `strata bench`.
#pragma once
#include <memory>
#include <vector>

#include "render/device_scene.h"
#include "render/gpu_scene.h"
#include "vk/context.h"
#include "vk/kernel.h"

namespace strata {

// The trace kernel (shaders/trace.comp) for `dev` in `mode` (gpu::kTrace*),
// with the scene bound; the caller binds BINDING_RAYS, BINDING_HITS and
// BINDING_WORK. `queue`: SPEC_WORK_QUEUE (useWorkQueue).
std::unique_ptr<vk::Kernel> makeTraceKernel(const vk::Context& ctx, const DeviceScene& dev, std::uint32_t features,
                                            std::uint32_t mode, bool queue, bool reuse = false);

// Rays one trace dispatch takes at most (bounds one dispatch's work queue;
// even, for kTraceSpawn's pairs), and the work-queue words for `rays` rays.
inline constexpr std::uint32_t kRaysPerTraceDispatch = 1u << 18;
VkDeviceSize traceWorkBytes(std::uint64_t rays);

// Records `kernel` over rays [0, count) of its bound ray buffer, in
// dispatches of at most kRaysPerTraceDispatch rays; with `queue`, zeroes
// `work` first and records each dispatch's two passes (the second sized by
// the first's last subgroup). Returns the dispatches recorded.
std::uint32_t recordTrace(VkCommandBuffer cmd, const vk::Context& ctx, vk::Kernel& kernel, const vk::Buffer& work,
                          std::uint64_t count, bool queue);

// The scene uploaded once and one kernel per mode, built on its first use
// (the mode is a specialization constant); trace() may be called many times.
class DeviceTracer {
public:
    // bvhWidth, stack: as uploadScene (render/device_scene.h).
    // queue: SPEC_WORK_QUEUE (useWorkQueue).
    DeviceTracer(const vk::Context& ctx, const GpuScene& scene, Traversal traversal, int bvhWidth = 4,
                 BvhStack stack = BvhStack::Auto, WorkQueue queue = WorkQueue::Auto);
    ~DeviceTracer();

    // `mode` is gpu::kTraceClosest, kTraceAny or kTraceSpawn (types.h). Runs
    // the rays `reps` times; `medianSeconds` receives the median device time
    // of one pass (Vulkan timestamps around the dispatches).
    std::vector<gpu::TraceHit> trace(const std::vector<gpu::TraceRay>& rays, std::uint32_t mode, int reps = 1,
                                     double* medianSeconds = nullptr);
    bool texel() const { return scene_.texel(); }
    const DeviceScene& deviceScene() const { return scene_; }
    int bvhWidth() const { return scene_.wide ? 4 : 2; }
    std::uint32_t bvhRegs() const { return scene_.bvhRegs; }
    bool memoryStack() const { return scene_.memoryStack; }
    bool workQueue() const { return workQueue_; }

private:
    vk::Kernel& kernel(std::uint32_t mode);

    const vk::Context& ctx_;
    DeviceScene scene_;
    std::uint32_t features_ = 0;
    bool workQueue_ = false;  // SPEC_WORK_QUEUE (useWorkQueue)
    std::unique_ptr<vk::Kernel> kernels_[3];  // by mode
};

// One-shot convenience: upload, trace once, return the hits.
std::vector<gpu::TraceHit> traceOnDevice(const vk::Context& ctx, const GpuScene& scene,
                                         const std::vector<gpu::TraceRay>& rays,
                                         Traversal traversal, std::uint32_t mode, int bvhWidth = 4);

}  // namespace strata
