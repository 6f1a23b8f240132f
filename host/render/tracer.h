// Runs the trace-only kernel (shaders/trace.comp) over a batch of rays: the
// shader's BVH traversal on its own, for tests and benchmarks.
#pragma once
#include <vector>

#include "render/device_scene.h"
#include "render/gpu_scene.h"
#include "vk/context.h"

namespace strata {

// `mode` is gpu::kTraceClosest, kTraceAny or kTraceSpawn (types.h).
std::vector<gpu::TraceHit> traceOnDevice(const vk::Context& ctx, const GpuScene& scene,
                                         const std::vector<gpu::TraceRay>& rays,
                                         Traversal traversal, std::uint32_t mode);

}  // namespace strata
