#include "render/tracer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "vk/timer.h"

namespace strata {

DeviceTracer::DeviceTracer(const vk::Context& ctx, const GpuScene& scene, Traversal traversal, int bvhWidth,
                           BvhStack stack, WorkQueue queue)
    : ctx_(ctx),
      scene_(uploadScene(ctx, scene, traversal, bvhWidth, stack)),
      features_(scene.features.bits),
      workQueue_(useWorkQueue(ctx, queue)) {}

vk::Kernel& DeviceTracer::kernel(std::uint32_t mode) {
    using namespace gpu;
    if (mode != kTraceClosest && mode != kTraceAny && mode != kTraceSpawn)
        throw std::invalid_argument("trace: unknown mode " + std::to_string(mode));
    std::unique_ptr<vk::Kernel>& k = kernels_[mode];
    if (!k) {
        std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
        setTraversalSpec(scene_, spec);
        spec[SPEC_FEATURES] = features_;  // alpha-tested holes are skipped as in pathtrace
        spec[SPEC_TRACE_MODE] = mode;
        spec[SPEC_WORK_QUEUE] = workQueue_ ? 1u : 0u;
        std::vector<vk::BindingDesc> bindings = sceneBindings();
        bindings.insert(bindings.end(), {{BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                         {BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                         {BINDING_WORK, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}});
        k = std::make_unique<vk::Kernel>(ctx_, traversalShader(scene_, false), std::move(bindings),
                                         sizeof(TraceParams), spec);
        bindTraversal(*k, scene_);
    }
    return *k;
}

DeviceTracer::~DeviceTracer() = default;

std::vector<gpu::TraceHit> DeviceTracer::trace(const std::vector<gpu::TraceRay>& rays, std::uint32_t mode,
                                               int reps, double* medianSeconds) {
    using namespace gpu;
    vk::Buffer rayBuf = vk::uploadVector(ctx_, rays, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const VkDeviceSize hitBytes = std::max<std::size_t>(16, rays.size() * sizeof(TraceHit));
    vk::Buffer hitBuf(ctx_, hitBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      vk::MemoryUse::Device);
    vk::Buffer back(ctx_, hitBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    constexpr std::size_t kRaysPerDispatch = 1u << 18;  // bounds one dispatch's work; even (spawn pairs)
    const std::size_t dispatches = std::max<std::size_t>(1, (rays.size() + kRaysPerDispatch - 1) / kRaysPerDispatch);
    // The work queue's words for each dispatch (types.h), zeroed at the start
    // of each pass; bound (the shader declares them) but unused without the queue.
    const VkDeviceSize workBytes = dispatches * kQueueWords * sizeof(std::uint32_t);
    vk::Buffer workBuf(ctx_, workBytes,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                       vk::MemoryUse::Device);
    vk::Kernel& kern = kernel(mode);
    kern.bind(BINDING_RAYS, rayBuf);
    kern.bind(BINDING_HITS, hitBuf);
    kern.bind(BINDING_WORK, workBuf);

    vk::OneShot submit(ctx_);
    vk::DeviceTimer timer(ctx_);
    std::vector<double> times;
    for (int r = 0; r < std::max(1, reps); ++r) {
        VkCommandBuffer cmd = submit.begin();
        timer.begin(cmd);
        if (workQueue_) {
            vkCmdFillBuffer(cmd, workBuf.handle(), 0, VK_WHOLE_SIZE, 0u);
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                              VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        }
        for (std::size_t first = 0, slot = 0; first < rays.size(); first += kRaysPerDispatch, ++slot) {
            TraceParams p{};
            p.count = static_cast<std::uint32_t>(std::min(kRaysPerDispatch, rays.size() - first));
            p.first = static_cast<std::uint32_t>(first);
            p.slot = static_cast<std::uint32_t>(slot);
            if (!workQueue_) {
                kern.dispatch(cmd, &p, (p.count + 63) / 64);
                continue;
            }
            // First pass: a subgroup per kQueueRaysPerSubgroup rays. Second
            // pass: as many groups as its last subgroup left in the words.
            const std::uint64_t subgroups = (std::uint64_t{p.count} + kQueueRaysPerSubgroup - 1) / kQueueRaysPerSubgroup;
            const std::uint64_t perGroup = std::max<std::uint32_t>(1, 64 / ctx_.info.subgroupSize);
            kern.dispatch(cmd, &p, static_cast<std::uint32_t>((subgroups + perGroup - 1) / perGroup));
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                              VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                              VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                                  VK_ACCESS_SHADER_WRITE_BIT);
            p.pass = 1;
            kern.dispatchIndirect(cmd, &p, workBuf, (slot * kQueueWords + 2) * sizeof(std::uint32_t));
        }
        timer.end(cmd);
        vk::recordReadback(cmd, hitBuf, back, hitBytes);
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
    return hits;
}

std::vector<gpu::TraceHit> traceOnDevice(const vk::Context& ctx, const GpuScene& scene,
                                         const std::vector<gpu::TraceRay>& rays, Traversal traversal,
                                         std::uint32_t mode, int bvhWidth) {
    DeviceTracer tracer(ctx, scene, traversal, bvhWidth);
    return tracer.trace(rays, mode);
}

}  // namespace strata
