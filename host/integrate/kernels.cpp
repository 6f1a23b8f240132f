#include "integrate/kernels.h"

#include <algorithm>

#include "spirv/cache.h"
#include "../../shaders/shared/bindings.h"

namespace strata {

namespace {

// The module's inputs from the uploaded scene and the render's settings
// (the AOV sums, the camera effects): spirv/features.h's table picks the
// axes from them.
spirv::VariantInputs variantInputs(const DeviceScene& scene, bool aov, bool cameraEffects) {
    return {scene.features.bits, scene.wide, scene.memoryStack, aov, cameraEffects};
}

}  // namespace

std::span<const std::uint32_t> traversalShader(const DeviceScene& scene, bool pathtrace, bool aov, bool motion) {
    const spirv::KernelId kernel = pathtrace ? spirv::KernelId::Pathtrace : spirv::KernelId::Trace;
    return spirv::moduleFor(spirv::chooseVariant(kernel, variantInputs(scene, aov, motion)));
}

std::span<const std::uint32_t> wavefrontShader(const DeviceScene& scene) {
    return spirv::moduleFor(spirv::chooseVariant(spirv::KernelId::Wavefront, variantInputs(scene, false, false)));
}

void setTraversalSpec(const DeviceScene& scene, std::vector<std::uint32_t>& spec) {
    spec.resize(std::max<std::size_t>(spec.size(), gpu::SPEC_BVH_REGS + 1), 0u);
    spec[gpu::SPEC_TEXEL_FETCH] = scene.reads;
    spec[gpu::SPEC_BVH_REGS] = scene.bvhRegs;
}

void bindArray(vk::Kernel& kernel, std::uint32_t storageBinding, std::uint32_t texelBinding, const DeviceArray& a) {
    kernel.bind(storageBinding, a.buffer, a.storageRange);
    kernel.bind(texelBinding, a.texel);
}

std::vector<vk::BindingDesc> sceneBindings() {
    using namespace gpu;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    constexpr VkDescriptorType texel = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    return {{BINDING_NODES, storage},     {BINDING_NODES_TEXEL, texel},     {BINDING_TRIS, storage},
            {BINDING_TRIS_TEXEL, texel},  {BINDING_SHADING, storage},       {BINDING_SHADING_TEXEL, texel},
            {BINDING_TEXCOORDS, storage}, {BINDING_TEXCOORDS_TEXEL, texel}, {BINDING_TANGENTS, storage},
            {BINDING_TANGENTS_TEXEL, texel}, {BINDING_MATERIALS, storage},  {BINDING_MATERIALS_TEXEL, texel},
            {BINDING_TEXREFS, storage},   {BINDING_TEXREFS_TEXEL, texel},   {BINDING_TEXELS, texel},
            {BINDING_COLORS, storage},    {BINDING_COLORS_TEXEL, texel},    {BINDING_INSTANCES, storage},
            {BINDING_INSTANCES_TEXEL, texel}};
}

void bindTraversal(vk::Kernel& kernel, const DeviceScene& scene) {
    using namespace gpu;
    bindArray(kernel, BINDING_NODES, BINDING_NODES_TEXEL, scene.nodes);
    bindArray(kernel, BINDING_TRIS, BINDING_TRIS_TEXEL, scene.tris);
    bindArray(kernel, BINDING_SHADING, BINDING_SHADING_TEXEL, scene.shading);
    bindArray(kernel, BINDING_TEXCOORDS, BINDING_TEXCOORDS_TEXEL, scene.texcoords);
    bindArray(kernel, BINDING_TANGENTS, BINDING_TANGENTS_TEXEL, scene.tangents);
    bindArray(kernel, BINDING_COLORS, BINDING_COLORS_TEXEL, scene.colors);
    bindArray(kernel, BINDING_INSTANCES, BINDING_INSTANCES_TEXEL, scene.instances);
    bindArray(kernel, BINDING_MATERIALS, BINDING_MATERIALS_TEXEL, scene.materials);
    bindArray(kernel, BINDING_TEXREFS, BINDING_TEXREFS_TEXEL, scene.textureRefs);
    kernel.bind(BINDING_TEXELS, scene.texelsView);
}

std::vector<vk::BindingDesc> pathBindings() {
    using namespace gpu;
    std::vector<vk::BindingDesc> bindings = sceneBindings();
    bindings.insert(bindings.end(), {
        {BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {BINDING_EMITTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_EMITTERS_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
        {BINDING_LIGHT_TREE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_LIGHT_TREE_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
        {BINDING_ACCUM, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_COUNTERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_ACTIVE_BLOCKS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_FILTER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_ENV_TEXELS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
        {BINDING_ENV_CDF, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {BINDING_ENV_CDF_TEXEL, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER},
    });
    return bindings;
}

void bindPathInputs(vk::Kernel& kernel, const DeviceScene& dev, const FilmBuffers& film) {
    using namespace gpu;
    bindTraversal(kernel, dev);
    kernel.bind(BINDING_FRAME, film.frame);
    bindArray(kernel, BINDING_EMITTERS, BINDING_EMITTERS_TEXEL, dev.emitters);
    bindArray(kernel, BINDING_LIGHT_TREE, BINDING_LIGHT_TREE_TEXEL, dev.lightTree);
    kernel.bind(BINDING_ACCUM, film.accum);
    kernel.bind(BINDING_COUNTERS, film.counters);
    kernel.bind(BINDING_ACTIVE_BLOCKS, film.activeBlocks);
    kernel.bind(BINDING_FILTER, film.filterTable);
    kernel.bind(BINDING_ENV_TEXELS, dev.envTexelView);
    bindArray(kernel, BINDING_ENV_CDF, BINDING_ENV_CDF_TEXEL, dev.envTables);
}

std::vector<std::uint32_t> pathSpec(const DeviceScene& dev, const RenderSettings& s) {
    using namespace gpu;
    std::vector<std::uint32_t> spec(SPEC_LIGHT_CANDIDATES + 1, 0u);
    setTraversalSpec(dev, spec);
    spec[SPEC_HAS_EMITTERS] = dev.features.emitters ? 1u : 0u;
    spec[SPEC_ADAPTIVE] = s.adaptive() ? 1u : 0u;
    spec[SPEC_SAMPLER] = s.sampler;
    spec[SPEC_FEATURES] = dev.features.bits;
    spec[SPEC_MIS] = s.mis;
    spec[SPEC_LIGHT_CANDIDATES] = (dev.features.bits & kFeatureLightTree) != 0u ? s.lightCandidateCount() : 1u;
    return spec;
}

bool useWorkQueue(const vk::Context& ctx, WorkQueue mode) {
    if (ctx.info.subgroupSize > 64) return false;  // trace.comp's chunks are whole 64-lane groups
    if (mode != WorkQueue::Auto) return mode == WorkQueue::On;
    return ctx.info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

std::unique_ptr<vk::Kernel> makeTraceKernel(const vk::Context& ctx, const DeviceScene& dev, std::uint32_t mode,
                                            bool queue, bool reuse) {
    using namespace gpu;
    std::vector<std::uint32_t> spec(SPEC_WORK_QUEUE + 1, 0u);
    setTraversalSpec(dev, spec);
    spec[SPEC_FEATURES] = dev.features.bits;  // alpha-tested holes are skipped as in pathtrace
    spec[SPEC_TRACE_MODE] = mode;
    spec[SPEC_WORK_QUEUE] = queue ? 1u : 0u;
    std::vector<vk::BindingDesc> bindings = sceneBindings();
    bindings.insert(bindings.end(), {{BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                     {BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                     {BINDING_HIT_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
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

}  // namespace strata
