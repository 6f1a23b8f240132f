// A GpuScene uploaded to the device: one buffer per array. The BVH nodes, the
// per-triangle arrays and the emitters are bound twice, as storage buffers and
// through RGBA32UI texel views of the same VkBuffer; SPEC_TEXEL_FETCH (kReads*,
// shaders/shared/types.h) says which of the two the shaders read. Texel reads
// are faster on lavapipe (docs/architecture.md, device facts) and reach
// maxTexelBufferElements texels (2 GiB there) where a storage descriptor
// reaches maxStorageBufferRange (128 MiB there), so scenes beyond the storage
// range read everything through them.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pack/gpu_scene.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/kernel.h"  // TexelView
#include "util/memory.h"  // sizeText

namespace strata {

// --reads: how the shaders read the scene arrays (chooseReads below).
enum class ReadMode { Auto, Texel, Storage };

// Where the four-wide traversal keeps its stack (shaders/lib/bvh4.glsl): in
// registers (CPU devices: lavapipe runs an indexed array as a scalar loop per
// lane) or in an indexed array (GPUs, where shifting registers costs more).
// Auto: registers on CPU devices, memory elsewhere.
enum class BvhStack { Auto, Registers, Memory };

// The limits a scene is planned and bound against. sceneLimits() gives the
// device's; a nonzero override lowers one (tests reach the large-scene path
// on small scenes that way).
struct SceneLimits {
    std::uint64_t storageRange = 0;   // bytes of one storage descriptor (maxStorageBufferRange)
    std::uint64_t texelElements = 0;  // texels of one texel view (maxTexelBufferElements)
    std::uint64_t allocation = 0;     // bytes of one buffer (maxMemoryAllocationSize)
    std::uint64_t memory = 0;         // bytes of all the render's buffers, an override only (the
                                      // upload finds the device's: its largest device-local heap,
                                      // on a CPU device at most the host memory budget)
};

SceneLimits sceneLimits(const vk::Context& ctx, const SceneLimits& overrides = {});


// SPEC_TEXEL_FETCH for `scene` (kReads*). Auto: every array through texel
// views on CPU devices (lavapipe; the BVH alone where another array does not
// fit a texel view), storage elsewhere, and every array through texel views
// wherever one exceeds limits.storageRange; Texel and Storage force the BVH's
// reads. Throws strata::Error (one line naming the scene file) when an array
// exceeds limits.allocation, when an array fits neither a storage descriptor
// nor a texel view, or when the forced reads cannot address the scene.
std::uint32_t chooseReads(const SceneLimits& limits, const GpuScene& scene, ReadMode mode, bool wide,
                          bool cpuDevice);

// "storage", "texel" (the BVH) or "texel-all" for a kReads* value.
const char* readsName(std::uint32_t reads);

// One array on the device, bound as a storage buffer over its first
// `storageRange` bytes and through `texel`, each within the limits it was
// uploaded with (the shader reads through one of them).
struct DeviceArray {
    vk::Buffer buffer;
    VkDeviceSize storageRange = 0;
    vk::TexelView texel;  // RGBA32UI
};

// releaseSource as vk::uploadBuffer: the bytes are read no more.
DeviceArray uploadArray(const vk::Context& ctx, std::span<const std::byte> bytes, const SceneLimits& limits,
                        bool releaseSource = false);

template <class T>
DeviceArray uploadArray(const vk::Context& ctx, const std::vector<T>& v, const SceneLimits& limits,
                        bool releaseSource = false) {
    return uploadArray(ctx, std::as_bytes(std::span<const T>(v)), limits, releaseSource);
}

struct DeviceScene {
    DeviceArray nodes, tris, shading, texcoords, tangents, colors, instances, emitters, materials, textureRefs;
    DeviceArray lightTree;  // GpuScene::lightTree (16 bytes without the tree)
    // Texturing inputs; a 16-byte zero buffer each when the scene has none
    // (every binding the shaders declare stays valid for the validation layers).
    vk::Buffer texels;
    vk::TexelView texelsView;  // R32UI over `texels`
    vk::Buffer envTexels;             // a 16-byte placeholder without an environment map
    DeviceArray envTables;            // sampling tables (16 bytes without a map)
    vk::TexelView envTexelView;       // RGBA32F over envTexels
    std::uint32_t reads = gpu::kReadsStorage;  // SPEC_TEXEL_FETCH
    bool wide = false;   // `nodes` holds GpuScene::wide, else the BVH2 (the bvh2 axis)
    std::uint32_t bvhRegs = 16;  // SPEC_BVH_REGS with `wide`
    bool memoryStack = false;    // with `wide`: the bvh4m axis (stack in an array)
    std::uint64_t triangles = 0;  // counts of what was uploaded (the GpuScene's
    std::uint64_t nodeCount = 0;  // arrays may be released since)
    std::uint64_t packedBytes = 0;  // bytes of the arrays uploaded, as packed
    std::uint64_t deviceBytes = 0;  // device memory of their buffers
    double uploadMs = 0.0;          // host wall time of the upload
    SceneFeatures features;         // what the kernels compile in (SPEC_FEATURES, SPEC_HAS_EMITTERS)
    gpu::FrameUniforms frame{};     // the scene's part of the frame constants (counts.xyz,
                                    // scene.x, env*); the renderer adds the camera, image and spp
    bool texel() const { return reads != gpu::kReadsStorage; }
};

// How a packed scene goes onto the device: how its arrays are read, which
// stack the four-wide traversal keeps, and the limits it is planned against.
// The tree traversed is the packed scene's (GpuScene::bvhWidth, chosen when
// packing), so the upload and the packing cannot disagree about it.
struct UploadOptions {
    ReadMode reads = ReadMode::Auto;
    BvhStack stack = BvhStack::Auto;  // the four-wide traversal's
    SceneLimits limits;               // overrides, as sceneLimits
    std::uint64_t imageBytes = 0;     // the render's sample sums (RenderSettings: sampleSumBytes),
                                      // counted with the scene's arrays against limits.memory
};

// Textures past what the device holds (one texel view's elements, one
// buffer's size, or the device memory the scene's other arrays and the
// sample sums leave) are made to fit: the largest halved first
// (shrinkTextures), with one warning naming them. A scene that fits is
// left as it is.
void fitTextures(const vk::Context& ctx, GpuScene& scene, const UploadOptions& options = {});

DeviceScene uploadScene(const vk::Context& ctx, const GpuScene& scene, const UploadOptions& options = {});

// The same, and frees each of the scene's large arrays (BVH, triangles,
// shading, texture coordinates, tangents, texture and environment texels) as
// soon as it is on the device (each array's pages handed back chunk by chunk
// as they are copied), so host memory does not hold the scene twice. The
// rest (materials, emitters, features, counts) stays for the report.
DeviceScene uploadAndRelease(const vk::Context& ctx, GpuScene& scene, const UploadOptions& options = {});

// "registers" (four-wide, register stack) or "memory" (an indexed array: the
// four-wide memory stack, and always the BVH2's).
const char* bvhStackName(const DeviceScene& scene);

// Uploads the environment map's texels (with their RGBA32F view) and tables
// (storage range and RGBA32UI view as `limits` allow).
void uploadEnvironment(const vk::Context& ctx, const GpuScene& scene, DeviceScene& dev, const SceneLimits& limits);

}  // namespace strata
