// Render statistics as one JSON object (for --stats-json) and as text (--stats).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "pack/gpu_scene.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace strata {

struct StatsInput {
    const vk::Context* ctx = nullptr;
    const Scene* scene = nullptr;
    const GpuScene* gpu = nullptr;
    const RenderSettings* settings = nullptr;
    const RenderResult* result = nullptr;
    double loadMs = 0.0;
    double packMs = 0.0;   // BVH build + packing
    double deviceMs = 0.0; // Vulkan instance and device creation
};

nlohmann::json statsJson(const StatsInput& in);
std::string statsText(const nlohmann::json& stats);

// The packed textures (StatsInput's GpuScene::images) in one line: count,
// bytes, how many were downsampled, the largest four with their sizes.
std::string texturesText(const nlohmann::json& textures);

// Memory: the scene's arrays as packed and the device memory holding them,
// the process's peak device memory (vk::peakDeviceMemoryBytes) and peak host
// resident set size, in bytes; memoryText is its one-line summary.
nlohmann::json memoryJson(std::uint64_t scenePackedBytes, std::uint64_t sceneDeviceBytes);
std::string memoryText(const nlohmann::json& memory);

// "load ... ms, BVH build ... ms (pack ... ms in all), device ... ms, upload
// ... ms" from a start-up object (load_ms, bvh_build_ms, pack_ms,
// device_init_ms, upload_ms), as `--stats` and `strata bench` print it.
std::string startupText(const nlohmann::json& startup);

}  // namespace strata
