#include "render/tracer.h"

#include <cstring>

#include <strata_spirv.h>

#include "vk/kernel.h"

namespace strata {

std::vector<gpu::TraceHit> traceOnDevice(const vk::Context& ctx, const GpuScene& scene,
                                         const std::vector<gpu::TraceRay>& rays,
                                         Traversal traversal, std::uint32_t mode) {
    using namespace gpu;
    DeviceScene dev = uploadScene(ctx, scene, traversal);
    vk::Buffer rayBuf = vk::uploadVector(ctx, rays, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const VkDeviceSize hitBytes = std::max<std::size_t>(16, rays.size() * sizeof(TraceHit));
    vk::Buffer hitBuf(ctx, hitBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      vk::MemoryUse::Device);
    vk::Buffer back(ctx, hitBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);

    std::vector<std::uint32_t> spec(1);
    spec[SPEC_TEXEL_FETCH] = dev.texel ? 1u : 0u;
    vk::Kernel kernel(ctx, {kSpirvPtr_trace, kSpirvSize_trace / 4},
                      {{BINDING_NODES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_TRIS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_NODES_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                       {BINDING_TRIS_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
                       {BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                       {BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                      sizeof(TraceParams), spec);
    bindTraversal(kernel, dev);
    kernel.bind(BINDING_RAYS, rayBuf);
    kernel.bind(BINDING_HITS, hitBuf);

    vk::OneShot submit(ctx);
    VkCommandBuffer cmd = submit.begin();
    constexpr std::size_t kRaysPerDispatch = 1u << 18;  // bounds one dispatch's work; even (spawn pairs)
    for (std::size_t first = 0; first < rays.size(); first += kRaysPerDispatch) {
        TraceParams p{};
        p.count = static_cast<std::uint32_t>(std::min(kRaysPerDispatch, rays.size() - first));
        p.mode = mode;
        p.first = static_cast<std::uint32_t>(first);
        kernel.dispatch(cmd, &p, (p.count + 63) / 64);
    }
    vk::recordReadback(cmd, hitBuf, back, hitBytes);
    submit.submitAndWait();
    back.invalidate();
    std::vector<TraceHit> hits(rays.size());
    std::memcpy(hits.data(), back.mapped(), rays.size() * sizeof(TraceHit));
    return hits;
}

}  // namespace strata
