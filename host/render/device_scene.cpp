#include "render/device_scene.h"

#include "util/error.h"

namespace strata {

bool chooseTexelTraversal(const vk::Context& ctx, const GpuScene& scene, Traversal mode) {
    const std::uint64_t texels = std::max<std::uint64_t>(scene.nodes.size() * 2, scene.tris.size() * 3);
    const bool fits = texels <= ctx.properties.limits.maxTexelBufferElements;
    switch (mode) {
        case Traversal::Texel:
            if (!fits)
                throw Error("strata: error: --traversal texel: the scene needs " + std::to_string(texels) +
                            " texels per view, the device allows " +
                            std::to_string(ctx.properties.limits.maxTexelBufferElements));
            return true;
        case Traversal::Storage: return false;
        case Traversal::Auto: break;
    }
    return fits && ctx.info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

DeviceScene uploadScene(const vk::Context& ctx, const GpuScene& scene, Traversal mode) {
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    constexpr VkBufferUsageFlags texel = storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    DeviceScene d;
    d.texel = chooseTexelTraversal(ctx, scene, mode);
    d.nodes = vk::uploadVector(ctx, scene.nodes, texel);
    d.tris = vk::uploadVector(ctx, scene.tris, texel);
    d.shading = vk::uploadVector(ctx, scene.shading, storage);
    d.materials = vk::uploadVector(ctx, scene.materials, storage);
    d.emitters = vk::uploadVector(ctx, scene.emitters, storage);
    d.nodesTexel = vk::TexelView(ctx, d.nodes);
    d.trisTexel = vk::TexelView(ctx, d.tris);
    uploadEnvironment(ctx, scene, d);
    return d;
}

void uploadEnvironment(const vk::Context& ctx, const GpuScene& scene, DeviceScene& d) {
    d.envTexels = vk::uploadVector(ctx, scene.envTexels, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    d.envTexelView = vk::TexelView(ctx, d.envTexels, VK_FORMAT_R32G32B32A32_SFLOAT);
    d.envTables = vk::uploadVector(ctx, scene.envTables, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

void bindTraversal(vk::Kernel& kernel, const DeviceScene& scene) {
    kernel.bind(gpu::BINDING_NODES, scene.nodes);
    kernel.bind(gpu::BINDING_TRIS, scene.tris);
    kernel.bind(gpu::BINDING_NODES_TEXEL, scene.nodesTexel);
    kernel.bind(gpu::BINDING_TRIS_TEXEL, scene.trisTexel);
}

}  // namespace strata
