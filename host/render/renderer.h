// The progressive render loop: the image in tiles, one sample of a tile at
// a time taken by the integrator (integrate/integrator.h), samples batched
// into submissions, float32 batch sums folded into a Film of 128-bit
// fixed-point sums (image/film.h, toFixed).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "image/film.h"
#include "settings/settings.h"
#include "scene/scene.h"
#include "upload/device_scene.h"
#include "vk/context.h"

namespace strata {

struct RenderResult;

// A render's accumulation as a state file holds it (render/state.h): the
// complete batches of samples [begin, folded) in `film`, and the device's
// float32 sums of [folded, end) (a batch not yet complete) in `pending`.
// Batches are the runs of RenderTuning::maxBatch sample indices starting
// at multiples of it, so the same samples always make the same batches.
struct Accumulation {
    Film film;
    std::vector<float> pending;  // Film::batchFloats() floats; empty when folded == end
    std::uint32_t begin = 0, folded = 0, end = 0;
    std::uint64_t nonFinite = 0;  // samples the device dropped as NaN or Inf (RenderCounters)
    // The image's sums: film with pending folded in.
    Film image() const;
};

// The sample indices a render takes, and its accumulation for state files.
struct SampleRun {
    std::uint32_t begin = 0;             // first sample index (a shard's): a multiple of maxBatch
    std::uint32_t end = 0;               // one past the last; 0: settings.spp
    const Accumulation* resume = nullptr;  // continue this one (its begin and end replace `begin`)
    bool keep = false;                   // fill RenderResult::state
    double checkpointSeconds = 0.0;      // call onCheckpoint this often (wall time), 0: never
    std::function<void(const Accumulation&)> onCheckpoint;
    // Called after every submission with the image's spp and a function
    // that returns the image so far (the batch in progress included: one
    // readback); returning false ends the render there, as a signal does
    // (strata view: a window's event loop between submissions).
    std::function<bool(std::uint32_t spp, const std::function<Film()>& image)> onSubmission;
};

// Called when the render has taken exactly `checkpoint` spp (ascending values
// <= spp); submissions are cut so every checkpoint is hit exactly.
struct Checkpoints {
    std::vector<std::uint32_t> spp;
    std::function<void(const RenderResult&)> onReached;
};

struct RenderResult {
    Film film;
    std::uint32_t spp = 0;              // samples per pixel in the image (with a resumed state's)
    std::uint32_t sppRendered = 0;      // of those, the ones this render took
    std::uint64_t samplesTaken = 0;     // pixel samples this render took (adaptive: fewer than
                                        // pixels x sppRendered)
    Accumulation state;                 // with SampleRun::keep: the accumulation the image is made of
    int interrupted = 0;                // the SIGINT or SIGTERM that ended the loop early
                                        // (util/interrupt.h), 0 when none
    double seconds = 0.0;               // wall time of the dispatch loop
    double deviceSeconds = 0.0;         // device time of the path-tracing dispatches (timestamps),
                                        // excluding upload and the readback of each batch;
                                        // equals `seconds` where the queue has no timestamps
    std::uint64_t nonFinite = 0;        // samples dropped as NaN/Inf, or in a batch whose
                                        // float32 sum overflowed (Film::overflowed)
    std::uint32_t submissions = 0;
    std::uint64_t dispatches = 0;       // path-tracing dispatches recorded in the loop
    double hostSubmitSeconds = 0.0;     // host wall time of the loop's submissions, from the
                                        // start of recording to the end of the wait
    std::uint64_t closestRays = 0;      // counted when tuning.countRays
    std::uint64_t shadowRays = 0;
    double uploadMs = 0.0;              // scene upload (host wall time)
    double pipelineMs = 0.0;            // vkCreateComputePipelines for pathtrace.comp (0 when reused)
    bool pipelineReused = false;        // an earlier render's pipeline was shared (reusePipeline)
    double warmUpDeviceSeconds = 0.0;   // the warm-up dispatch (tuning.warmUp), timestamps
    double warmUpHostSeconds = 0.0;     // its submission, recording to end of wait
    std::uint32_t warmUpPixels = 0;
    std::uint32_t reads = gpu::kReadsStorage;  // SPEC_TEXEL_FETCH: how the scene's arrays were read
    int bvhWidth = 2;                   // the BVH the shader traversed
    const char* bvhStack = "memory";    // its stack: bvhStackName (upload/device_scene.h)
    std::uint64_t sceneBytes = 0;       // the scene's arrays as packed (DeviceScene::packedBytes)
    std::uint64_t sceneDeviceBytes = 0; // device memory holding them
    std::uint64_t peakDeviceBytes = 0;  // most device memory the process held at once, by the
                                        // render's end (scene, image, staging: vk::Buffer)
    double msamplesPerSecond() const {
        return seconds > 0 ? static_cast<double>(samplesTaken) / seconds * 1e-6 : 0.0;
    }
};

// The samples of a render's first submission, before any time per sample is
// known: as many as 2^17 pixel samples allow (128x128: 8), at most 8 and
// the integrator's samples a dispatch, at least 1 (from about 362x362 on).
// A dispatch of one sample runs each lane's path alone: on lavapipe its
// sample costs 1.4x one of eight (docs/experiments/integrators.md, "The
// first submission"); 2^17 pixel samples are about 0.3 s of many-lights.
std::uint32_t firstSubmissionSamples(std::size_t pixels, std::uint32_t samplesPerDispatch);

// Throws strata::Error when the image's sample sums (32 bytes a pixel, 112
// with AOVs; one buffer) exceed the device's maxMemoryAllocationSize (or limits'). render
// checks it after the scene's own limits (a scene that does not fit is named
// first).
void checkImageFits(const vk::Context& ctx, const RenderSettings& settings, const SceneLimits& limits = {});

// Renders a scene on the device (upload/device_scene.h) through `camera`:
// samples [run.begin, run.end), or on from run.resume. Checkpoints count
// the image's spp.
RenderResult render(const vk::Context& ctx, const DeviceScene& scene, const Camera& camera,
                    const RenderSettings& settings, const RenderTuning& tuning = {},
                    const Checkpoints& checkpoints = {}, const SampleRun& run = {});

}  // namespace strata
