// Runs the trace-only kernel (shaders/trace.comp) over batches of rays: the
// shader's BVH traversal on its own, for tests and `strata bench`
// (integrate/kernels.h builds the kernel).
#pragma once
#include <memory>
#include <vector>

#include "settings/settings.h"
#include "upload/device_scene.h"
#include "pack/gpu_scene.h"
#include "vk/context.h"
#include "vk/kernel.h"

namespace strata {

// The scene uploaded once and one kernel per mode, built on its first use
// (the mode is a specialization constant); trace() may be called many times.
class DeviceTracer {
public:
    // `scene` uploaded (stages/stages.h: uploadPrepared); queue:
    // SPEC_WORK_QUEUE (useWorkQueue).
    DeviceTracer(const vk::Context& ctx, DeviceScene scene, WorkQueue queue = WorkQueue::Auto);
    // The same of a packed scene, uploaded with these reads and stack (the
    // tree traversed is the packing's: GpuScene::bvhWidth).
    DeviceTracer(const vk::Context& ctx, const GpuScene& scene, ReadMode reads, BvhStack stack = BvhStack::Auto,
                 WorkQueue queue = WorkQueue::Auto);
    ~DeviceTracer();

    // `mode` is gpu::kTraceClosest, kTraceAny or kTraceSpawn (types.h). Runs
    // the rays `reps` times; `medianSeconds` receives the median device time
    // of one pass (Vulkan timestamps around the dispatches). `instances`,
    // when given, receives each closest hit's instance (its record's first
    // texel in GpuScene::instances; gpu::kNoInstance for a scene without
    // instances, and undefined for a miss).
    std::vector<gpu::TraceHit> trace(const std::vector<gpu::TraceRay>& rays, std::uint32_t mode, int reps = 1,
                                     double* medianSeconds = nullptr, std::vector<std::uint32_t>* instances = nullptr);
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
    bool workQueue_ = false;  // SPEC_WORK_QUEUE (useWorkQueue)
    std::unique_ptr<vk::Kernel> kernels_[3];  // by mode
};

// One-shot convenience: upload, trace once, return the hits.
std::vector<gpu::TraceHit> traceOnDevice(const vk::Context& ctx, const GpuScene& scene,
                                         const std::vector<gpu::TraceRay>& rays, ReadMode reads, std::uint32_t mode);

}  // namespace strata
