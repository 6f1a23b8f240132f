#include "stages/stages.h"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "util/error.h"

namespace strata {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SceneRequest sceneRequest(const RenderSettings& settings, const RenderTuning& tuning) {
    SceneRequest r;
    r.load.motion = motionOptions(settings);
    r.camera = CameraChoice{{}, settings.width, settings.height};
    r.bvhWidth = settings.bvhWidth;
    r.lights = settings.lightSampler;
    r.textureLod = settings.textureLod;
    r.stack = settings.bvhStack;
    r.reads = settings.reads;
    r.limits = tuning.limits;
    r.imageBytes = sampleSumBytes(settings);
    return r;
}

Scene loadScene(const SceneRequest& request) {
    HeldWarnings held;  // printed once the scene has loaded, dropped on an error
    Scene scene = request.bytes ? loadSceneWithEnvironment(request.file, *request.bytes, request.env, request.load)
                                : loadSceneWithEnvironment(request.file, request.env, request.load);
    held.release();
    return scene;
}

Camera requestedCamera(const SceneRequest& request, const Scene& scene) {
    if (!request.camera) throw std::logic_error("requestedCamera: the request chooses no camera");
    return chooseCamera(scene, request.camera->view, request.camera->width, request.camera->height);
}

HostScene prepareScene(const SceneRequest& request) {
    HeldWarnings held;  // the loader's and the packer's, until both are done
    const auto t0 = std::chrono::steady_clock::now();
    Scene scene = loadScene(request);
    const double loadMs = msSince(t0);
    HostScene h = prepareScene(request, std::move(scene));
    h.loadMs = loadMs;
    held.release();
    return h;
}

HostScene prepareScene(const SceneRequest& request, Scene scene) {
    HostScene h;
    h.scene = std::move(scene);
    if (request.camera) h.camera = requestedCamera(request, h.scene);
    const auto t0 = std::chrono::steady_clock::now();
    SceneBvh bvh = buildSceneBvh(h.scene, request.build);
    if (request.keepPlacements) h.bottoms = bvh.bottoms;
    if (request.consume == Consume::None) {
        h.gpu = packScene(h.scene, std::move(bvh), request.bvhWidth, request.lights,
                          {request.textureMaxSize, request.textureLod});
    } else {
        // Packing releases the placements with the triangles; a sequence of
        // frames poses them again.
        std::vector<MeshInstance> instances;
        if (request.keepPlacements) instances = h.scene.instances;
        h.gpu = packSceneAndRelease(h.scene, std::move(bvh), request.bvhWidth, request.lights,
                                    {request.textureMaxSize, request.textureLod});
        if (request.keepPlacements) h.scene.instances = std::move(instances);
    }
    h.packMs = msSince(t0);
    return h;
}

UploadOptions uploadOptions(const SceneRequest& request) {
    return {request.reads, request.stack, request.limits, request.imageBytes};
}

DeviceScene uploadPrepared(const vk::Context& ctx, const SceneRequest& request, GpuScene& gpu) {
    fitTextures(ctx, gpu, uploadOptions(request));
    if (request.consume == Consume::All) return uploadAndRelease(ctx, gpu, uploadOptions(request));
    return uploadScene(ctx, gpu, uploadOptions(request));
}

DeviceScene uploadPrepared(const vk::Context& ctx, const SceneRequest& request, const GpuScene& gpu) {
    return uploadScene(ctx, gpu, uploadOptions(request));
}

}  // namespace strata
