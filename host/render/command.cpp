#include "render/command.h"

#include <chrono>
#include <cstdio>
#include <fstream>

#include "denoise/command.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "bvh/scene_bvh.h"
#include "pack/gpu_scene.h"
#include "render/sampler_kind.h"
#include "render/report.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "util/error.h"
#include "util/files.h"
#include "vk/check.h"
#include "vk/context.h"

namespace strata {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

GpuScene buildAndPackReleasing(Scene& scene, int bvhWidth, double& ms) {
    const auto t0 = std::chrono::steady_clock::now();
    SceneBvh bvh = buildSceneBvh(scene);
    GpuScene gpu = packSceneAndRelease(scene, std::move(bvh), bvhWidth);
    ms = msSince(t0);
    return gpu;
}

int runRender(const RenderCommand& cmd) {
    for (const auto& out : cmd.outputs) outputFormat(out);  // reject bad input before any work
    for (const auto& out : cmd.outputs) requireImageSupport(out);
    for (const auto& out : cmd.outputs) checkOutputPath(out);
    if (!cmd.statsJson.empty()) checkOutputPath(cmd.statsJson);
    checkSamplerSettings(samplerByKind(cmd.settings.sampler), cmd.settings.spp, cmd.settings.width,
                         cmd.settings.height);

    auto t0 = std::chrono::steady_clock::now();
    LoadOptions load;
    load.variant = cmd.variant;
    load.instancing = cmd.instancing;
    Scene scene = loadSceneWithEnvironment(cmd.scene, cmd.env, load);
    const double loadMs = msSince(t0);
    const Camera camera = chooseCamera(scene, cmd.view, int(cmd.settings.width), int(cmd.settings.height));

    double packMs = 0.0;  // the BVH build and the packing
    GpuScene gpu = buildAndPackReleasing(scene, cmd.settings.bvhWidth, packMs);
    const auto t1 = std::chrono::steady_clock::now();
    vk::Context ctx({cmd.device, cmd.validation});
    const double deviceMs = msSince(t1);
    if (!cmd.quiet)
        std::fprintf(stderr, "strata: device %u: %s (%s, %s)\n", ctx.info.index, ctx.info.name.c_str(),
                     ctx.info.type.c_str(), ctx.info.driver.c_str());

    const DeviceScene dev = uploadAndRelease(ctx, gpu, uploadOptions(cmd.settings, cmd.tuning));
    RenderResult result = render(ctx, dev, camera, cmd.settings, cmd.tuning);

    StatsInput in{&ctx, &scene, &gpu, &cmd.settings, &result, loadMs, packMs, deviceMs};
    nlohmann::json stats = statsJson(in);
    if (ctx.validation && vk::validationMessageCount() > 0)
        throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                              " Vulkan validation message(s) during the render");

    // The statistics first, taken back if an image cannot be written: all
    // outputs or none.
    if (!cmd.statsJson.empty()) writeTextAtomically(cmd.statsJson, stats.dump(2) + "\n");
    try {
        if (cmd.denoise) {
            const AovImages aov = aovImages(result.film);
            const DenoiseMethod method = cmd.denoiseFast ? DenoiseMethod::Fast : DenoiseMethod::Nfor;
            const DenoiseResult d = denoise(ctx, denoiseInput(aov), method);
            if (ctx.validation && vk::validationMessageCount() > 0)
                throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                                      " Vulkan validation message(s) while denoising");
            writeDenoised(cmd.outputs, aov, d.rgb);
            if (!cmd.quiet)
                std::fprintf(stderr, "strata: denoised (%s) in %.3f s (device %.3f s)\n", denoiseMethodName(method),
                             d.seconds, d.deviceSeconds);
        } else if (cmd.settings.aov) {
            const AovImages aov = aovImages(result.film);
            writeImages(cmd.outputs, cmd.settings.width, cmd.settings.height, aov.color, aovChannels(aov));
        } else if (cmd.variance) {
            ExtraChannels var;
            var.add("variance", "RGB", result.film.varianceOfMean());
            writeImages(cmd.outputs, cmd.settings.width, cmd.settings.height, result.film.mean(), var);
        } else {
            writeImages(cmd.outputs, cmd.settings.width, cmd.settings.height, result.film.mean());
        }
    } catch (...) {
        if (!cmd.statsJson.empty()) std::remove(cmd.statsJson.c_str());
        throw;
    }
    if (cmd.stats) std::fputs(statsText(stats).c_str(), stdout);
    if (result.nonFinite > 0)
        warn(cmd.scene, std::to_string(result.nonFinite) + " of " +
                            std::to_string(std::uint64_t(result.spp) * cmd.settings.width * cmd.settings.height) +
                            " samples were NaN or Inf and were left out of the image");
    if (!cmd.quiet)
        for (const auto& out : cmd.outputs) std::fprintf(stderr, "strata: wrote %s\n", out.c_str());
    return 0;
}

}  // namespace strata
