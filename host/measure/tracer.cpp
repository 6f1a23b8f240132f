#include "measure/tracer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "../../shaders/shared/bindings.h"
#include "integrate/kernels.h"
#include "vk/timer.h"

namespace strata {

DeviceTracer::DeviceTracer(const vk::Context& ctx, DeviceScene scene, WorkQueue queue)
    : ctx_(ctx), scene_(std::move(scene)), workQueue_(useWorkQueue(ctx, queue)) {}

DeviceTracer::DeviceTracer(const vk::Context& ctx, const GpuScene& scene, ReadMode reads, BvhStack stack,
                           WorkQueue queue)
    : DeviceTracer(ctx, uploadScene(ctx, scene, {reads, stack}), queue) {}

vk::Kernel& DeviceTracer::kernel(std::uint32_t mode) {
    using namespace gpu;
    if (mode != kTraceClosest && mode != kTraceAny && mode != kTraceSpawn)
        throw std::invalid_argument("trace: unknown mode " + std::to_string(mode));
    std::unique_ptr<vk::Kernel>& k = kernels_[mode];
    if (!k) k = makeTraceKernel(ctx_, scene_, mode, workQueue_);
    return *k;
}

DeviceTracer::~DeviceTracer() = default;

std::vector<gpu::TraceHit> DeviceTracer::trace(const std::vector<gpu::TraceRay>& rays, std::uint32_t mode,
                                               int reps, double* medianSeconds, std::vector<std::uint32_t>* instances) {
    using namespace gpu;
    vk::Buffer rayBuf = vk::uploadVector(ctx_, rays, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const VkDeviceSize hitBytes = std::max<std::size_t>(16, rays.size() * sizeof(TraceHit));
    vk::Buffer hitBuf(ctx_, hitBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      vk::MemoryUse::Device);
    vk::Buffer back(ctx_, hitBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    // The work queue's words for each dispatch (types.h), zeroed at the start
    // of each pass; bound (the shader declares them) but unused without the queue.
    vk::Buffer workBuf(ctx_, traceWorkBytes(rays.size()),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                       vk::MemoryUse::Device);
    vk::Kernel& kern = kernel(mode);
    kern.bind(BINDING_RAYS, rayBuf);
    kern.bind(BINDING_HITS, hitBuf);
    // Each closest hit's instance (written by the instanced shaders only).
    const VkDeviceSize instanceBytes = std::max<std::size_t>(16, rays.size() * sizeof(std::uint32_t));
    vk::Buffer instanceBuf(ctx_, instanceBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                           vk::MemoryUse::Device);
    vk::Buffer instanceBack(ctx_, instanceBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    kern.bind(BINDING_HIT_INSTANCES, instanceBuf);
    const bool instanced = (scene_.features.bits & kFeatureInstancing) != 0u;
    kern.bind(BINDING_WORK, workBuf);

    vk::OneShot submit(ctx_);
    vk::DeviceTimer timer(ctx_);
    std::vector<double> times;
    for (int r = 0; r < std::max(1, reps); ++r) {
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        recordTrace(cmd, ctx_, kern, workBuf, rays.size(), workQueue_);
        timer.end(cmd);
        vk::recordReadback(cmd, hitBuf, back, hitBytes);
        if (instances && instanced) vk::recordReadback(cmd, instanceBuf, instanceBack, instanceBytes);
        submit.submitAndWait();
        times.push_back(timer.seconds());
    }
    if (medianSeconds) {
        std::sort(times.begin(), times.end());
        *medianSeconds = times[times.size() / 2];
    }
    back.invalidate();
    std::vector<TraceHit> hits(rays.size());
    std::memcpy(hits.data(), back.mapped(), rays.size() * sizeof(TraceHit));
    if (instances) {
        instances->assign(rays.size(), kNoInstance);
        if (instanced) {
            instanceBack.invalidate();
            std::memcpy(instances->data(), instanceBack.mapped(), rays.size() * sizeof(std::uint32_t));
        }
    }
    return hits;
}

std::vector<gpu::TraceHit> traceOnDevice(const vk::Context& ctx, const GpuScene& scene,
                                         const std::vector<gpu::TraceRay>& rays, ReadMode reads,
                                         std::uint32_t mode) {
    DeviceTracer tracer(ctx, scene, reads);
    return tracer.trace(rays, mode);
}

}  // namespace strata
