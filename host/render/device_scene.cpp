#include "render/device_scene.h"

#include "util/error.h"

namespace strata {

bool chooseTexelTraversal(const vk::Context& ctx, const GpuScene& scene, Traversal mode, bool wide) {
    const std::uint64_t nodeTexels = wide ? scene.wide.size() * 7 : scene.nodes.size() * 2;
    const std::uint64_t texels = std::max<std::uint64_t>(nodeTexels, scene.tris.size() * 3);
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

DeviceScene uploadScene(const vk::Context& ctx, const GpuScene& scene, Traversal mode, int bvhWidth) {
    const std::uint32_t regs = bvhRegsFor(scene.wideDepth);
    const bool wide = bvhWidth == 4 && regs > 0 && !scene.wide.empty();
    constexpr VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    constexpr VkBufferUsageFlags texel = storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    checkTexelLimit(ctx, scene);
    DeviceScene d;
    d.texel = chooseTexelTraversal(ctx, scene, mode, wide);
    d.wide = wide;
    d.bvhRegs = wide ? regs : 16u;
    d.nodes = wide ? vk::uploadVector(ctx, scene.wide, texel) : vk::uploadVector(ctx, scene.nodes, texel);
    d.tris = vk::uploadVector(ctx, scene.tris, texel);
    d.shading = vk::uploadVector(ctx, scene.shading, storage);
    d.materials = vk::uploadVector(ctx, scene.materials, storage);
    d.emitters = vk::uploadVector(ctx, scene.emitters, storage);
    d.nodesTexel = vk::TexelView(ctx, d.nodes);
    d.trisTexel = vk::TexelView(ctx, d.tris);
    d.texcoords = vk::uploadVector(ctx, scene.texcoords, storage);
    d.tangents = vk::uploadVector(ctx, scene.tangents, storage);
    d.textureRefs = vk::uploadVector(ctx, scene.textureRefs, storage);
    d.texels = vk::uploadVector(ctx, scene.texels, texel);
    d.texelsView = vk::TexelView(ctx, d.texels, VK_FORMAT_R32_UINT);
    uploadEnvironment(ctx, scene, d);
    return d;
}

void setTraversalSpec(const DeviceScene& scene, std::vector<std::uint32_t>& spec) {
    spec.resize(std::max<std::size_t>(spec.size(), gpu::SPEC_BVH_REGS + 1), 0u);
    spec[gpu::SPEC_TEXEL_FETCH] = scene.texel ? 1u : 0u;
    spec[gpu::SPEC_BVH_WIDE] = scene.wide ? 1u : 0u;
    spec[gpu::SPEC_BVH_REGS] = scene.bvhRegs;
}

void uploadEnvironment(const vk::Context& ctx, const GpuScene& scene, DeviceScene& d) {
    d.envTexels = vk::uploadVector(ctx, scene.envTexels, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    d.envTexelView = vk::TexelView(ctx, d.envTexels, VK_FORMAT_R32G32B32A32_SFLOAT);
    d.envTables = vk::uploadVector(ctx, scene.envTables, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}

void checkTexelLimit(const vk::Context& ctx, const GpuScene& scene) {
    const std::uint64_t limit = ctx.properties.limits.maxTexelBufferElements;
    if (scene.texels.size() > limit) {
        throw Error(scene.source + ": error: the textures need " + std::to_string(scene.texels.size()) +
                    " texel-buffer words, more than the device's maxTexelBufferElements " +
                    std::to_string(limit));
    }
}

std::vector<vk::BindingDesc> sceneBindings() {
    using namespace gpu;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    constexpr VkDescriptorType texel = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    return {{BINDING_NODES, storage},     {BINDING_TRIS, storage},      {BINDING_NODES_TEXEL, texel},
            {BINDING_TRIS_TEXEL, texel},  {BINDING_SHADING, storage},   {BINDING_MATERIALS, storage},
            {BINDING_TEXCOORDS, storage}, {BINDING_TANGENTS, storage},  {BINDING_TEXREFS, storage},
            {BINDING_TEXELS, texel}};
}

void bindTraversal(vk::Kernel& kernel, const DeviceScene& scene) {
    kernel.bind(gpu::BINDING_NODES, scene.nodes);
    kernel.bind(gpu::BINDING_TRIS, scene.tris);
    kernel.bind(gpu::BINDING_NODES_TEXEL, scene.nodesTexel);
    kernel.bind(gpu::BINDING_TRIS_TEXEL, scene.trisTexel);
    kernel.bind(gpu::BINDING_SHADING, scene.shading);
    kernel.bind(gpu::BINDING_MATERIALS, scene.materials);
    kernel.bind(gpu::BINDING_TEXCOORDS, scene.texcoords);
    kernel.bind(gpu::BINDING_TANGENTS, scene.tangents);
    kernel.bind(gpu::BINDING_TEXREFS, scene.textureRefs);
    kernel.bind(gpu::BINDING_TEXELS, scene.texelsView);
}

}  // namespace strata
