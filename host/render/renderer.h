// The progressive render loop: one path per pixel per dispatch, dispatches
// batched into submissions, float32 batch sums folded into a double Film.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "image/film.h"
#include "render/filter.h"
#include "render/device_scene.h"
#include "render/gpu_scene.h"
#include "scene/scene.h"
#include "vk/context.h"
#include "vk/kernel.h"

namespace strata {

// How a sample is taken: pathtrace.comp, one invocation per path with both
// traversals inlined (the megakernel), or the wavefront integrator's stages
// with every traversal in the trace kernel (render/wavefront.h).
enum class Integrator { Megakernel, Wavefront };

struct RenderSettings {
    int width = 512;
    int height = 512;
    std::uint32_t spp = 64;
    std::uint32_t seed = 0;
    std::uint32_t maxDepth = 16;        // scattering events (pbrt's convention)
    double timeLimit = 0.0;             // seconds; 0 = none. Stops after the submission in progress
    bool progress = false;              // progress line on stderr
    Traversal traversal = Traversal::Auto;
    int bvhWidth = 4;                   // 4: four-wide BVH where it fits (render/device_scene.h), 2: BVH2
    BvhStack bvhStack = BvhStack::Auto; // the four-wide traversal's stack (render/device_scene.h)
    std::uint32_t sampler = gpu::kSamplerSobol;  // render/sampler_kind.h; default: Sobol,
                                        // the best time-to-error measured (README, Sampling)
    PixelFilter filter;                 // pixel reconstruction filter (box, radius 0.5)
    std::uint32_t mis = gpu::kMisPower; // gpu::kMis*: light and BSDF sampling by the power
                                        // heuristic, or one technique alone (for comparisons)
    std::uint32_t maxBatch = 64;        // samples per float32 device batch before folding
    double submitSeconds = 0.25;        // target wall time of one submission (sets how many
                                        // samples each carries; never changes the image)
    std::uint32_t tileSize = 512;       // dispatch covers at most tileSize^2 pixels
    std::uint32_t fixedBatch = 0;       // samples per submission (cut at folds and checkpoints);
                                        // 0: adapt to submitSeconds
    bool warmUp = false;                // one dispatch (a tile of at most 64x64 pixels, sample 0)
                                        // before the loop, timed apart and cleared from the image
    bool countRays = true;              // SPEC_COUNT_RAYS: closest/shadow ray counters
    WorkQueue workQueue = WorkQueue::Auto;  // SPEC_WORK_QUEUE: 8x8 blocks in a permuted order
                                        // (render/device_scene.h; on for CPU devices)
    SceneLimits limits;                 // lower device limits to plan the scene against (0: the
                                        // device's; render/device_scene.h)
    Integrator integrator = Integrator::Megakernel;
    bool reusePipeline = true;          // share the compiled pipeline of an earlier render with the
                                        // same shader and constants (vk::Kernel's reuse; bench
                                        // turns it off to time pipeline creation)
};

struct RenderResult;

// Called when the render has taken exactly `checkpoint` spp (ascending values
// <= spp); submissions are cut so every checkpoint is hit exactly.
struct Checkpoints {
    std::vector<std::uint32_t> spp;
    std::function<void(const RenderResult&)> onReached;
};

struct RenderResult {
    Film film;
    std::uint32_t spp = 0;              // samples per pixel actually taken
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
    std::uint64_t closestRays = 0;      // counted on the device when settings.countRays
    std::uint64_t shadowRays = 0;
    double uploadMs = 0.0;              // scene upload (host wall time)
    double pipelineMs = 0.0;            // vkCreateComputePipelines for pathtrace.comp (0 when reused)
    bool pipelineReused = false;        // an earlier render's pipeline was shared (reusePipeline)
    double warmUpDeviceSeconds = 0.0;   // the warm-up dispatch (settings.warmUp), timestamps
    double warmUpHostSeconds = 0.0;     // its submission, recording to end of wait
    std::uint32_t warmUpPixels = 0;
    std::uint32_t reads = gpu::kReadsStorage;  // SPEC_TEXEL_FETCH: how the scene's arrays were read
    int bvhWidth = 2;                   // the BVH the shader traversed
    const char* bvhStack = "memory";    // its stack: bvhStackName (render/device_scene.h)
    std::uint64_t sceneBytes = 0;       // the scene's arrays as packed (DeviceScene::packedBytes)
    std::uint64_t sceneDeviceBytes = 0; // device memory holding them
    std::uint64_t peakDeviceBytes = 0;  // most device memory the process held at once, by the
                                        // render's end (scene, image, staging: vk::Buffer)
    double msamplesPerSecond() const {
        return seconds > 0 ? static_cast<double>(film.pixels()) * spp / seconds * 1e-6 : 0.0;
    }
};

// What the path-tracing shaders (pathtrace.comp and wavefront.comp's
// stages) read and write besides the scene: the bindings of the frame, the
// emitters, the sample sums and counters, the filter table and the
// environment; binding those buffers; and the specialization constants
// both take from the scene and the settings (SPEC_WORK_QUEUE and up are
// left 0 for the caller).
std::vector<vk::BindingDesc> pathBindings();
void bindPathInputs(vk::Kernel& kernel, const DeviceScene& dev, const vk::Buffer& frame, const vk::Buffer& filterTable,
                    const vk::Buffer& accum, const vk::Buffer& counters);
std::vector<std::uint32_t> pathSpec(const DeviceScene& dev, const GpuScene& scene, const RenderSettings& s);

// Throws strata::Error when the image's sample sums (32 bytes a pixel, one
// buffer) exceed the device's maxMemoryAllocationSize (or s.limits'). render
// checks it after the scene's own limits (a scene that does not fit is named
// first).
void checkImageFits(const vk::Context& ctx, const RenderSettings& settings);

// Uploads `scene` (render/device_scene.h) and renders it.
RenderResult render(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                    const RenderSettings& settings, const Checkpoints& checkpoints = {});

// Renders a scene already on the device; `scene` is the GpuScene it was
// uploaded from, of which only what uploadAndRelease keeps is read (lights,
// features, emitter count).
RenderResult render(const vk::Context& ctx, const DeviceScene& dev, const GpuScene& scene, const Camera& camera,
                    const RenderSettings& settings, const Checkpoints& checkpoints = {});

}  // namespace strata
