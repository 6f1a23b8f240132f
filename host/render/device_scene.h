// A GpuScene uploaded to the device: one storage buffer per array, and
// RGBA32UI texel views over the node and triangle buffers for devices where
// texel fetches beat storage-buffer loads (lavapipe; see DESIGN.md).
#pragma once
#include "../../shaders/shared/bindings.h"
#include "render/gpu_scene.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/kernel.h"

namespace strata {

enum class Traversal { Auto, Texel, Storage };

struct DeviceScene {
    vk::Buffer nodes, tris, shading, materials, emitters;
    vk::TexelView nodesTexel, trisTexel;
    vk::Buffer envTexels, envTables;  // 16-byte placeholders without an environment map
    vk::TexelView envTexelView;       // RGBA32F over envTexels
    bool texel = false;  // traversal reads nodes/triangles through the texel views
};

// Texel reads on CPU devices (lavapipe), storage reads elsewhere, unless forced.
// Throws strata::Error when texel reads are forced but the buffers exceed the
// device's maxTexelBufferElements.
bool chooseTexelTraversal(const vk::Context& ctx, const GpuScene& scene, Traversal mode);

DeviceScene uploadScene(const vk::Context& ctx, const GpuScene& scene, Traversal mode);

// Binds nodes, triangles and their texel views (the BVH traversal's inputs).
void bindTraversal(vk::Kernel& kernel, const DeviceScene& scene);

// Uploads the environment map's texels (with their RGBA32F view) and tables.
void uploadEnvironment(const vk::Context& ctx, const GpuScene& scene, DeviceScene& dev);

}  // namespace strata
