// `strata render`: load -> BVH -> pack -> upload -> render -> write, the
// one-way flow of docs/architecture.md, with the options of the command line.
#pragma once
#include <string>
#include <vector>

#include "pack/gpu_scene.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/environment.h"
#include "scene/view.h"

namespace strata {

struct RenderCommand {
    std::string scene;
    std::vector<std::string> outputs;   // .exr and/or .png
    RenderSettings settings;
    RenderTuning tuning;                // tests lower tuning.limits; the command line never sets it
    EnvironmentOptions env;             // --env / --env-color, --env-intensity, --env-rotate
    ViewOptions view;                   // --camera, --look-from, --look-at, --up, --fov
    std::string variant;                // --variant (KHR_materials_variants)
    Instancing instancing = Instancing::Auto;  // --instancing
    int device = -1;
    bool quiet = false;
    bool stats = false;
    std::string statsJson;
    bool validation = false;
    bool variance = false;              // EXR outputs get variance.R/G/B channels
    bool denoise = false;               // --denoise: R, G, B denoised (settings.aov is set too)
    bool denoiseFast = false;           // '--denoise fast': the a-trous filter, not the regression
};

// The BVH and packing stages as the commands run them, consuming the scene
// (packSceneAndRelease); `ms` receives their host time together.
GpuScene buildAndPackReleasing(Scene& scene, int bvhWidth, double& ms);

// Returns the process exit status. Throws strata::Error for bad input and
// vk::DeviceError for device failures; writes no output file on any error.
int runRender(const RenderCommand& cmd);

}  // namespace strata
