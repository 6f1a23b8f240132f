#include "upload/device_scene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <type_traits>

#include "util/error.h"
#include "util/memory.h"

namespace strata {
namespace {

constexpr VkDeviceSize kTexel = 16;  // bytes of one RGBA32UI texel

// One array of the scene as the shaders read it: through a storage
// descriptor, a texel view of `texelBytes` per texel (0: none), or either
// (the BVH's two, `bvh`, and the other per-triangle arrays).
struct ArrayUse {
    const char* what;
    std::uint64_t bytes;
    bool storage;
    std::uint64_t texelBytes;
    bool bvh = false;
};

std::vector<ArrayUse> arrayUses(const GpuScene& s, bool wide) {
    const std::uint64_t nodes = wide ? s.wide.size() * sizeof(gpu::BvhNode4) : s.nodes.size() * sizeof(gpu::BvhNode);
    return {{"BVH nodes", nodes, true, kTexel, true},
            {"triangle vertices", s.tris.size() * sizeof(gpu::TriVerts), true, kTexel, true},
            {"instances", s.instances.size() * sizeof(glm::uvec4), true, kTexel, true},
            {"triangle shading data", s.shading.size() * sizeof(gpu::TriShading), true, kTexel},
            {"texture coordinates", s.texcoords.size() * sizeof(gpu::TriTexcoords), true, kTexel},
            {"tangents", s.tangents.size() * sizeof(gpu::TriTangents), true, kTexel},
            {"vertex colours", s.colors.size() * sizeof(gpu::TriColors), true, kTexel},
            {"emitters", s.emitters.size() * sizeof(gpu::Emitter), true, kTexel},
            {"light tree", s.lightTree.size() * sizeof(gpu::LightNode), true, kTexel},
            {"materials", s.materials.size() * sizeof(gpu::Material), true, kTexel},
            {"texture references", s.textureRefs.size() * sizeof(gpu::TextureRef), true, kTexel},
            {"environment sampling tables", s.envTables.size() * sizeof(float), true, kTexel},
            {"texture texels", s.texels.size() * sizeof(std::uint32_t), false, sizeof(std::uint32_t)},
            {"environment map texels", s.envTexels.size() * sizeof(glm::vec4), false, sizeof(glm::vec4)}};
}

bool fitsStorage(const ArrayUse& a, const SceneLimits& l) { return a.storage && a.bytes <= l.storageRange; }
bool fitsTexel(const ArrayUse& a, const SceneLimits& l) {
    return a.texelBytes > 0 && (a.bytes + a.texelBytes - 1) / a.texelBytes <= l.texelElements;
}

std::string need(const ArrayUse& a) { return std::string("the ") + a.what + " need " + sizeText(a.bytes); }
std::string storageLimit(const SceneLimits& l) { return "maxStorageBufferRange (" + sizeText(l.storageRange) + ")"; }
std::string texelLimit(const SceneLimits& l, const ArrayUse& a) {
    return "maxTexelBufferElements (" + std::to_string(l.texelElements) + " texels of " +
           std::to_string(a.texelBytes) + " bytes)";
}

VkDeviceSize paddedSize(std::size_t bytes) { return std::max<VkDeviceSize>(16, (bytes + 15) & ~VkDeviceSize(15)); }

// The device's memory (vk::deviceMemory), or the lowered limit.
using MemoryLimit = vk::DeviceMemory;
MemoryLimit deviceMemory(const vk::Context& ctx, std::uint64_t override) {
    MemoryLimit m = vk::deviceMemory(ctx.memory, ctx.info.vkType);
    if (override > 0 && (m.bytes == 0 || override < m.bytes)) m = {override, "the limit set"};
    return m;
}

// Every buffer of the render before the first is made: the scene's arrays
// (the traversed tree's) and the image's sample sums, against the device's
// memory (twice the sums on a CPU device, whose readback copy is in the same
// memory). A scene past it is a one-line error naming what it needs.
void checkDeviceMemory(const vk::Context& ctx, const GpuScene& scene, bool wide, const UploadOptions& options) {
    const MemoryLimit limit = deviceMemory(ctx, options.limits.memory);
    if (limit.bytes == 0) return;
    std::uint64_t arrays = 0;
    for (const ArrayUse& a : arrayUses(scene, wide)) arrays += paddedSize(a.bytes);
    const bool cpu = ctx.info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    const std::uint64_t sums = options.imageBytes * (cpu ? 2u : 1u);
    if (arrays + sums <= limit.bytes) return;
    fail(scene.source, "the render needs " + sizeText(arrays + sums) + " of device memory (the scene's arrays " +
                           sizeText(arrays) + ", the image's sample sums " + sizeText(sums) + "), more than the " +
                           sizeText(limit.bytes) + " of " + ctx.info.name + " (" + limit.what + ")");
}

template <class T>
void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
}
template <class T>
void release(const std::vector<T>&) {}

// G is GpuScene (each large array freed once uploaded) or const GpuScene (kept).
template <class G>
DeviceScene upload(const vk::Context& ctx, G& scene, const UploadOptions& options) {
    const auto t0 = std::chrono::steady_clock::now();
    const SceneLimits limits = sceneLimits(ctx, options.limits);
    const BvhStack stack = options.stack;
    const std::uint32_t regs = bvhRegsFor(scene.wideDepth);
    const bool wide = scene.bvhWidth == 4;  // packing's choice (GpuScene::bvhWidth)
    constexpr bool consume = !std::is_const_v<G>;  // each array released as it is copied
    const bool cpu = ctx.info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    DeviceScene d;
    d.reads = chooseReads(limits, scene, options.reads, wide, cpu);
    checkDeviceMemory(ctx, scene, wide, options);
    d.wide = wide;
    d.bvhRegs = wide ? regs : 16u;
    d.memoryStack = wide && (stack == BvhStack::Memory || (stack == BvhStack::Auto && !cpu));
    d.triangles = scene.tris.size();
    d.nodeCount = wide ? scene.wide.size() : scene.nodes.size();
    for (const ArrayUse& a : arrayUses(scene, wide)) d.packedBytes += a.bytes;
    d.features = scene.features;
    d.frame.counts = glm::uvec4(scene.emitters.size(), d.triangles, d.nodeCount, 0u);
    d.frame.scene = glm::vec4(static_cast<float>(scene.totalPower), 0.0f, 0.0f, 0.0f);
    setLightUniforms(d.frame, scene);
    // Each array is handed back as it is copied and released once on the
    // device; the tree not traversed is released first.
    auto put = [&](DeviceArray& dst, auto& src) {
        dst = uploadArray(ctx, src, limits, consume);
        release(src);
    };
    if (wide) {
        release(scene.nodes);
        put(d.nodes, scene.wide);
    } else {
        release(scene.wide);
        put(d.nodes, scene.nodes);
    }
    put(d.tris, scene.tris);
    put(d.shading, scene.shading);
    put(d.texcoords, scene.texcoords);
    put(d.tangents, scene.tangents);
    put(d.colors, scene.colors);
    put(d.instances, scene.instances);
    d.emitters = uploadArray(ctx, scene.emitters, limits);
    d.lightTree = uploadArray(ctx, scene.lightTree, limits);
    d.materials = uploadArray(ctx, scene.materials, limits);
    d.textureRefs = uploadArray(ctx, scene.textureRefs, limits);
    d.texels = vk::uploadVector(ctx, scene.texels, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    d.texelsView = vk::TexelView(ctx, d.texels, VK_FORMAT_R32_UINT);
    release(scene.texels);
    uploadEnvironment(ctx, scene, d, limits);
    release(scene.envTexels);
    for (const DeviceArray* a : {&d.nodes, &d.tris, &d.shading, &d.texcoords, &d.tangents, &d.colors, &d.instances,
                                  &d.emitters, &d.lightTree, &d.materials, &d.textureRefs, &d.envTables})
        d.deviceBytes += a->buffer.allocationSize();
    for (const vk::Buffer* b : {&d.texels, &d.envTexels})
        d.deviceBytes += b->allocationSize();
    d.uploadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return d;
}

}  // namespace

void fitTextures(const vk::Context& ctx, GpuScene& scene, const UploadOptions& options) {
    if (scene.images.empty()) return;
    const SceneLimits limits = sceneLimits(ctx, options.limits);
    // One R32UI view and one buffer hold the words; the device's memory
    // holds them with every other array and the image's sample sums.
    std::uint64_t room = limits.texelElements * sizeof(std::uint32_t);
    std::string what = "one texel view's " + std::to_string(limits.texelElements) + " texels";
    if (limits.allocation > 0 && limits.allocation < room)
        room = limits.allocation, what = "one buffer's " + sizeText(limits.allocation);
    const MemoryLimit memory = deviceMemory(ctx, options.limits.memory);
    if (memory.bytes > 0) {
        const bool cpu = ctx.info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU;
        std::uint64_t others = options.imageBytes * (cpu ? 2u : 1u);
        for (const ArrayUse& a : arrayUses(scene, scene.bvhWidth == 4))
            if (std::string(a.what) != "texture texels") others += paddedSize(a.bytes);
        const std::uint64_t left = memory.bytes > others ? memory.bytes - others : 0;
        if (left < room) room = left, what = "the " + sizeText(left) + " of device memory the rest leaves";
    }
    // Padded as the upload pads the buffer.
    if (paddedSize(scene.texels.size() * sizeof(std::uint32_t)) <= room) return;
    std::vector<PackedImage> before = scene.images;
    const std::vector<std::size_t> halved = shrinkTextures(scene.texels, scene.textureRefs, scene.images, room & ~std::uint64_t(15));
    if (halved.empty() || scene.texels.size() * sizeof(std::uint32_t) > room) return;  // refused by the checks after
    std::string list;
    constexpr std::size_t kNamed = 3;
    for (std::size_t k = 0; k < std::min(halved.size(), kNamed); ++k) {
        const PackedImage& a = before[halved[k]];
        const PackedImage& b = scene.images[halved[k]];
        list += (k == 0 ? "" : ", ") + a.name + " " + std::to_string(a.width) + "x" + std::to_string(a.height) + " to " +
                std::to_string(b.width) + "x" + std::to_string(b.height);
    }
    if (halved.size() > kNamed) list += " and " + std::to_string(halved.size() - kNamed) + " more";
    warn(scene.source, std::to_string(halved.size()) + " texture(s) downsampled to fit " + what + " (" +
                           sizeText(scene.texels.size() * sizeof(std::uint32_t)) + " of texels): " + list);
}

SceneLimits sceneLimits(const vk::Context& ctx, const SceneLimits& overrides) {
    VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &m3;
    vkGetPhysicalDeviceProperties2(ctx.physical, &props);
    const VkPhysicalDeviceLimits& l = props.properties.limits;
    auto lower = [](std::uint64_t device, std::uint64_t override) {
        return override > 0 ? std::min(device, override) : device;
    };
    return {lower(l.maxStorageBufferRange, overrides.storageRange),
            lower(l.maxTexelBufferElements, overrides.texelElements),
            lower(m3.maxMemoryAllocationSize, overrides.allocation), overrides.memory};
}

std::uint32_t chooseReads(const SceneLimits& limits, const GpuScene& scene, ReadMode mode, bool wide,
                          bool cpuDevice) {
    const ArrayUse* beyondStorage = nullptr;  // first array read either way that only a texel view holds
    const ArrayUse* beyondTexel = nullptr;    // ... that only a storage descriptor holds
    const ArrayUse* bvhBeyondTexel = nullptr;
    const std::vector<ArrayUse> uses = arrayUses(scene, wide);
    for (const ArrayUse& a : uses) {
        if (paddedSize(a.bytes) > limits.allocation)
            fail(scene.source, need(a) + " in one buffer, more than the device's maxMemoryAllocationSize (" +
                                   sizeText(limits.allocation) + ")");
        const bool storage = fitsStorage(a, limits), texel = fitsTexel(a, limits);
        if (!storage && !texel) {
            std::string why = a.storage ? storageLimit(limits) : "";
            if (a.texelBytes > 0) why += (why.empty() ? "" : " and ") + texelLimit(limits, a);
            fail(scene.source, need(a) + ", more than the device's " + why);
        }
        if (!a.storage || a.texelBytes == 0) continue;
        if (!storage && !beyondStorage) beyondStorage = &a;
        if (!texel && !beyondTexel) beyondTexel = &a;
        if (!texel && a.bvh && !bvhBeyondTexel) bvhBeyondTexel = &a;
    }
    if (mode == ReadMode::Storage) {
        if (beyondStorage)
            fail(scene.source, "--reads storage: " + need(*beyondStorage) + ", more than the device's " +
                                   storageLimit(limits));
        return gpu::kReadsStorage;
    }
    if (mode == ReadMode::Texel && bvhBeyondTexel)
        fail(scene.source, "--reads texel: " + need(*bvhBeyondTexel) + ", more than the device's " +
                               texelLimit(limits, *bvhBeyondTexel));
    if (beyondStorage) {  // past the storage range: everything through texel views, if they hold it
        if (beyondTexel)
            fail(scene.source, need(*beyondStorage) + ", more than the device's " + storageLimit(limits) + ", and " +
                                   need(*beyondTexel) + ", more than its " + texelLimit(limits, *beyondTexel));
        return gpu::kReadsTexelAll;
    }
    if (mode == ReadMode::Texel) return gpu::kReadsTexelBvh;
    // CPU devices: every array through texel views where they all fit (a
    // divergent storage load is a scalar loop on lavapipe).
    if (cpuDevice && !beyondTexel) return gpu::kReadsTexelAll;
    return cpuDevice && !bvhBeyondTexel ? gpu::kReadsTexelBvh : gpu::kReadsStorage;
}

const char* readsName(std::uint32_t reads) {
    return reads == gpu::kReadsTexelAll ? "texel-all" : reads == gpu::kReadsTexelBvh ? "texel" : "storage";
}

DeviceArray uploadArray(const vk::Context& ctx, std::span<const std::byte> bytes, const SceneLimits& limits,
                        bool releaseSource) {
    DeviceArray a;
    a.buffer = vk::uploadBuffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                releaseSource);
    const VkDeviceSize size = a.buffer.size();  // a multiple of 16, at least 16
    a.storageRange = std::max<VkDeviceSize>(kTexel, std::min<VkDeviceSize>(size, limits.storageRange) & ~(kTexel - 1));
    const VkDeviceSize texelRange = std::min<VkDeviceSize>(size, std::max<std::uint64_t>(1, limits.texelElements) * kTexel);
    a.texel = vk::TexelView(ctx, a.buffer, VK_FORMAT_R32G32B32A32_UINT, texelRange);
    return a;
}


DeviceScene uploadScene(const vk::Context& ctx, const GpuScene& scene, const UploadOptions& options) {
    return upload(ctx, scene, options);
}

DeviceScene uploadAndRelease(const vk::Context& ctx, GpuScene& scene, const UploadOptions& options) {
    return upload(ctx, scene, options);
}

const char* bvhStackName(const DeviceScene& scene) {
    return scene.wide && !scene.memoryStack ? "registers" : "memory";
}

void uploadEnvironment(const vk::Context& ctx, const GpuScene& scene, DeviceScene& d, const SceneLimits& limits) {
    d.envTexels = vk::uploadVector(ctx, scene.envTexels, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
    d.envTexelView = vk::TexelView(ctx, d.envTexels, VK_FORMAT_R32G32B32A32_SFLOAT);
    d.envTables = uploadArray(ctx, scene.envTables, limits);
}

}  // namespace strata
