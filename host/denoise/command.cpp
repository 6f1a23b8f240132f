#include "denoise/command.h"

#include <cstdio>

#include "image/image_io.h"
#include "util/error.h"
#include "util/files.h"
#include "vk/check.h"
#include "vk/context.h"

namespace strata {

const char* denoiseMethodName(DenoiseMethod method) { return method == DenoiseMethod::Fast ? "fast" : "nfor"; }

DenoiseInput denoiseInput(const AovImages& a) {
    DenoiseInput in;
    in.width = a.width;
    in.height = a.height;
    in.color = a.color;
    in.halfA = a.halfA;
    in.halfB = a.halfB;
    in.variance = a.variance;
    in.albedo = a.albedo;
    in.normal = a.normal;
    in.depth = a.depth;
    in.emitter = a.emitter;
    in.albedoVariance = a.albedoVariance;
    in.normalVariance = a.normalVariance;
    in.depthVariance = a.depthVariance;
    return in;
}

void writeDenoised(const std::vector<std::string>& paths, const AovImages& aov, const std::vector<float>& denoised) {
    ExtraChannels extra;
    extra.add("noisy", "RGB", aov.color);
    extra.attributes = aov.attributes;
    const ExtraChannels layers = aovChannels(aov);
    extra.names.insert(extra.names.end(), layers.names.begin(), layers.names.end());
    extra.planes.insert(extra.planes.end(), layers.planes.begin(), layers.planes.end());
    writeImages(paths, aov.width, aov.height, denoised, extra);
}

int runDenoise(const DenoiseCommand& cmd) {
    for (const std::string& out : cmd.outputs) checkOutputPath(out);
    const AovImages aov = readAovImages(cmd.input);
    vk::Context ctx({cmd.device, cmd.validation});
    const DenoiseResult d = denoise(ctx, denoiseInput(aov), cmd.method);
    if (ctx.validation && vk::validationMessageCount() > 0)
        throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                              " Vulkan validation message(s) while denoising");
    writeDenoised(cmd.outputs, aov, d.rgb);
    if (!cmd.quiet) {
        std::fprintf(stderr, "strata: denoised %dx%d (%s) in %.3f s (device %.3f s; pipelines %.0f ms)\n", aov.width,
                     aov.height, denoiseMethodName(cmd.method), d.seconds, d.deviceSeconds, d.pipelineMs);
        for (const auto& out : cmd.outputs) std::fprintf(stderr, "strata: wrote %s\n", out.c_str());
    }
    return 0;
}

}  // namespace strata
