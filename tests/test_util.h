// Shared helpers for the render tests: one Vulkan context per test process
// (validation layers on when STRATA_VALIDATION is set, as ctest does), and
// the statistics used to compare renders with known answers.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstring>

#include <doctest/doctest.h>
#include <string>
#include <vector>

#include "bvh/scene_bvh.h"
#include "pack/gpu_scene.h"
#include "render/renderer.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "stages/stages.h"
#include "stats/stats.h"
#include "upload/device_scene.h"
#include "vk/context.h"

namespace strata::test {

inline std::string sourcePath(const std::string& rel) { return std::string(STRATA_SOURCE_DIR) + "/" + rel; }

inline vk::Context& context() {
    static vk::Context ctx(vk::ContextOptions{-1, vk::validationRequestedByEnvironment()});
    return ctx;
}

struct Rendered {
    Scene scene;
    GpuScene gpu;
    RenderResult result;
};

// The request of the stages (stages/stages.h) as `strata render` makes it
// for these settings, keeping the Scene and the GpuScene (Consume::None).
inline SceneRequest keptRequest(const RenderSettings& settings = {}, const RenderTuning& tuning = {}) {
    SceneRequest r = sceneRequest(settings, tuning);
    r.consume = Consume::None;
    return r;
}

// The BVH and packing stages of a render, as `strata render` runs them
// (without releasing the scene); `bvhWidth` chooses the tree traversed,
// `textureLod` whether textures get mip chains (the megakernel's default).
inline GpuScene buildAndPack(const Scene& scene, const BvhBuildOptions& options = {}, int bvhWidth = 4,
                             bool textureLod = true) {
    SceneRequest r = keptRequest();
    r.camera.reset();
    r.build = options;
    r.bvhWidth = bvhWidth;
    r.textureLod = textureLod;
    return prepareScene(r, scene).gpu;
}

// Uploads a packed scene as the settings ask and renders it. The BVH is the
// one `gpu` was packed for: settings.bvhWidth 2 needs a scene packed so.
inline RenderResult uploadAndRender(const GpuScene& gpu, const Camera& camera, const RenderSettings& settings,
                                    const RenderTuning& tuning = {}, const Checkpoints& checkpoints = {}) {
    REQUIRE_MESSAGE((settings.bvhWidth == 4 || gpu.bvhWidth == 2), "pack the scene for --bvh 2: buildAndPack(s, {}, 2)");
    const DeviceScene dev = uploadPrepared(context(), keptRequest(settings, tuning), gpu);
    return render(context(), dev, camera, settings, tuning, checkpoints);
}

// Packs (for settings.bvhWidth) and renders a loaded scene from its first
// camera. Every test scene renders without a single NaN/Inf sample.
inline RenderResult renderScene(const Scene& scene, const RenderSettings& settings, const RenderTuning& tuning = {}) {
    RenderResult r = uploadAndRender(buildAndPack(scene, {}, settings.bvhWidth), scene.cameras.at(0), settings, tuning);
    CHECK(r.nonFinite == 0);
    return r;
}

// Loads a scene file (its own lights, no --env), packs and renders it through
// the stages as `strata render` does, from the file's first camera.
inline Rendered renderFile(const std::string& relPath, const RenderSettings& settings, const RenderTuning& tuning = {}) {
    SceneRequest request = keptRequest(settings, tuning);
    request.file = sourcePath(relPath);
    HostScene host = prepareScene(request);
    REQUIRE(!host.scene.cameras.empty());
    Rendered r;
    r.result = render(context(), uploadPrepared(context(), request, host.gpu), host.camera, settings, tuning);
    r.scene = std::move(host.scene);
    r.gpu = std::move(host.gpu);
    CHECK(r.result.nonFinite == 0);
    return r;
}

// Settings whose box filter of radius 1e-5 pixels puts every sample at its
// pixel's centre (within 1e-6 of its uv on the scenes' planes).
inline RenderSettings centreSettings(int size, std::uint32_t spp, std::uint32_t maxDepth, std::uint32_t seed) {
    RenderSettings s;
    s.width = s.height = size;
    s.spp = spp;
    s.maxDepth = maxDepth;
    s.seed = seed;
    s.filter.radius = 1e-5f;
    return s;
}

// Fresnel reflectance of a dielectric (relative index eta) for unpolarised
// light at incidence cosine c (Born & Wolf).
inline double fresnelDielectric(double c, double eta) {
    const double s2 = (1.0 - c * c) / (eta * eta);
    if (s2 >= 1.0) return 1.0;
    const double t = std::sqrt(1.0 - s2);
    const double rs = (c - eta * t) / (c + eta * t), rp = (eta * c - t) / (eta * c + t);
    return 0.5 * (rs * rs + rp * rp);
}

// The camera ray through image point (x, y) in pixels, as pathtrace.comp makes it.
inline glm::dvec3 cameraRay(const Camera& cam, int w, int h, double x, double y) {
    const double tanHalf = std::tan(cam.yfov * 0.5);
    const double aspect = double(w) / h;
    const glm::dvec3 f(cam.forward), right = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
    const glm::dvec3 up = glm::cross(right, f);
    const double nx = 2.0 * x / w - 1.0, ny = 1.0 - 2.0 * y / h;
    return glm::normalize(f + nx * tanHalf * aspect * right + ny * tanHalf * up);
}

inline Scene loadWithWhiteEnvironment(const std::string& path) {
    EnvironmentOptions env;
    env.hasColor = true;
    env.color = glm::vec3(1.0f);
    return loadSceneWithEnvironment(path, env);
}

// Each channel's image mean of scene file `file` (16 x 16, 256 spp,
// maxDepth 1) in a uniform environment of radiance 1, and its standard
// error; the packed scene must have the feature bits `features`.
struct FurnaceMean {
    glm::dvec3 mean{0.0};
    glm::dvec3 se{0.0};
};

// Each channel's image mean of `film` and its standard error.
inline FurnaceMean imageMeans(const Film& film) {
    const auto m = film.mean();
    const auto v = film.varianceOfMean();
    const std::size_t n = m.size() / 3;
    FurnaceMean out;
    for (int c = 0; c < 3; ++c) {
        double sum = 0.0, var = 0.0;
        for (std::size_t i = 0; i < n; ++i) sum += m[i * 3 + c], var += v[i * 3 + c];
        out.mean[c] = sum / double(n);
        out.se[c] = std::sqrt(var) / double(n);
    }
    return out;
}

inline FurnaceMean whiteFurnaceMean(const std::string& file, std::uint32_t features) {
    const Scene scene = loadWithWhiteEnvironment(sourcePath(file));
    const GpuScene gpu = buildAndPack(scene);
    CHECK((gpu.features.bits & features) == features);
    RenderSettings s;
    s.width = s.height = 16;
    s.spp = 256;
    s.maxDepth = 1;
    const RenderResult r = uploadAndRender(gpu, scene.cameras.at(0), s);
    CHECK(r.nonFinite == 0);
    return imageMeans(r.film);
}

// The materials board under scenes/env/sky.hdr with a directional light
// added: every kind of light the environment code has.
inline Scene envBoardWithSun() {
    EnvironmentOptions env;
    env.file = sourcePath("scenes/env/sky.hdr");
    Scene scene = loadSceneWithEnvironment(sourcePath("scenes/materials-board-env.gltf"), env);
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
    scene.lights.push_back(sun);
    return scene;
}

// True when the two films' mean images are the same bits.
// `count` triangles, one per leaf, each `ratio` times the size and distance
// of the one before (the middle one at x = 1): a BVH about as deep as it
// gets, for the four-wide traversal's stack limits.
inline Scene triangleChain(int count, float ratio) {
    Scene chain;
    chain.path = "chain";
    chain.materials.push_back(MaterialDesc{});
    for (int i = 0; i < count; ++i) {
        const float x = std::pow(ratio, float(i - count / 2)), s = 0.3f * x;
        Triangle t;
        t.v[0] = {x, 0.0f, 0.0f};
        t.v[1] = {x + s, s, 0.0f};
        t.v[2] = {x, s, s};
        t.n[0] = t.n[1] = t.n[2] = glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
        chain.triangles.push_back(t);
    }
    return chain;
}

inline bool sameImage(const Film& a, const Film& b) {
    const auto x = a.mean(), y = b.mean();
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
}

// Mean over all pixels and channels of the image, and its estimated standard
// error from the per-pixel variances (pixels are independent).
struct ImageMean {
    double mean = 0.0;
    double stdError = 0.0;
};

inline ImageMean imageMean(const Film& film) {
    const auto m = film.mean();
    const auto v = film.varianceOfMean();
    double sum = 0.0, var = 0.0;
    for (std::size_t i = 0; i < m.size(); ++i) sum += m[i], var += v[i];
    const double n = static_cast<double>(m.size());
    // Channels of one pixel are correlated (same path); bound the variance of
    // their average by treating them as fully correlated: var(sum of 3) <= 9 var.
    return {sum / n, std::sqrt(3.0 * var) / n};
}

// Per pixel in `mask`: value and expected = mean of the three channels; sigma
// = mean of the channels' standard errors (bounds the standard error of the
// channel mean). Mean test of (value - expected) over the pixels at 4 standard
// errors (two-sided alpha 6.3e-5, pixels independent), and the count of
// pixels individually within 4.5 sigma (alpha 6.8e-6 each).
struct PixelCheck {
    stats::MeanTestResult mean;
    std::size_t pixels = 0, within = 0;
    double expectedMean = 0.0;
};

inline PixelCheck checkPixels(const RenderResult& r, const std::vector<double>& expected, const std::vector<char>& mask) {
    const auto m = r.film.mean();
    const auto v = r.film.varianceOfMean();
    std::vector<double> diff, var;
    PixelCheck c;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        if (!mask[i]) continue;
        double value = 0.0, sigma = 0.0;
        for (int k = 0; k < 3; ++k) {
            value += m[i * 3 + k] / 3.0;
            sigma += std::sqrt(static_cast<double>(v[i * 3 + k])) / 3.0;
        }
        diff.push_back(value - expected[i]);
        var.push_back(sigma * sigma);
        c.within += std::abs(value - expected[i]) <= 4.5 * sigma;
        c.expectedMean += expected[i];
    }
    c.pixels = diff.size();
    c.expectedMean /= static_cast<double>(std::max<std::size_t>(1, c.pixels));
    c.mean = stats::meanTest(diff, var, 0.0, 4.0);
    return c;
}

inline void report(const std::string& what, const PixelCheck& c) {
    MESSAGE(what << ": " << c.pixels << " pixels, expected mean " << c.expectedMean << ", mean difference "
                 << c.mean.mean << " +- " << c.mean.stdError << " (z " << c.mean.z << "), " << c.within
                 << " within 4.5 sigma");
    CHECK(c.pixels > 0);
    CHECK(c.mean.passed);
    CHECK(static_cast<double>(c.within) >= 0.99 * static_cast<double>(c.pixels));
}

// Camera rays of shaders/pathtrace.comp with the frame vectors of
// render/renderer.cpp, in double: through image position (sx, sy) in pixels,
// ndc = (2 sx / W - 1, 1 - 2 sy / H), dir = normalize(forward + ndc.x right
// tan(yfov / 2) aspect + ndc.y up tan(yfov / 2)), right = normalize(cross(
// forward, up)), up = cross(right, forward).
struct CameraRays {
    glm::dvec3 origin, forward, right, up;  // right and up scaled as above
    int width, height;
    CameraRays(const Camera& cam, int w, int h) : origin(cam.position), forward(cam.forward), width(w), height(h) {
        const double tanHalf = std::tan(0.5 * static_cast<double>(cam.yfov));
        const glm::dvec3 r = glm::normalize(glm::cross(forward, glm::dvec3(cam.up)));
        right = r * tanHalf * (static_cast<double>(w) / h);
        up = glm::cross(r, forward) * tanHalf;
    }
    glm::dvec3 dir(double sx, double sy) const {
        return glm::normalize(forward + (2.0 * sx / width - 1.0) * right + (1.0 - 2.0 * sy / height) * up);
    }
    // Centre of sub-pixel (i, j) of pixel (px, py) on a sub x sub grid (the
    // midpoint rule for the box filter of radius 0.5).
    glm::dvec3 subDir(int px, int py, int i, int j, int sub) const {
        return dir(px + (i + 0.5) / sub, py + (j + 0.5) / sub);
    }
};

}  // namespace strata::test
