// State files (.state): a render's whole accumulation (Accumulation,
// render/renderer.h) with what decides its image, written atomically. They
// let a render be resumed (--resume), checkpointed (--checkpoint-every) and
// split into shards of its sample indices (--shard I/K) that `strata merge`
// sums exactly (docs/distributed.md).
//
// The file, little-endian: "STRATAst", u32 format version, u32 header
// length, the header (JSON: StateInfo and the sample range), then count
// (u64 a pixel), sum and sumSq (3 FixedSum a pixel each), the AOV sums
// (Film::kAovSums FixedSum a pixel, with AOVs), the pending float32 sums
// (Film::batchFloats, when the range ends inside a batch), and a Hash64 of
// everything before it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pack/gpu_scene.h"
#include "render/renderer.h"
#include "settings/settings.h"
#include "scene/scene.h"

namespace strata {

inline constexpr std::uint32_t kStateVersion = 1;

// A state's header. `settings` decide the image: states combine only when
// they are equal. `implementation` (the device, its driver, the traversal)
// does not change what is estimated: states from different ones combine into
// an image statistically equivalent to a single render, not the same bits.
struct StateInfo {
    std::string scene;                      // the scene's path as given (messages only)
    std::string sceneHash;                  // sceneContentHash
    nlohmann::ordered_json settings;        // stateSettings
    nlohmann::ordered_json implementation;  // stateImplementation; with "others" after a mixed merge
    std::uint32_t spp = 0;                  // the render's --spp: its sample indices are [0, spp)
    std::uint32_t shard = 0, shards = 0;    // --shard I/K (shards 0: none)
    std::uint32_t batch = 64;               // RenderTuning::maxBatch
};

struct RenderState {
    StateInfo info;
    Accumulation acc;
};

// A hash of what the device renders: the packed scene's geometry, materials,
// textures, lights and environment (not the BVH's nodes, which the traversal
// choice changes) and the camera.
std::string sceneContentHash(const GpuScene& scene, const Camera& camera);

// The settings that decide the image, as the header records them (keyed by
// their flags' names, so that a difference reads as the flag). `spp`
// only for the samplers whose pattern it sizes (SamplerInfo::prefixesAreSamplings
// false): for the others a state can be resumed to more samples.
// `lightTree`: the scene's lights are chosen by the light tree (then
// --light-candidates is one of them).
nlohmann::ordered_json stateSettings(const RenderSettings& s, const Camera& camera, bool lightTree);
nlohmann::ordered_json stateImplementation(const std::string& device, const std::string& driver,
                                           const RenderSettings& s);

// Shard i of k: a contiguous run of whole batches of [0, spp), the runs as
// even as whole batches allow. Throws strata::Error when i >= k or there are
// fewer batches than shards.
struct SampleRange {
    std::uint32_t begin = 0, end = 0;
};
SampleRange shardRange(std::uint32_t spp, std::uint32_t i, std::uint32_t k, std::uint32_t batch);

// Throws strata::Error ("PATH: error: ...") on failure; the file appears
// whole or not at all.
void writeState(const std::string& path, const RenderState& state);

// Throws strata::Error naming `path` for a file that is not a state, of
// another version, truncated, corrupted (checksum) or inconsistent.
RenderState readState(const std::string& path);

// What keeps `b` from combining with `a` (the first difference of scene or
// settings, in words naming both files), or "" when they may.
std::string stateMismatch(const StateInfo& a, const std::string& aName, const StateInfo& b, const std::string& bName);

// Whether two states come from one implementation (device, driver,
// integrator, BVH width); never for a merge of several ("others").
bool sameImplementation(const StateInfo& a, const StateInfo& b);

// A one-line description of an implementation ("llvmpipe ... (Mesa ...), bvh 4, ...").
std::string implementationText(const nlohmann::ordered_json& implementation);

}  // namespace strata
