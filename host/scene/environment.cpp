#include "scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <utility>

#include "image/image_io.h"
#include "util/error.h"
#include "util/files.h"

namespace strata {

namespace {

// Radiance past the float range would make every sample that sees it Inf
// and be dropped: a black image.
void requireFloat(double radiance, const std::string& file, const std::string& what) {
    if (!(radiance <= double(std::numeric_limits<float>::max()))) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", radiance);
        fail(file, what + " is " + text + ", beyond the float range (3.4e+38)");
    }
}

// An enabled environment with the rotation of `o`, no radiance yet.
Environment colorlessEnvironment(const EnvironmentOptions& o) {
    Environment env;
    env.enabled = true;
    // Reduced to [0, 360) in double first, so whole turns change nothing and
    // a large angle is not carried to the float (1e39 would be inf).
    const double turn = std::fmod(o.rotateDegrees, 360.0);
    env.rotation = static_cast<float>((turn < 0.0 ? turn + 360.0 : turn) * std::numbers::pi / 180.0);
    return env;
}

}  // namespace

Environment makeEnvironment(const EnvironmentOptions& o) {
    if (!o.given()) return Environment{};
    if (o.hasColor) {
        Environment env = colorlessEnvironment(o);
        env.source = "--env-color";
        env.scale = o.color * o.intensity;
        const double brightest = std::max({double(o.color.r), double(o.color.g), double(o.color.b)});
        requireFloat(brightest * double(o.intensity), "strata", "--env-color times --env-intensity");
        return env;
    }
    if (!o.restrictPaths.empty()) {
        if (const std::string outside = outsideRoot(o.file, o.restrictPaths); !outside.empty())
            fail(o.file, "the environment map resolves to " + outside + ", outside --restrict-paths " + o.restrictPaths);
    }
    return environmentFromImage(o, readRgb(o.file));
}

Environment environmentFromImage(const EnvironmentOptions& o, RgbImage img) {
    Environment env = colorlessEnvironment(o);
    env.source = o.file;
    env.scale = glm::vec3(o.intensity);
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
    requireFloat(double(*std::max_element(img.rgb.begin(), img.rgb.end())) * double(o.intensity), o.file,
                 "the brightest texel times --env-intensity");
    env.width = img.width;
    env.height = img.height;
    env.rgb = std::move(img.rgb);
    return env;
}

namespace {

// `load` as loadSceneWithEnvironment gives it to loadGltf, and the map added.
template <class LoadGltf>
Scene withEnvironment(const EnvironmentOptions& options, LoadOptions load, const LoadGltf& loadGltfWith) {
    load.externalLight = options.given();
    Scene scene = loadGltfWith(load);
    EnvironmentOptions env = options;
    env.restrictPaths = load.restrictPaths;
    if (options.given()) scene.environment = makeEnvironment(env);
    return scene;
}

}  // namespace

Scene loadSceneWithEnvironment(const std::string& path, const EnvironmentOptions& options, LoadOptions load) {
    return withEnvironment(options, std::move(load), [&](const LoadOptions& l) { return loadGltf(path, l); });
}

Scene loadSceneWithEnvironment(const std::string& path, const std::vector<unsigned char>& bytes,
                               const EnvironmentOptions& options, LoadOptions load) {
    return withEnvironment(options, std::move(load), [&](const LoadOptions& l) { return loadGltf(path, bytes, l); });
}

}  // namespace strata
