// The kernels of the integrators and of the trace-only driver
// (measure/tracer.h), built for an uploaded scene: which SPIR-V its BVH
// takes, the scene's bindings and specialization constants, the
// path-tracing inputs both integrators share, and the trace kernel with its
// work queue (shaders/trace.comp).
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "settings/settings.h"
#include "upload/device_scene.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/kernel.h"

namespace strata {

// The SPIR-V of pathtrace.comp (pathtrace true) or trace.comp, and of
// wavefront.comp, for the scene: the table's module (spirv::chooseVariant),
// compiled or taken from the shader cache (spirv::moduleFor).
std::span<const std::uint32_t> traversalShader(const DeviceScene& scene, bool pathtrace, bool aov = false,
                                               bool motion = false);
std::span<const std::uint32_t> wavefrontShader(const DeviceScene& scene);

// The specialization constants that pick the traversal (SPEC_TEXEL_FETCH,
// SPEC_BVH_REGS) into `spec`, grown as needed. The BVH width and the stack
// are the shader's (traversalShader).
void setTraversalSpec(const DeviceScene& scene, std::vector<std::uint32_t>& spec);

// Binds the array's storage range at `storageBinding` and its view at `texelBinding`.
void bindArray(vk::Kernel& kernel, std::uint32_t storageBinding, std::uint32_t texelBinding, const DeviceArray& a);

// The traversal's inputs: nodes, triangles, their texel views, and what the
// alpha test reads (shading, materials, texture coordinates, texture refs and
// texels; shaders/lib/material.glsl) plus the tangents. sceneBindings() lists
// their descriptor types for a vk::Kernel.
std::vector<vk::BindingDesc> sceneBindings();
void bindTraversal(vk::Kernel& kernel, const DeviceScene& scene);

// The buffers the progressive loop (render/renderer.h) owns and every
// integrator reads or adds to.
struct FilmBuffers {
    const vk::Buffer& frame;        // BINDING_FRAME: gpu::FrameUniforms
    const vk::Buffer& filterTable;  // BINDING_FILTER: settings/filter.h's inverse CDF
    const vk::Buffer& accum;        // BINDING_ACCUM: kAccumVec4PerPixel vec4 per pixel
    const vk::Buffer& counters;     // BINDING_COUNTERS: gpu::RenderCounters
    const vk::Buffer& activeBlocks; // BINDING_ACTIVE_BLOCKS: render/adaptive.h (SPEC_ADAPTIVE)
};

// What the path-tracing shaders (pathtrace.comp and wavefront.comp's
// stages) read and write: the scene's bindings, the emitters, the
// environment and the film's buffers; binding them; and the specialization
// constants both take from the scene and the settings (SPEC_COUNT_RAYS,
// SPEC_TRACE_MODE and SPEC_WORK_QUEUE are left 0 for the caller).
std::vector<vk::BindingDesc> pathBindings();
void bindPathInputs(vk::Kernel& kernel, const DeviceScene& dev, const FilmBuffers& film);
std::vector<std::uint32_t> pathSpec(const DeviceScene& dev, const RenderSettings& s);

// SPEC_WORK_QUEUE for this device and mode (upload/device_scene.h, WorkQueue).
bool useWorkQueue(const vk::Context& ctx, WorkQueue mode = WorkQueue::Auto);

// The trace kernel (shaders/trace.comp) for `dev` in `mode` (gpu::kTrace*),
// with the scene bound; the caller binds BINDING_RAYS, BINDING_HITS,
// BINDING_HIT_INSTANCES (written for an instanced scene's closest hits) and
// BINDING_WORK. `queue`: SPEC_WORK_QUEUE (useWorkQueue).
std::unique_ptr<vk::Kernel> makeTraceKernel(const vk::Context& ctx, const DeviceScene& dev, std::uint32_t mode,
                                            bool queue, bool reuse = false);

// Rays one trace dispatch takes at most (bounds one dispatch's work queue;
// even, for kTraceSpawn's pairs), and the work-queue words for `rays` rays.
inline constexpr std::uint32_t kRaysPerTraceDispatch = 1u << 18;
VkDeviceSize traceWorkBytes(std::uint64_t rays);

// Records `kernel` over rays [0, count) of its bound ray buffer, in
// dispatches of at most kRaysPerTraceDispatch rays; with `queue`, zeroes
// `work` first and records each dispatch's two passes (the second sized by
// the first's last subgroup). Returns the dispatches recorded.
std::uint32_t recordTrace(VkCommandBuffer cmd, const vk::Context& ctx, vk::Kernel& kernel, const vk::Buffer& work,
                          std::uint64_t count, bool queue);

}  // namespace strata
