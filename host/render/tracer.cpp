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

std::unique_ptr<vk::Kernel> makeTraceKernel(const vk::Context& ctx, const DeviceScene& dev, std::uint32_t features,
                                            std::uint32_t mode, bool queue, bool reuse) {
    using namespace gpu;
    std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
    setTraversalSpec(dev, spec);
    spec[SPEC_FEATURES] = features;  // alpha-tested holes are skipped as in pathtrace
    spec[SPEC_TRACE_MODE] = mode;
    spec[SPEC_WORK_QUEUE] = queue ? 1u : 0u;
    std::vector<vk::BindingDesc> bindings = sceneBindings();
    bindings.insert(bindings.end(), {{BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                     {BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                     {BINDING_WORK, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}});
    auto k = std::make_unique<vk::Kernel>(ctx, traversalShader(dev, false), std::move(bindings), sizeof(TraceParams),
                                          spec, reuse);
    bindTraversal(*k, dev);
    return k;
}

VkDeviceSize traceWorkBytes(std::uint64_t rays) {
    const std::uint64_t dispatches = std::max<std::uint64_t>(1, (rays + kRaysPerTraceDispatch - 1) / kRaysPerTraceDispatch);
    return dispatches * gpu::kQueueWords * sizeof(std::uint32_t);
}

std::uint32_t recordTrace(VkCommandBuffer cmd, const vk::Context& ctx, vk::Kernel& kernel, const vk::Buffer& work,
                          std::uint64_t count, bool queue) {
    using namespace gpu;
    if (queue) {
        vkCmdFillBuffer(cmd, work.handle(), 0, VK_WHOLE_SIZE, 0u);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
    std::uint32_t dispatches = 0;
    for (std::uint64_t first = 0, slot = 0; first < count; first += kRaysPerTraceDispatch, ++slot) {
        TraceParams p{};
        p.count = static_cast<std::uint32_t>(std::min<std::uint64_t>(kRaysPerTraceDispatch, count - first));
        p.first = static_cast<std::uint32_t>(first);
        p.slot = static_cast<std::uint32_t>(slot);
        ++dispatches;
        if (!queue) {
            kernel.dispatch(cmd, &p, (p.count + 63) / 64);
            continue;
        }
        // First pass: a subgroup per kQueueRaysPerSubgroup rays. Second
        // pass: as many groups as its last subgroup left in the words.
        const std::uint64_t subgroups = (std::uint64_t{p.count} + kQueueRaysPerSubgroup - 1) / kQueueRaysPerSubgroup;
        const std::uint64_t perGroup = std::max<std::uint32_t>(1, 64 / ctx.info.subgroupSize);
        kernel.dispatch(cmd, &p, static_cast<std::uint32_t>((subgroups + perGroup - 1) / perGroup));
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                          VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                              VK_ACCESS_SHADER_WRITE_BIT);
        p.pass = 1;
        kernel.dispatchIndirect(cmd, &p, work, (slot * kQueueWords + 2) * sizeof(std::uint32_t));
    }
    return dispatches;
}

vk::Kernel& DeviceTracer::kernel(std::uint32_t mode) {
    using namespace gpu;
    if (mode != kTraceClosest && mode != kTraceAny && mode != kTraceSpawn)
        throw std::invalid_argument("trace: unknown mode " + std::to_string(mode));
    std::unique_ptr<vk::Kernel>& k = kernels_[mode];
    if (!k) k = makeTraceKernel(ctx_, scene_, features_, mode, workQueue_);
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
    // The work queue's words for each dispatch (types.h), zeroed at the start
    // of each pass; bound (the shader declares them) but unused without the queue.
    vk::Buffer workBuf(ctx_, traceWorkBytes(rays.size()),
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
        recordTrace(cmd, ctx_, kern, workBuf, rays.size(), workQueue_);
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
