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
    // Texturing inputs; a 16-byte zero buffer each when the scene has none
    // (every binding the shaders declare stays valid for the validation layers).
    vk::Buffer texcoords, tangents, textureRefs, texels;
    vk::TexelView texelsView;  // R32UI over `texels`
    vk::Buffer envTexels, envTables;  // 16-byte placeholders without an environment map
    vk::TexelView envTexelView;       // RGBA32F over envTexels
    bool texel = false;  // traversal reads nodes/triangles through the texel views
    bool wide = false;   // `nodes` holds GpuScene::wide (SPEC_BVH_WIDE), else the BVH2
    std::uint32_t bvhRegs = 16;  // SPEC_BVH_REGS with `wide`
};

// Texel reads on CPU devices (lavapipe), storage reads elsewhere, unless forced.
// Throws strata::Error when texel reads are forced but the buffers exceed the
// device's maxTexelBufferElements.
bool chooseTexelTraversal(const vk::Context& ctx, const GpuScene& scene, Traversal mode, bool wide);

// bvhWidth 4: the four-wide BVH (SPEC_BVH_WIDE 1) unless the scene's wide tree
// is deeper than kBvhMaxRegs (bvh/wide.h); 2: the BVH2.
DeviceScene uploadScene(const vk::Context& ctx, const GpuScene& scene, Traversal mode, int bvhWidth = 4);

// The specialization constants that pick the traversal (SPEC_TEXEL_FETCH,
// SPEC_BVH_WIDE, SPEC_BVH_REGS) into `spec`, grown as needed.
void setTraversalSpec(const DeviceScene& scene, std::vector<std::uint32_t>& spec);

// Throws strata::Error (one line naming the scene file) when the packed
// texture words exceed the device's maxTexelBufferElements.
void checkTexelLimit(const vk::Context& ctx, const GpuScene& scene);

// The traversal's inputs: nodes, triangles, their texel views, and what the
// alpha test reads (shading, materials, texture coordinates, texture refs and
// texels; shaders/lib/material.glsl) plus the tangents. sceneBindings() lists
// their descriptor types for a vk::Kernel.
std::vector<vk::BindingDesc> sceneBindings();
void bindTraversal(vk::Kernel& kernel, const DeviceScene& scene);

// Uploads the environment map's texels (with their RGBA32F view) and tables.
void uploadEnvironment(const vk::Context& ctx, const GpuScene& scene, DeviceScene& dev);

}  // namespace strata
