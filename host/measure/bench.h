// `strata bench`: the speed of strata on one scene, in four sections, with
// warm-up excluded and device time from Vulkan timestamps:
//
// - traversal: the shader BVH on the ray sets of the Embree peer benchmark
//   (shared/peers/embree-rays), so the two run side by side: primary rays
//   through pixel centres, one cosine-distributed diffuse bounce from each
//   primary hit (the peer's PCG RXS-M-XS draws and frame), and occlusion rays
//   from each primary hit to the top centre of the scene bounds;
// - path tracing: the renderer itself, Msamples/s, rays/s from the shader's
//   ray counters, mean path length, relMSE against --reference (speed is
//   never reported without its error when a reference exists);
// - dispatch throughput: one-sample dispatches at 64^2 .. 2048^2, and the
//   effect of recording 1, 8 or 64 of them per submission;
// - start-up (load, BVH build, pipeline creation, first dispatch) and the
//   BVH and the scene's enabled features.
#pragma once
#include "scene/scene.h"
#include <cstdint>
#include <string>

#include "upload/device_scene.h"
#include "render/renderer.h"
#include "scene/environment.h"
#include "scene/view.h"

namespace strata {

// The peer's image size (1024x768) and 4 spp for the path-tracing section;
// the rest as `strata render`.
inline RenderSettings benchDefaults() {
    RenderSettings s;
    s.width = 1024;
    s.height = 768;
    s.spp = 4;
    return s;
}

struct BenchCommand {
    std::string scene;
    RenderSettings settings = benchDefaults();  // size, spp, seed, max depth, BVH, reads,
                                                // stack, integrator (the flags render has)
    int reps = 5;                     // timed passes per ray set (median)
    ViewOptions view;                   // --camera, --look-from, --look-at, --up, --fov
    std::string variant;                // --variant (KHR_materials_variants)
    std::string restrictPaths;          // --restrict-paths DIR (as given)
    Instancing instancing = Instancing::Auto;  // --instancing
    std::uint32_t textureMaxSize = 0;   // --texture-max-size (0: every texture whole)
    int device = -1;
    std::string reference;            // EXR of the same size: relMSE of the path-tracing image
    EnvironmentOptions env;           // --env / --env-color, --env-intensity, --env-rotate (as render)
    bool quick = false;               // small dispatch section, for tests
    std::string only;                 // "traversal": start-up, BVH and traversal sections only
    std::string json;
    bool validation = false;
};

// `cmd` as the command line parsed and checked it (cli/checks.h): what
// the flags alone decide is not checked again.
int runBench(const BenchCommand& cmd);

}  // namespace strata
