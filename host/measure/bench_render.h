// The sections of `strata bench` that run the path tracer (measure/bench.h):
// path tracing and dispatch throughput. Each render() they make warms the
// pipeline up with one dispatch first (RenderTuning::warmUp) and is timed
// with Vulkan timestamps around its dispatches.
#pragma once
#include <vector>

#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "measure/bench.h"
#include "pack/gpu_scene.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace strata {

// Host ms of vkCreateComputePipelines of every render() a section made, in order.
using PipelineTimes = std::vector<double>;

// The renderer at the command's size, spp, seed and max depth: Msamples/s,
// rays/s and mean path length from the device's ray counters, relMSE when
// `reference` is given (same size, checked by the caller), and the cost of
// the ray counters (renders with and without them, alternated).
nlohmann::ordered_json benchPathTracing(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                                        const BenchCommand& cmd, const RgbImage* reference,
                                        PipelineTimes& pipelines);

// One-sample dispatches at square sizes 64 .. 2048 (64, 128 with --quick),
// sample counts capped by a budget of samples per size; then 1, 8 and 64
// dispatches per submission at 64^2.
nlohmann::ordered_json benchDispatch(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                                     const BenchCommand& cmd, PipelineTimes& pipelines);

}  // namespace strata
