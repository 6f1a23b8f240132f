#include "scene/environment.h"

#include <cmath>
#include <numbers>

#include "image/image_io.h"
#include "util/error.h"

namespace strata {

Environment makeEnvironment(const EnvironmentOptions& o) {
    Environment env;
    if (!o.given()) return env;
    env.enabled = true;
    env.rotation = static_cast<float>(static_cast<double>(o.rotateDegrees) * std::numbers::pi / 180.0);
    if (o.hasColor) {
        env.source = "--env-color";
        env.scale = o.color * o.intensity;
        return env;
    }
    env.source = o.file;
    env.scale = glm::vec3(o.intensity);
    RgbImage img = readRgb(o.file);
    if (img.width < 1 || img.height < 1) fail(o.file, "environment map has no texels");
    bool anyLight = false;
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        const float v = img.rgb[i];
        if (!std::isfinite(v) || v < 0.0f) {
            const std::size_t texel = i / 3;
            fail(o.file, "environment map texel (" + std::to_string(texel % img.width) + ", " +
                             std::to_string(texel / img.width) + ") has a " +
                             (std::isfinite(v) ? "negative" : "non-finite") + " value");
        }
        anyLight |= v > 0.0f;
    }
    if (!anyLight) fail(o.file, "environment map is black (every texel is 0); omit --env for no environment");
    env.width = img.width;
    env.height = img.height;
    env.rgb = std::move(img.rgb);
    return env;
}

Scene loadSceneWithEnvironment(const std::string& path, const EnvironmentOptions& options, LoadOptions load) {
    load.externalLight = options.given();
    Scene scene = loadGltf(path, load);
    scene.environment = makeEnvironment(options);
    return scene;
}

}  // namespace strata
