// The stages of a render before the progressive loop, run in one place:
// load -> camera -> BVH -> pack (the host part, prepareScene) and upload
// (uploadPrepared: `strata render` opens the device between the two, after
// checking a --resume state). Every command, the fuzz targets and the tests'
// helpers describe what they want as one SceneRequest; each choice in it is
// acted on by one stage (docs/architecture.md, the one-way flow).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bvh/scene_bvh.h"
#include "pack/gpu_scene.h"
#include "settings/settings.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "scene/view.h"
#include "upload/device_scene.h"
#include "vk/context.h"

namespace strata {

// Which stages consume their input: each array's pages are handed back as
// soon as the next stage has copied it (docs/architecture.md).
enum class Consume {
    None,   // packScene, uploadScene: the Scene and the GpuScene stay as they were (tests, converge)
    Scene,  // packSceneAndRelease, then uploadScene: the GpuScene stays, to be uploaded again (bench)
    All,    // packSceneAndRelease, uploadAndRelease: host memory never holds the scene twice (render)
};

// The camera stage's choice (chooseCamera, scene/view.h).
struct CameraChoice {
    ViewOptions view;  // --camera, --look-from, --look-at, --up, --fov
    int width = 512, height = 512;  // the image: its aspect frames a scene without a camera
};

struct SceneRequest {
    // Load: the file (or its bytes, already read: the fuzz targets), the
    // command line's environment, and the loader's options (variant,
    // restrictPaths canonical, instancing, motion with frames, host memory).
    std::string file;
    std::optional<std::vector<unsigned char>> bytes;
    EnvironmentOptions env;
    LoadOptions load;
    // Camera: none where the caller frames the scene itself (bench) or has
    // its camera (tests); HostScene::camera is then the default Camera.
    std::optional<CameraChoice> camera;
    // BVH: the build's options, the width asked for (--bvh 2 or 4: packing
    // decides the tree traversed, GpuScene::bvhWidth) and the four-wide
    // traversal's stack (--bvh-stack: the upload's).
    BvhBuildOptions build;
    int bvhWidth = 4;
    BvhStack stack = BvhStack::Auto;
    // Pack: whether the light tree is built (--light-sampler), the largest
    // texture side kept (--texture-max-size; 0: every texture whole), and
    // whether textures get mip chains (--texture-lod; the megakernel only).
    LightSampler lights = LightSampler::Auto;
    std::uint32_t textureMaxSize = 0;
    bool textureLod = true;
    // Upload: the reads (--reads), lowered device limits (tests), and the
    // image's sample sums counted beside the scene against device memory.
    ReadMode reads = ReadMode::Auto;
    SceneLimits limits;
    std::uint64_t imageBytes = 0;
    Consume consume = Consume::All;
    // --frames: Scene::instances (which packing releases) and the bottom
    // levels' roots are kept, so that each frame can pose them again.
    bool keepPlacements = false;
};

// What the host part hands on: the scene (with Consume::Scene or All its
// geometry released; with keepPlacements its instances kept), the camera,
// the packed scene, and the host times that the commands report.
struct HostScene {
    Scene scene;
    Camera camera;
    GpuScene gpu;
    std::vector<BottomLevel> bottoms;  // SceneBvh::bottoms, with keepPlacements
    double loadMs = 0.0;  // loading (with the environment map)
    double packMs = 0.0;  // the BVH build and the packing together
};

// The request of a render with these settings: the camera's image size, the
// loader's motion options (--shutter, --animation), --bvh, --bvh-stack,
// --reads, tuning.limits and the image's sample sums (sampleSumBytes).
SceneRequest sceneRequest(const RenderSettings& settings, const RenderTuning& tuning = {});

// The load stage: loadSceneWithEnvironment of the file or its bytes.
Scene loadScene(const SceneRequest& request);

// The camera stage: chooseCamera with request.camera (which must be set).
Camera requestedCamera(const SceneRequest& request, const Scene& scene);

// The host part: load -> camera -> BVH -> pack.
HostScene prepareScene(const SceneRequest& request);
// The same from a scene already loaded (or made: tests): camera -> BVH -> pack.
HostScene prepareScene(const SceneRequest& request, Scene scene);

// The upload's options: request.reads, stack, limits and imageBytes.
UploadOptions uploadOptions(const SceneRequest& request);

// The upload part: with Consume::All, uploadAndRelease (the GpuScene keeps
// what the report reads); else uploadScene. A const GpuScene is never
// released.
DeviceScene uploadPrepared(const vk::Context& ctx, const SceneRequest& request, GpuScene& gpu);
DeviceScene uploadPrepared(const vk::Context& ctx, const SceneRequest& request, const GpuScene& gpu);

}  // namespace strata
