// What a render is asked for (RenderSettings: the command line's flags) and
// how the progressive loop dispatches and measures it (RenderTuning: knobs
// that tests and `strata bench` turn; `strata render` keeps the defaults).
#pragma once
#include <cstdint>

#include "../../shaders/shared/types.h"
#include "settings/filter.h"
#include "scene/scene.h"
#include "upload/device_scene.h"

namespace strata {

// How a sample is taken: pathtrace.comp, one invocation per path with both
// traversals inlined (the megakernel), or the wavefront integrator's stages
// with every traversal in the trace kernel (integrate/wavefront.h).
enum class IntegratorKind { Megakernel, Wavefront };

// SPEC_WORK_QUEUE (integrate/kernels.h, useWorkQueue): whether the trace
// kernel's subgroups take their rays from a counter (BINDING_WORK;
// shaders/trace.comp) instead of by workgroup index, and the path tracer
// shades a tile's 8x8 blocks in a permuted order (shaders/pathtrace.comp). lavapipe splits a dispatch's workgroups into one
// contiguous share per thread, so uneven rows or a core slowed by other
// processes left a thread idle; a GPU schedules workgroups itself. Auto: on
// for CPU devices; never with subgroups wider than 64.
enum class WorkQueue { Auto, On, Off };

struct RenderSettings {
    int width = 512;
    int height = 512;
    std::uint32_t spp = 64;
    std::uint32_t seed = 0;
    std::uint32_t maxDepth = 16;        // scattering events (pbrt's convention)
    double timeLimit = 0.0;             // seconds; 0 = none. Stops after the submission in progress
    bool progress = false;              // progress line on stderr
    ReadMode reads = ReadMode::Auto;    // --reads: the scene arrays through texel views or storage
    int bvhWidth = 4;                   // --bvh: 4, the four-wide BVH where it fits, or 2, the BVH2
                                        // (packing decides: GpuScene::bvhWidth)
    BvhStack bvhStack = BvhStack::Auto; // the four-wide traversal's stack (upload/device_scene.h)
    std::uint32_t sampler = gpu::kSamplerSobol;  // gpu::kSampler* (render/sampler_kind.h names them)
    PixelFilter filter;                 // pixel reconstruction filter (box, radius 0.5)
    std::uint32_t mis = gpu::kMisPower; // gpu::kMis*: light and BSDF sampling by the power
                                        // heuristic, or one technique alone (for comparisons)
    IntegratorKind integrator = IntegratorKind::Megakernel;
    // --light-sampler: the light tree or the alias table alone (pack/light_tree.h).
    LightSampler lightSampler = LightSampler::Auto;
    // --light-candidates: with the light tree, each light sample is one of
    // this many descents, resampled (SPEC_LIGHT_CANDIDATES, lib/lights.glsl);
    // 0: not given, kLightCandidates.
    std::uint32_t lightCandidates = 0;
    static constexpr std::uint32_t kLightCandidates = 2;
    std::uint32_t lightCandidateCount() const { return lightCandidates ? lightCandidates : kLightCandidates; }
    // --texture-lod: textures read at the level of each lookup's ray-cone
    // footprint (mip chains, kFeatureTextureLod), by either integrator.
    bool textureLod = true;
    // The camera effects (the motion axis, lib/camera.glsl):
    float lensRadius = 0.0f;            // --lens-radius (world units): 0 is a pinhole
    float focusDistance = 1.0f;         // --focus-distance: the plane in focus, along the view direction
    std::uint32_t apertureBlades = 0;   // --aperture-blades: 0 a round aperture, 3 or more a polygon
    bool shutter = false;               // --shutter given: the scene posed by its animation
    double shutterOpen = 0.0;           // --shutter OPEN,CLOSE (seconds on the animation's timeline)
    double shutterClose = 0.0;
    std::string animation;              // --animation: its name or index; empty: the first
    // Whether the render needs the camera effects' shader variants: a lens,
    // or a shutter interval (motion blur).
    bool cameraEffects() const { return lensRadius > 0.0f || (shutter && shutterClose > shutterOpen); }
    bool aov = false;                   // --aov: the AOV sums as well (the aov axis; Film::aovSum);
                                        // the megakernel only
    // Adaptive sampling (render/adaptive.h): --noise-threshold (0: off; then
    // --spp is the cap) and --min-spp (0: kAdaptiveStep).
    double noiseThreshold = 0.0;
    std::uint32_t minSpp = 0;
    bool adaptive() const { return noiseThreshold > 0.0; }
};

// The loader's part of the settings: --shutter and --animation.
inline MotionOptions motionOptions(const RenderSettings& s) {
    return {s.shutter, s.animation, s.shutterOpen, s.shutterClose};
}

struct RenderTuning {
    std::uint32_t maxBatch = 64;        // samples per float32 device batch before folding
    double submitSeconds = 0.25;        // target wall time of one submission (sets how many
                                        // samples each carries; never changes the image)
    double maxSubmitSeconds = 2.0;      // with samplesPerDispatch > 1 a render that does not
                                        // split samples lets a submission grow towards
                                        // kDispatchSamples samples, up to this long
    std::uint32_t samplesPerDispatch = 64;  // the megakernel's most samples of a tile in one
                                        // dispatch (a submission's, one after another in each
                                        // invocation; the same image; at most 8 on a CPU
                                        // device, integrate/megakernel.cpp); 1: one each
    std::uint32_t tileSize = 512;       // a dispatch covers at most tileSize^2 pixels
    std::uint32_t fixedBatch = 0;       // samples per submission (cut at folds and checkpoints);
                                        // 0: adapt to submitSeconds
    bool splitSamples = false;          // a sample that takes longer than submitSeconds is
                                        // submitted a run of tiles at a time (strata view, whose
                                        // window answers between submissions; the same image)
    bool warmUp = false;                // one dispatch (a tile of at most 64x64 pixels, sample 0)
                                        // before the loop, timed apart and cleared from the image
    bool countRays = true;              // SPEC_COUNT_RAYS: closest/shadow ray counters
    WorkQueue workQueue = WorkQueue::Auto;  // SPEC_WORK_QUEUE (above)
    SceneLimits limits;                 // lower device limits to plan the scene against (0: the
                                        // device's; upload/device_scene.h)
    bool reusePipeline = true;          // share the compiled pipeline of an earlier render with the
                                        // same shader and constants (vk::Kernel's reuse; bench
                                        // turns it off to time pipeline creation)
};

// The vec4 per pixel of the device's sums: the image's, and the AOVs' with --aov.
inline std::uint32_t accumVec4PerPixel(const RenderSettings& s) {
    return gpu::kAccumVec4PerPixel + (s.aov ? gpu::kAovVec4PerPixel : 0u);
}

// Bytes of the image's sample sums on the device (one buffer).
inline std::uint64_t sampleSumBytes(const RenderSettings& s) {
    return std::uint64_t(s.width) * std::uint64_t(s.height) * accumVec4PerPixel(s) * 16u;
}

}  // namespace strata
