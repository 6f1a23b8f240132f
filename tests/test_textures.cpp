// glTF textures: known answers rendered by the real shaders (lavapipe,
// validation on), plus CPU checks of texture-coordinate decoding and tangent
// generation. Scenes: tests/data/textures/, written by
// scripts/make_texture_scenes.py, whose constants are mirrored here.
//
// "Direct" scenes are seen at max depth 0 with a box filter of radius 1e-5
// pixels, so every sample sees the pixel centre's uv (within 1e-6) and a
// pixel is exactly emissiveFactor x the decoded texture there.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>

#include "pack/textures.h"
#include "render/report.h"
#include "measure/tracer.h"
#include "scene/tangents.h"
#include "stats/stats.h"
#include "settings/filter.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

const std::string kDir = "tests/data/textures/";
constexpr glm::dvec3 kEmissive{1.0, 0.5, 0.25};
// 4 x 2 sRGB texels, rows top to bottom (checker.png).
constexpr int kChecker[2][4][3] = {{{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}},
                                   {{10, 20, 30}, {128, 64, 200}, {40, 200, 90}, {0, 0, 0}}};
// 3 x 2 16-bit texels (rgb; alpha 65535).
constexpr int kChecker16[2][3][3] = {{{65535, 0, 1000}, {300, 40000, 65535}, {12345, 54321, 7}},
                                     {{0, 0, 0}, {65535, 65535, 65535}, {32768, 16384, 49152}}};

enum class WrapMode { Repeat, Clamp, Mirror };

// OpenGL 4.6 sec. 8.14.2, written independently of the shader.
int wrapIndex(int i, int n, WrapMode mode) {
    if (mode == WrapMode::Clamp) return std::clamp(i, 0, n - 1);
    if (mode == WrapMode::Mirror) {
        const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
        return m < n ? m : 2 * n - 1 - m;
    }
    return ((i % n) + n) % n;
}

glm::dvec3 checkerTexel(int x, int y) {
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) c[k] = srgbToLinear(kChecker[y][x][k] / 255.0);
    return c;
}

// Nearest lookup of checker.png: the texel, and the distance (in texels) of
// uv from the nearest texel boundary.
glm::dvec3 checkerNearest(glm::dvec2 uv, WrapMode s, WrapMode t, double* boundary = nullptr) {
    const glm::dvec2 x = uv * glm::dvec2(4.0, 2.0);
    if (boundary) {
        const glm::dvec2 f = x - glm::floor(x);
        *boundary = std::min({f.x, 1.0 - f.x, f.y, 1.0 - f.y});
    }
    return checkerTexel(wrapIndex(static_cast<int>(std::floor(x.x)), 4, s),
                        wrapIndex(static_cast<int>(std::floor(x.y)), 2, t));
}

glm::dvec3 checkerBilinear(glm::dvec2 uv, WrapMode s, WrapMode t) {
    const glm::dvec2 c = uv * glm::dvec2(4.0, 2.0) - 0.5;
    const glm::dvec2 b = glm::floor(c), f = c - b;
    auto at = [&](int dx, int dy) {
        return checkerTexel(wrapIndex(static_cast<int>(b.x) + dx, 4, s),
                            wrapIndex(static_cast<int>(b.y) + dy, 2, t));
    };
    return glm::mix(glm::mix(at(0, 0), at(1, 0), f.x), glm::mix(at(0, 1), at(1, 1), f.x), f.y);
}

RenderSettings centreSettings(int size, std::uint32_t spp, std::uint32_t maxDepth, std::uint32_t seed) {
    RenderSettings s;
    s.width = s.height = size;
    s.spp = spp;
    s.maxDepth = maxDepth;
    s.seed = seed;
    s.filter.radius = 1e-5f;
    return s;
}

struct DirectCheck {
    double maxRelError = 0.0;
    std::size_t skipped = 0;  // pixels whose centre is within 1e-5 texel of a texel boundary
};

// Renders a direct scene and compares every pixel with `expected(s, t)`, the
// radiance at pixel centre (s, t) in [0, 1]^2; returns the largest relative
// error max |r - e| / max(e, 1e-3) over channels.
DirectCheck checkDirect(const std::string& file, int size,
                        const std::function<glm::dvec3(glm::dvec2, double*)>& expected) {
    const Rendered r = renderFile(kDir + file, centreSettings(size, 4, 0, 3));
    const auto mean = r.result.film.mean();
    DirectCheck out;
    for (int py = 0; py < size; ++py) {
        for (int px = 0; px < size; ++px) {
            double boundary = 1.0;
            const glm::dvec2 st((px + 0.5) / size, (py + 0.5) / size);
            const glm::dvec3 e = expected(st, &boundary);
            // Samples lie within 1e-5 px of the centre: < 5e-6 texel here.
            if (boundary < 1e-5) {
                ++out.skipped;
                continue;
            }
            for (int c = 0; c < 3; ++c) {
                const double v = mean[(static_cast<std::size_t>(py) * size + px) * 3 + c];
                out.maxRelError = std::max(out.maxRelError, std::abs(v - e[c]) / std::max(e[c], 1e-3));
            }
        }
    }
    return out;
}

// uv of the direct scenes' quad: UV0 + (s, t) * span.
glm::dvec2 quadUv(glm::dvec2 st, glm::dvec2 uv0, glm::dvec2 span) { return uv0 + st * span; }

}  // namespace

TEST_CASE("texture: an emissive checker seen directly is emissiveFactor x the sRGB-decoded texel") {
    const DirectCheck d = checkDirect("nearest.gltf", 24, [](glm::dvec2 st, double* b) {
        return kEmissive * checkerNearest(st, WrapMode::Repeat, WrapMode::Repeat, b);
    });
    CAPTURE(d.maxRelError);
    CHECK(d.skipped == 0);
    CHECK(d.maxRelError < 1e-5);  // float32 pow/unpack against the double curve

    const DirectCheck d16 = checkDirect("nearest-16bit.gltf", 24, [](glm::dvec2 st, double* b) {
        const glm::dvec2 x = st * glm::dvec2(3.0, 2.0);
        const glm::dvec2 f = x - glm::floor(x);
        *b = std::min({f.x, 1.0 - f.x, f.y, 1.0 - f.y});
        glm::dvec3 c;
        for (int k = 0; k < 3; ++k)
            c[k] = srgbToLinear(kChecker16[static_cast<int>(x.y)][static_cast<int>(x.x)][k] / 65535.0);
        return kEmissive * c;
    });
    CAPTURE(d16.maxRelError);
    CHECK(d16.skipped == 0);
    CHECK(d16.maxRelError < 1e-5);  // 16-bit PNG: decoded to 16 bits, not 8
    CHECK(vk::validationMessageCount() == 0);
}

// --texture-max-size 2 halves checker.png (4 x 2) to 2 x 1: each texel the
// mean of its 2 x 2 block in linear light, stored in sRGB again (8 bits).
TEST_CASE("texture: --texture-max-size halves a texture in linear light, the render reads the smaller one") {
    SceneRequest request = keptRequest(centreSettings(24, 4, 0, 3));
    request.file = sourcePath(kDir + "nearest.gltf");
    request.textureMaxSize = 2;
    HostScene host = prepareScene(request);
    REQUIRE(host.gpu.images.size() == 1);
    CHECK(host.gpu.images[0].width == 2);
    CHECK(host.gpu.images[0].height == 1);
    CHECK(host.gpu.images[0].fileWidth == 4);
    CHECK(host.gpu.images[0].levels == 2);       // and its 1x1 mip level (--texture-lod on)
    CHECK(host.gpu.images[0].bytes == (2 + 1) * 4);
    const RenderResult r = render(context(), uploadPrepared(context(), request, host.gpu), host.camera,
                                  centreSettings(24, 4, 0, 3));
    auto halfTexel = [](int x) {
        glm::dvec3 c(0.0);
        for (int y = 0; y < 2; ++y)
            for (int dx = 0; dx < 2; ++dx) c += 0.25 * checkerTexel(2 * x + dx, y);
        for (int k = 0; k < 3; ++k) {  // stored as 8-bit sRGB again
            const double v = c[k] <= 0.0031308 ? c[k] * 12.92 : 1.055 * std::pow(c[k], 1.0 / 2.4) - 0.055;
            c[k] = srgbToLinear(std::round(v * 255.0) / 255.0);
        }
        return c;
    };
    const auto mean = r.film.mean();
    double worst = 0.0;
    std::size_t compared = 0;
    for (int py = 0; py < 24; ++py)
        for (int px = 0; px < 24; ++px) {
            const glm::dvec2 st((px + 0.5) / 24, (py + 0.5) / 24);
            const double x = st.x * 2.0;  // the quad's uv spans [0, 1]: nearest texel of the 2 x 1 image
            if (std::abs(x - std::round(x)) < 1e-5) continue;
            const glm::dvec3 e = kEmissive * halfTexel(static_cast<int>(x) % 2);
            for (int c = 0; c < 3; ++c) {
                const double v = mean[(static_cast<std::size_t>(py) * 24 + px) * 3 + c];
                worst = std::max(worst, std::abs(v - e[c]) / std::max(e[c], 1e-3));
            }
            ++compared;
        }
    CAPTURE(worst);
    CHECK(compared > 500);
    CHECK(worst < 1e-5);
    CHECK(vk::validationMessageCount() == 0);
}

// The materials board's three 64x64 textures (48 KiB of words) on a device
// whose texel view holds 4096 texels (16 KiB): each is halved once, the
// largest first, and the render is --texture-max-size 32's, bit for bit.
TEST_CASE("texture: textures past a texel view's range are halved to fit, as --texture-max-size would") {
    RenderSettings s = centreSettings(24, 2, 2, 1);
    RenderTuning lowered;
    lowered.limits.texelElements = 4096;
    SceneRequest request = keptRequest(s, lowered);
    request.file = sourcePath("scenes/materials-board.gltf");
    HostScene host = prepareScene(request);
    REQUIRE(host.gpu.images.size() == 3);
    const RenderResult fitted = render(context(), uploadPrepared(context(), request, host.gpu), host.camera, s, lowered);
    for (const PackedImage& p : host.gpu.images) {
        CHECK(p.width == 32);
        CHECK(p.fileWidth == 64);
    }
    CHECK(host.gpu.texels.size() * 4 <= 4096 * 4);
    SceneRequest halved = keptRequest(s);
    halved.file = request.file;
    halved.textureMaxSize = 32;
    HostScene small = prepareScene(halved);
    const RenderResult expected = render(context(), uploadPrepared(context(), halved, small.gpu), small.camera, s);
    CHECK(sameImage(fitted.film, expected.film));
    // Without the lowered range nothing is halved.
    SceneRequest whole = keptRequest(s);
    whole.file = request.file;
    HostScene full = prepareScene(whole);
    (void)uploadPrepared(context(), whole, full.gpu);
    for (const PackedImage& p : full.gpu.images) CHECK(p.width == 64);
    CHECK(vk::validationMessageCount() == 0);
}

// receding.gltf at max depth 0 (the floor's emission seen directly), 64x64,
// 4 spp: rows 22-40 lie on the floor, minified by about 2 to 100 texels a
// pixel. Texture LOD reads the checker's mean grey there instead of single
// black and white texels: the same mean over the region (4 standard
// errors), and a per-sample variance at least 10 times lower.
TEST_CASE("texture: LOD on a receding checker: the same mean, at least 10x less variance a sample") {
    RenderSettings s;
    s.width = s.height = 64;
    s.spp = 4;
    s.maxDepth = 0;
    s.seed = 5;
    struct Region {
        double mean = 0.0, stdError = 0.0, variance = 0.0;
    };
    auto region = [&](bool lod) {
        s.textureLod = lod;
        const Rendered r = renderFile(kDir + "receding.gltf", s);
        CHECK(((r.gpu.features.bits & gpu::kFeatureTextureLod) != 0u) == lod);
        const auto mean = r.result.film.mean(), var = r.result.film.varianceOfMean();
        Region out;
        std::size_t n = 0;
        double varOfSum = 0.0;
        for (int y = 22; y <= 40; ++y)
            for (int x = 0; x < 64; ++x) {
                const std::size_t i = (std::size_t(y) * 64 + std::size_t(x)) * 3;  // green: the channels are equal
                out.mean += mean[i + 1];
                varOfSum += var[i + 1];
                out.variance += var[i + 1] * s.spp;
                ++n;
            }
        out.mean /= double(n);
        out.stdError = std::sqrt(varOfSum) / double(n);
        out.variance /= double(n);
        return out;
    };
    const Region on = region(true), off = region(false);
    MESSAGE("mean " << on.mean << " +- " << on.stdError << " with LOD, " << off.mean << " +- " << off.stdError
                    << " without; variance a sample " << on.variance << " against " << off.variance << " ("
                    << off.variance / on.variance << "x)");
    CHECK(std::abs(on.mean - off.mean) <= 4.0 * std::sqrt(on.stdError * on.stdError + off.stdError * off.stdError));
    CHECK(off.variance >= 10.0 * on.variance);
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// Texture LOD's level, measured: a scene whose texture is a checker of
// single texels (1/32 world units), 32x32 pixels, samples [first, first +
// 16) of the pixels. Where sample s asks for a level lambda_s in (0, 1) a
// lookup reads level 0 with probability 1 - lambda_s and level 1, the
// checker's uniform grey, otherwise: so a pixel's variance a sample is 1 -
// the mean of clamp(lambda_s, 0, 1) times the variance without LOD.
// `analytic(direction)` gives a camera ray's footprint level: log2 of the
// pixel angle x the cone's length / texel (the footprint's minor axis: no
// 1/|cos|), NaN off the measured part; lambda_s adds sample s's bias.
// Returns the level measured, 1 - sum(var on) / sum(var off), and the mean
// expected one over the pixels whose expected level is in [0.15, 0.85].
struct MeasuredLevel {
    double measured = 0.0, analytic = 0.0;
    std::size_t pixels = 0;
};

// Sample s's level bias, as lib/material.glsl lodBiasForSample gives it.
double lodBiasForSample(std::uint32_t s) {
    return std::max(double(gpu::kLodBiasMin),
                    double(gpu::kLodBiasFirst) - double(gpu::kLodBiasPerDoubling) * std::log2(double(s) + 1.0));
}

constexpr std::uint32_t kLevelSamples = 16;

MeasuredLevel measureLevel(const std::string& file, RenderSettings s, const ViewOptions& view,
                           const std::function<double(const CameraRays&, double, glm::dvec3)>& analytic,
                           std::uint32_t first = 0) {
    s.width = s.height = 32;
    s.spp = first + kLevelSamples;
    SampleRun run;
    run.begin = first;
    std::vector<double> variance[2];
    Camera camera;
    for (int lod = 0; lod < 2; ++lod) {
        s.textureLod = lod == 1;
        SceneRequest request = keptRequest(s);
        request.file = sourcePath(kDir + file);
        request.camera->view = view;
        HostScene host = prepareScene(request);
        camera = host.camera;
        const RenderResult r =
            render(context(), uploadPrepared(context(), request, host.gpu), host.camera, s, {}, {}, run);
        const auto v = r.film.varianceOfMean();
        for (std::size_t i = 0; i < 32 * 32; ++i) variance[lod].push_back(v[i * 3 + 1] * kLevelSamples);
    }
    const CameraRays rays(camera, 32, 32);
    const double spread = 2.0 * std::tan(0.5 * double(camera.yfov)) / 32.0;
    MeasuredLevel out;
    double on = 0.0, off = 0.0;
    for (int py = 0; py < 32; ++py)
        for (int px = 0; px < 32; ++px) {
            const double footprint = analytic(rays, spread, rays.dir(px + 0.5, py + 0.5));
            double lambda = 0.0;
            for (std::uint32_t k = first; k < first + kLevelSamples; ++k)
                lambda += std::clamp(footprint + lodBiasForSample(k), 0.0, 1.0) / kLevelSamples;
            if (!(lambda >= 0.15 && lambda <= 0.85)) continue;
            const std::size_t i = std::size_t(py) * 32 + std::size_t(px);
            on += variance[1][i];
            off += variance[0][i];
            out.analytic += lambda;
            ++out.pixels;
        }
    out.analytic /= double(std::max<std::size_t>(out.pixels, 1));
    out.measured = 1.0 - on / off;
    return out;
}

}  // namespace

// lod-plane.gltf at max depth 0, seen from 4.5 and 5.9 away and at 40
// degrees: the level measured within a quarter of the analytic one.
TEST_CASE("texture: LOD reads the level of the ray cone's footprint on a plane (distances and an angle)") {
    struct View {
        glm::vec3 from;
        std::string what;
    };
    for (const View& view : {View{{0.0f, 0.0f, 4.5f}, "4.5 away"}, View{{0.0f, 0.0f, 5.9f}, "5.9 away"},
                             View{{0.0f, -3.0f, 3.6f}, "40 degrees"}}) {
        CAPTURE(view.what);
        RenderSettings s;
        s.maxDepth = 0;
        s.seed = 9;
        ViewOptions v;
        v.lookFrom = view.from;
        v.lookAt = glm::vec3(0.0f);
        v.fovDegrees = 20.0f;
        const MeasuredLevel m =
            measureLevel("lod-plane.gltf", s, v, [](const CameraRays& rays, double spread, glm::dvec3 d) {
                const double t = -rays.origin.z / d.z;  // the plane z = 0
                return std::log2(spread * t * 32.0);
            });
        MESSAGE(view.what << ": level " << m.measured << " measured, " << m.analytic << " analytic (" << m.pixels
                          << " pixels)");
        REQUIRE(m.pixels >= 200);
        CHECK(std::abs(m.measured - m.analytic) <= 0.25);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// The level's bias follows the sample index (lodBiasForSample): samples
// 64-79 read about 1.3 levels sharper than the footprint. From 9.4 away the
// footprint is about 1.75 levels: those samples read a level near 0.45,
// where a fixed bias of half a level (this test's failure when the index
// is ignored) would read level 1 and above, the checker's grey (1).
TEST_CASE("texture: LOD's level bias follows the sample index: later samples read sharper levels") {
    RenderSettings s;
    s.maxDepth = 0;
    s.seed = 3;
    ViewOptions v;
    v.lookFrom = glm::vec3(0.0f, 0.0f, 9.4f);
    v.lookAt = glm::vec3(0.0f);
    v.fovDegrees = 20.0f;
    const MeasuredLevel m = measureLevel(
        "lod-plane.gltf", s, v,
        [](const CameraRays& rays, double spread, glm::dvec3 d) {
            const double t = -rays.origin.z / d.z;
            return std::log2(spread * t * 32.0);
        },
        64);
    MESSAGE("samples 64-79, 9.4 away: level " << m.measured << " measured, " << m.analytic << " analytic ("
                                               << m.pixels << " pixels)");
    REQUIRE(m.pixels >= 200);
    CHECK(std::abs(m.measured - m.analytic) <= 0.25);
    CHECK(vk::validationMessageCount() == 0);
}

// The camera cone spans the pixel filter's diameter (FrameUniforms
// scene.z): the tent filter of radius 1 reads one level above the box
// filter's pixel, here from 2.9 away (the box filter's level there is below
// the measured range).
TEST_CASE("texture: LOD with a tent filter of radius 1 reads the level of the filter's two-pixel footprint") {
    RenderSettings s;
    s.maxDepth = 0;
    s.seed = 5;
    s.filter = filterByName("tent");
    REQUIRE(s.filter.radius == 1.0f);
    ViewOptions v;
    v.lookFrom = glm::vec3(0.0f, 0.0f, 2.9f);
    v.lookAt = glm::vec3(0.0f);
    v.fovDegrees = 20.0f;
    const MeasuredLevel m = measureLevel("lod-plane.gltf", s, v, [](const CameraRays& rays, double spread, glm::dvec3 d) {
        const double t = -rays.origin.z / d.z;
        return std::log2(2.0 * spread * t * 32.0);
    });
    MESSAGE("tent, 2.9 away: level " << m.measured << " measured, " << m.analytic << " analytic (" << m.pixels
                                     << " pixels)");
    REQUIRE(m.pixels >= 200);
    CHECK(std::abs(m.measured - m.analytic) <= 0.25);
    CHECK(vk::validationMessageCount() == 0);
}

// lod-mirror.gltf at max depth 1: the plane seen in a smooth white metal
// mirror (reflectance 1; a delta bounce leaves the cone's spread as it is),
// against the level of the cone's whole length, t1 + t2, and |cos| at the plane.
TEST_CASE("texture: LOD after a mirror bounce reads the level of the cone's whole length") {
    RenderSettings s;
    s.maxDepth = 1;
    s.seed = 4;
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.0, -1.0, -1.0)), centre(0.0, 0.0, 3.0);
    const MeasuredLevel m = measureLevel("lod-mirror.gltf", s, {}, [&](const CameraRays& rays, double spread, glm::dvec3 d) {
        const double t1 = glm::dot(centre - rays.origin, n) / glm::dot(d, n);
        const glm::dvec3 p = rays.origin + t1 * d;
        if (std::abs(p.x) > 0.9 || std::abs(p.y) > 0.6) return std::nan("");  // off the mirror or near its edges
        const glm::dvec3 r = d - 2.0 * glm::dot(d, n) * n;
        const double t2 = -p.z / r.z;
        return std::log2(spread * (t1 + t2) * 32.0);
    });
    MESSAGE("after the mirror: level " << m.measured << " measured, " << m.analytic << " analytic (" << m.pixels
                                       << " pixels)");
    REQUIRE(m.pixels >= 200);
    CHECK(std::abs(m.measured - m.analytic) <= 0.25);
    CHECK(vk::validationMessageCount() == 0);
}

// lod-sphere.gltf at max depth 1: the checker plane seen in a smooth
// mirror sphere of radius 1. The cone reaches the sphere w1 = spread x t1
// wide and leaves it spreading by spread + 2 w1 / R (the sphere's
// curvature, from its vertex normals); the level is that cone's width at
// the plane (texels of 0.2). Without the curvature
// term the level reads about two lower.
TEST_CASE("texture: LOD after a curved mirror widens the cone by the surface's curvature") {
    RenderSettings s;
    s.maxDepth = 1;
    s.seed = 6;
    const glm::dvec3 centre(0.0, 0.0, -4.0);
    const MeasuredLevel m = measureLevel("lod-sphere.gltf", s, {}, [&](const CameraRays& rays, double spread, glm::dvec3 d) {
        const glm::dvec3 oc = rays.origin - centre;
        const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - 1.0);
        if (disc <= 0.0) return std::nan("");
        const double t1 = -b - std::sqrt(disc);
        const glm::dvec3 p = rays.origin + t1 * d, n = p - centre;
        if (glm::dot(-d, n) < 0.5) return std::nan("");  // near the silhouette
        const glm::dvec3 r = d - 2.0 * glm::dot(d, n) * n;
        const double t2 = (0.5 - p.z) / r.z;
        const glm::dvec3 q = p + t2 * r;
        if (!(t2 > 0.0) || std::abs(q.x) > 12.0 || std::abs(q.y) > 12.0) return std::nan("");
        const double w1 = spread * t1, w2 = w1 + (spread + 2.0 * w1) * t2;
        return std::log2(w2 / 0.2);
    });
    MESSAGE("after the sphere: level " << m.measured << " measured, " << m.analytic << " analytic (" << m.pixels
                                       << " pixels)");
    REQUIRE(m.pixels >= 100);
    CHECK(std::abs(m.measured - m.analytic) <= 0.25);
    CHECK(vk::validationMessageCount() == 0);
}

// foliage.gltf at max depth 0: leaves (MASK, 35% of the texels, emitting
// green) over holes (red texels, alpha 0) in front of a blue emitter,
// minified about 24 texels a pixel. Blue is the share of camera rays that
// pass the cut-out, red the holes' colour seen on leaves. With LOD the
// alpha test reads the first level (its coverage exact) and the levels the
// leaves' colour is read from take it over the leaves alone: no more red
// than bilinear lookups of the first level show at the leaves' edges (4
// standard errors). --texture-max-size 16 (the texture 16x smaller) keeps
// the coverage within 5% of the whole texture's (Castano's scaled alpha).
TEST_CASE("texture: an alpha cut-out keeps its coverage and its colour minified and downsampled") {
    RenderSettings s;
    s.width = s.height = 64;
    s.spp = 16;
    s.maxDepth = 0;
    s.seed = 3;
    struct Means {
        double coverage = 0.0, red = 0.0, redError = 0.0, coverageError = 0.0;
    };
    auto measure = [&](bool lod, std::uint32_t maxSize) {
        s.textureLod = lod;
        SceneRequest request = keptRequest(s);
        request.file = sourcePath(kDir + "foliage.gltf");
        request.textureMaxSize = maxSize;
        HostScene host = prepareScene(request);
        CHECK(((host.gpu.features.bits & gpu::kFeatureTextureLod) != 0u) == lod);
        const RenderResult r = render(context(), uploadPrepared(context(), request, host.gpu), host.camera, s);
        const auto mean = r.film.mean(), var = r.film.varianceOfMean();
        Means m;
        double varRed = 0.0, varBlue = 0.0;
        const std::size_t n = std::size_t(64) * 64;
        for (std::size_t i = 0; i < n; ++i) {
            m.red += mean[i * 3];
            m.coverage += 1.0 - mean[i * 3 + 2];
            varRed += var[i * 3];
            varBlue += var[i * 3 + 2];
        }
        m.red /= double(n);
        m.coverage /= double(n);
        m.redError = std::sqrt(varRed) / double(n);
        m.coverageError = std::sqrt(varBlue) / double(n);
        return m;
    };
    const Means on = measure(true, 0), off = measure(false, 0), small = measure(false, 16);
    MESSAGE("coverage " << on.coverage << " +- " << on.coverageError << " with LOD, " << off.coverage << " +- "
                        << off.coverageError << " without, " << small.coverage << " +- " << small.coverageError
                        << " at 16x16; red " << on.red << " +- " << on.redError << " against " << off.red << " +- "
                        << off.redError);
    CHECK(off.coverage == doctest::Approx(0.35).epsilon(0.05));  // the texture's share of leaf texels, about
    CHECK(std::abs(on.coverage - off.coverage) <= 4.0 * std::hypot(on.coverageError, off.coverageError));
    CHECK(on.red <= off.red + 4.0 * std::hypot(on.redError, off.redError));
    CHECK(std::abs(small.coverage - off.coverage) <= 0.05 * off.coverage);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: wrap modes REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT per axis") {
    struct Case {
        const char* file;
        WrapMode s, t;
    };
    for (const Case c : {Case{"wrap-repeat.gltf", WrapMode::Repeat, WrapMode::Repeat},
                         Case{"wrap-clamp-mirror.gltf", WrapMode::Clamp, WrapMode::Mirror},
                         Case{"wrap-mirror-clamp.gltf", WrapMode::Mirror, WrapMode::Clamp}}) {
        CAPTURE(c.file);
        // uv spans [-1, 2]^2: three periods per axis.
        const DirectCheck d = checkDirect(c.file, 24, [&](glm::dvec2 st, double* b) {
            return kEmissive * checkerNearest(quadUv(st, {-1, -1}, {3, 3}), c.s, c.t, b);
        });
        CAPTURE(d.maxRelError);
        CHECK(d.skipped == 0);
        CHECK(d.maxRelError < 1e-5);
        // The test can tell the modes apart: the expected image of every
        // other mode pair differs in at least a sixth of the pixels.
        for (const WrapMode s : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
            for (const WrapMode t : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
                if (s == c.s && t == c.t) continue;
                int differ = 0;
                for (int i = 0; i < 24 * 24; ++i) {
                    const glm::dvec2 uv = quadUv({(i % 24 + 0.5) / 24, (i / 24 + 0.5) / 24}, {-1, -1}, {3, 3});
                    differ += checkerNearest(uv, s, t) != checkerNearest(uv, c.s, c.t);
                }
                CHECK(differ >= 24 * 24 / 6);
            }
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: KHR_texture_transform offset, rotation, scale and texCoord override") {
    // offset (0.25, -0.5), rotation 0.6 rad, scale (1.5, -2), TEXCOORD_1;
    // uv' = offset + R (scale * uv), R columns (cos, -sin), (sin, cos).
    const double c = std::cos(0.6), s = std::sin(0.6);
    const DirectCheck d = checkDirect("transform.gltf", 24, [&](glm::dvec2 st, double* b) {
        const glm::dvec2 q = st * glm::dvec2(1.5, -2.0);
        const glm::dvec2 uv(0.25 + c * q.x + s * q.y, -0.5 - s * q.x + c * q.y);
        return kEmissive * checkerNearest(uv, WrapMode::Repeat, WrapMode::Repeat, b);
    });
    CAPTURE(d.maxRelError);
    CAPTURE(d.skipped);
    CHECK(d.skipped == 0);
    CHECK(d.maxRelError < 1e-5);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: bilinear filtering, and half-way between texel centres is their average") {
    // 23 x 23 pixels: pixel (11, 11) sees uv (0.5, 0.5), half-way between
    // the centres of texels (1..2, 0..1).
    const DirectCheck d = checkDirect("bilinear.gltf", 23, [](glm::dvec2 st, double*) {
        return kEmissive * checkerBilinear(st, WrapMode::Clamp, WrapMode::Repeat);
    });
    CAPTURE(d.maxRelError);
    CHECK(d.maxRelError < 1e-4);
    const Rendered r = renderFile(kDir + "bilinear.gltf", centreSettings(23, 1, 0, 5));
    const auto mean = r.result.film.mean();
    const glm::dvec3 average =
        0.25 * (checkerTexel(1, 0) + checkerTexel(2, 0) + checkerTexel(1, 1) + checkerTexel(2, 1));
    for (int k = 0; k < 3; ++k) {
        CAPTURE(k);
        CHECK(mean[(11 * 23 + 11) * 3 + k] == doctest::Approx(kEmissive[k] * average[k]).epsilon(1e-4));
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: alpha MASK holes (alpha 127/255 < cutoff 0.5 <= 128/255) show the emitter behind") {
    // 8 x 8 checker of alpha 127 (hole) and 128 (kept) over a white emitter.
    const Rendered r = renderFile(kDir + "alpha-mask.gltf", centreSettings(24, 4, 0, 9));
    const auto mean = r.result.film.mean();
    std::size_t wrong = 0, lit = 0;
    for (int py = 0; py < 24; ++py) {
        for (int px = 0; px < 24; ++px) {
            const bool hole = (px / 3 + py / 3) % 2 == 0;
            const float v = mean[(static_cast<std::size_t>(py) * 24 + px) * 3];
            wrong += v != (hole ? 1.0f : 0.0f);
            lit += v == 1.0f;
        }
    }
    CHECK(wrong == 0);
    CHECK(lit == 24 * 24 / 2);
    CHECK((r.gpu.features.bits & gpu::kFeatureAlphaTest) != 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: alpha BLEND 0.3 lets 70% of camera rays through, deterministically per seed") {
    RenderSettings s = centreSettings(32, 64, 0, 21);
    s.filter = PixelFilter{};  // box, radius 0.5: every sample is another ray
    const Rendered a = renderFile(kDir + "alpha-blend.gltf", s);
    const Rendered b = renderFile(kDir + "alpha-blend.gltf", s);
    const auto ma = a.result.film.mean(), mb = b.result.film.mean();
    CHECK(std::memcmp(ma.data(), mb.data(), ma.size() * sizeof(float)) == 0);
    // Each sample is 1 (through) or 0 (stopped): Bernoulli(0.7).
    const double n = 32.0 * 32.0 * 64.0;
    double through = 0.0, sq = 0.0;
    for (std::size_t i = 0; i < ma.size(); i += 3) {
        through += ma[i];
        sq += static_cast<double>(ma[i]) * ma[i];
    }
    const double pixels = 32.0 * 32.0;
    const double p = through / pixels;
    const double se = std::sqrt(0.7 * 0.3 / n);  // 0.0018
    CAPTURE(p);
    CHECK(std::abs(p - 0.7) <= 4.0 * se);
    // Per-pixel fractions spread as Binomial(64, 0.7) / 64 (variance
    // 0.00328) when the samples of a pixel are independent; the sample
    // variance over 1024 pixels has a relative standard deviation of 4.4%,
    // so +-20% is a 4.5-sigma bound.
    const double var = sq / pixels - p * p;
    CAPTURE(var);
    CHECK(var == doctest::Approx(0.7 * 0.3 / 64.0).epsilon(0.2));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: alpha holes are skipped by trace.comp's closest-hit and any-hit alike") {
    const Scene scene = loadGltf(sourcePath(kDir + "alpha-mask.gltf"));
    const GpuScene gpu = buildAndPack(scene);
    // Rays down -Z through the centres of the blocker's 8 x 8 cells (z = 0.5,
    // [-0.75, 0.75]^2); the emitter is at z = 0.
    std::vector<gpu::TraceRay> rays;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            rays.push_back({glm::vec3(-0.75f + (x + 0.5f) * 0.1875f, 0.75f - (y + 0.5f) * 0.1875f, 1.0f), 0.0f,
                            glm::vec3(0, 0, -1), 0.75f});
    const auto any = traceOnDevice(context(), gpu, rays, ReadMode::Auto, gpu::kTraceAny);
    for (auto& r : rays) r.tmax = 2.0f;
    const auto closest = traceOnDevice(context(), gpu, rays, ReadMode::Auto, gpu::kTraceClosest);
    for (int i = 0; i < 64; ++i) {
        const bool hole = (i % 8 + i / 8) % 2 == 0;
        CAPTURE(i);
        CHECK((any[i].t < 0.0f) == hole);                                // tmax 0.75 ends before the emitter
        CHECK(closest[i].t == doctest::Approx(hole ? 1.0 : 0.5));        // the emitter, else the blocker
    }
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// Normal-map scenes: a square emitter [-0.5, 0.5]^2 at y = 1 (radiance 1,
// facing down) over the Lambertian plane y = 0 (albedo 0.5); the camera at
// (0, 0.9, 0) looks straight down. Tangent frame on the plane: T = +X
// (uv's u), bitangent = -Z (v grows along +Z; the normal map's +Y points to
// decreasing v), N = +Y.
constexpr double kPlaneAlbedo = 0.5;
using Polygon = std::array<glm::dvec3, 4>;
constexpr Polygon kLight = {{{-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5}}};
// The emitting half of plane-half-light.gltf's textured light, and its mirror image.
constexpr Polygon kHalfLight = {{{-0.5, 1, -0.5}, {0.0, 1, -0.5}, {0.0, 1, 0.5}, {-0.5, 1, 0.5}}};
constexpr Polygon kOtherHalf = {{{0.0, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {0.0, 1, 0.5}}};

// The shading normal a constant normal texel gives (glTF: n = 2 c / 255 - 1).
glm::dvec3 mappedNormal(int r, int g, int b) {
    const glm::dvec3 m(2.0 * r / 255.0 - 1.0, 2.0 * g / 255.0 - 1.0, 2.0 * b / 255.0 - 1.0);
    return glm::normalize(m.x * glm::dvec3(1, 0, 0) + m.y * glm::dvec3(0, 0, -1) + m.z * glm::dvec3(0, 1, 0));
}

// Irradiance at p with normal n from the uniform polygon emitter (radiance
// 1), by Lambert's formula: E = 1/2 sum_i Theta_i (n . Gamma_i), Theta_i the
// angle the edge (v_i, v_i+1) subtends at p, Gamma_i the unit normal of the
// plane through p and the edge (Arvo 1995, "Applications of Irradiance
// Tensors"). Exact when the whole polygon is above the tangent plane of n.
double polygonIrradiance(const glm::dvec3& p, const glm::dvec3& n, const Polygon& light = kLight) {
    double e = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
        const glm::dvec3 a = glm::normalize(light[i] - p);
        const glm::dvec3 b = glm::normalize(light[(i + 1) % 4] - p);
        e += 0.5 * std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
    }
    return std::abs(e);
}

// The plane point seen through pixel (px, py)'s centre, with the camera
// model of shaders/pathtrace.comp and render/renderer.cpp.
glm::dvec3 planePoint(const Camera& cam, int px, int py, int size) {
    const glm::dvec3 f(cam.forward);
    const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
    const glm::dvec3 up = glm::cross(right, f);
    const double t = std::tan(0.5 * static_cast<double>(cam.yfov));
    const glm::dvec3 d = glm::normalize(f + (2.0 * (px + 0.5) / size - 1.0) * t * right +
                                        (1.0 - 2.0 * (py + 0.5) / size) * t * up);
    return glm::dvec3(cam.position) + (-static_cast<double>(cam.position.y) / d.y) * d;
}

struct PlaneFit {
    stats::MeanTestResult mean;
    double expectedMean = 0.0;
    std::size_t pixels = 0;
    std::size_t within = 0;     // pixels within 4.5 sigma of the expected value
    std::size_t otherFails = 0; // pixels more than 4.5 sigma from the `other` answer
};

// Renders a plane scene at max depth 1 and tests its pixels against
// L = (albedo / pi) E(p, n) in the mean (4 standard errors).
PlaneFit fitPlane(const std::string& file, const glm::dvec3& n, std::uint32_t seed,
                  const Polygon& light = kLight, const Polygon& other = kLight) {
    constexpr int kSize = 16;
    const Rendered r = renderFile(kDir + file, centreSettings(kSize, 256, 1, seed));
    const auto mean = r.result.film.mean();
    const auto var = r.result.film.varianceOfMean();
    std::vector<double> diff, diffVar;
    PlaneFit fit;
    for (int py = 0; py < kSize; ++py) {
        for (int px = 0; px < kSize; ++px) {
            const glm::dvec3 p = planePoint(r.scene.cameras[0], px, py, kSize);
            for (const glm::dvec3& c : light) REQUIRE(glm::dot(c - p, n) > 0.0);
            const double expected = kPlaneAlbedo / std::numbers::pi * polygonIrradiance(p, n, light);
            const std::size_t i = (static_cast<std::size_t>(py) * kSize + px) * 3;
            diff.push_back(mean[i] - expected);
            diffVar.push_back(var[i]);
            fit.expectedMean += expected / (kSize * kSize);
            const double sigma = std::sqrt(static_cast<double>(var[i]));
            const double otherValue = kPlaneAlbedo / std::numbers::pi * polygonIrradiance(p, n, other);
            ++fit.pixels;
            fit.within += std::abs(mean[i] - expected) <= 4.5 * sigma;
            fit.otherFails += std::abs(mean[i] - otherValue) > 4.5 * sigma;
        }
    }
    fit.mean = stats::meanTest(diff, diffVar, 0.0, 4.0);
    return fit;
}

}  // namespace

TEST_CASE("texture: the polygon irradiance formula agrees with the square-light form factor" * doctest::test_suite("unit")) {
    // Below the centre, normal +Y: E = pi F, F = 0.2394564704607735
    // (tests/test_known_answers.cpp, Howell B-3).
    CHECK(polygonIrradiance({0, 0, 0}, {0, 1, 0}) ==
          doctest::Approx(std::numbers::pi * 0.2394564704607735).epsilon(1e-12));
}

TEST_CASE("texture: a tilted constant normal map shades a diffuse plane by the tilted cosine") {
    const glm::dvec3 tilted = mappedNormal(191, 128, 221);
    const double tilt = std::acos(tilted.y);
    CAPTURE(tilt);
    CHECK(tilt > 0.5);  // 34 degrees towards +X
    const PlaneFit flat = fitPlane("plane-no-map.gltf", {0, 1, 0}, 31);
    const PlaneFit mapped = fitPlane("plane-tilted-map.gltf", tilted, 32);
    for (const PlaneFit* f : {&flat, &mapped}) {
        CAPTURE(f->mean.mean);
        CAPTURE(f->mean.stdError);
        CAPTURE(f->expectedMean);
        CAPTURE(f->within);
        CHECK(f->mean.passed);
        CHECK(f->mean.stdError < 2e-3 * f->expectedMean);
        CHECK(static_cast<double>(f->within) >= 0.99 * f->pixels);
    }
    // The tilt changes the answer by far more than the test's resolution.
    CHECK(std::abs(mapped.expectedMean - flat.expectedMean) > 20.0 * mapped.mean.stdError);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: next-event estimation reads an emissive texture at the sampled point") {
    // Half the light is black: the plane sees the other half's irradiance
    // (BSDF-sampled hits and light samples both go through emissionAt).
    const PlaneFit half = fitPlane("plane-half-light.gltf", {0, 1, 0}, 51, kHalfLight, kOtherHalf);
    CAPTURE(half.mean.mean);
    CAPTURE(half.mean.stdError);
    CAPTURE(half.expectedMean);
    CAPTURE(half.within);
    CAPTURE(half.otherFails);
    CHECK(half.mean.passed);
    CHECK(half.mean.stdError < 5e-3 * half.expectedMean);
    // Per pixel (4.5 sigma, 99% of pixels): the texture is read where the
    // light was sampled. Reading it at the wrong point, e.g. mirrored, gives
    // the other half's light, which most pixels reject.
    CHECK(static_cast<double>(half.within) >= 0.99 * half.pixels);
    CHECK(static_cast<double>(half.otherFails) >= 0.5 * half.pixels);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: a flat normal map (128, 128, 255) renders as no normal map") {
    // Same seed, so the same samples: only the 0.0055 rad tilt of
    // (128, 128, 255) (2 * 128 / 255 - 1 = 0.0039) separates the images.
    RenderSettings s = centreSettings(16, 16, 1, 41);
    auto relDiffs = [&](std::vector<double>& rel, double& sumRatio) {
        const Rendered a = renderFile(kDir + "plane-no-map.gltf", s);
        const Rendered b = renderFile(kDir + "plane-flat-map.gltf", s);
        CHECK((b.gpu.features.bits & gpu::kFeatureNormalMap) != 0);
        CHECK((a.gpu.features.bits & gpu::kFeatureNormalMap) == 0);
        const auto ma = a.result.film.mean(), mb = b.result.film.mean();
        double sumA = 0.0, sumB = 0.0;
        for (std::size_t i = 0; i < ma.size(); ++i) {
            rel.push_back(std::abs(static_cast<double>(mb[i]) - ma[i]) / ma[i]);
            sumA += ma[i];
            sumB += mb[i];
        }
        std::sort(rel.begin(), rel.end());
        sumRatio = sumB / sumA;
    };
    // Light sampling alone (the light's directions do not depend on the
    // normal): every sample's cosine changes by at most 0.0055 tan(45 deg)
    // (the steepest light direction in view), so every pixel by 0.55%.
    s.mis = gpu::kMisLight;
    std::vector<double> light;
    double lightRatio = 0.0;
    relDiffs(light, lightRatio);
    CAPTURE(light.back());
    CHECK(light.back() < 5.5e-3);
    // Both techniques: the power heuristic's weights move with the BSDF's
    // density as well, and a few BSDF-sampled rays cross the light's edge
    // in one image and not in the other.
    s.mis = gpu::kMisPower;
    std::vector<double> both;
    double ratio = 0.0;
    relDiffs(both, ratio);
    const double median = both[both.size() / 2];
    CAPTURE(median);
    CAPTURE(both.back());
    CHECK(median < 2e-3);
    CHECK(both.back() < 0.1);
    CHECK(ratio == doctest::Approx(1.0).epsilon(2e-3));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: texture coordinates decode from normalized u8/u16, tangents go to world space" * doctest::test_suite("unit")) {
    const Scene scene = loadGltf(sourcePath(kDir + "loader.gltf"), LoadOptions{false, false});
    REQUIRE(scene.triangles.size() == 2);
    REQUIRE(scene.texcoords.size() == 2);  // the plain primitive is back-filled with zeros
    REQUIRE(scene.tangents.size() == 2);
    for (const glm::vec4& uv : scene.texcoords[0]) CHECK(uv == glm::vec4(0.0f));
    // The mirrored node swaps vertices 1 and 2 to keep the front face.
    const TriangleUv& uv = scene.texcoords[1];
    CHECK(uv[0] == glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));                         // (0, 255), (0, 65535)
    CHECK(uv[2] == glm::vec4(0.2f, 0.4f, 13107.0f / 65535.0f, 0.0f));          // (51, 102), (13107, 0)
    CHECK(uv[1] == glm::vec4(1.0f, 0.0f, 1.0f, 32768.0f / 65535.0f));          // (255, 0), (65535, 32768)
    // TANGENT (1, 0, 0, +1) under scale (-1, 1, 1): (-1, 0, 0), handedness -1.
    for (const glm::vec4& t : scene.tangents[1]) CHECK(t == glm::vec4(-1.0f, 0.0f, 0.0f, -1.0f));
    const MaterialDesc& m = scene.materials[scene.triangles[1].material];
    CHECK(m.normalTexture.used());
    CHECK(m.normalScale == 0.5f);
}

TEST_CASE("texture: generated tangents follow +u, with glTF handedness, and survive degenerate uvs" * doctest::test_suite("unit")) {
    // Unit quad in the XY plane facing +Z; image convention: v grows downwards (-Y).
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<glm::vec3> n(4, glm::vec3(0, 0, 1));
    const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
    const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    for (const glm::vec4& t : generateTangents(p, n, uv, idx)) CHECK(t == glm::vec4(1, 0, 0, 1));
    // u mirrored: tangent -X, and the bitangent w cross(n, t) still points to -dP/dv (+Y).
    const std::vector<glm::vec2> mirrored = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
    for (const glm::vec4& t : generateTangents(p, n, mirrored, idx)) {
        CHECK(t == glm::vec4(-1, 0, 0, -1));
        CHECK(t.w * glm::cross(n[0], glm::vec3(t)) == glm::vec3(0, 1, 0));
    }
    // uv rotated by 90 degrees: u grows along +Y.
    const std::vector<glm::vec2> rotated = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    for (const glm::vec4& t : generateTangents(p, n, rotated, idx)) CHECK(t == glm::vec4(0, 1, 0, 1));
    // A tangent with a normal component is orthogonalised: normals tilted in x-z.
    const std::vector<glm::vec3> tiltedN(4, glm::normalize(glm::vec3(1, 0, 1)));
    for (const glm::vec4& t : generateTangents(p, tiltedN, uv, idx)) {
        CHECK(std::abs(glm::dot(glm::vec3(t), tiltedN[0])) < 1e-6f);
        CHECK(glm::length(glm::vec3(t)) == doctest::Approx(1.0f));
    }
    // All uvs equal: any unit tangent orthogonal to the normal.
    const std::vector<glm::vec2> same(4, glm::vec2(0.5f));
    for (const glm::vec4& t : generateTangents(p, n, same, idx)) {
        CHECK(std::abs(glm::dot(glm::vec3(t), n[0])) < 1e-6f);
        CHECK(glm::length(glm::vec3(t)) == doctest::Approx(1.0f));
    }
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

namespace {

TextureImage image8(int width, int height, const std::vector<std::array<int, 4>>& texels) {
    TextureImage im;
    im.width = width;
    im.height = height;
    for (const auto& t : texels)
        for (int c : t) im.data.push_back(static_cast<std::uint8_t>(c));
    return im;
}

}  // namespace

TEST_CASE("texture: downsampling averages colour in linear light, renormalises normals, covers odd sizes") {
    // sRGB: red and three black texels: a quarter of red's light, 137 in sRGB (not 64, the mean of the codes).
    const TextureImage quad = image8(2, 2, {{255, 0, 0, 255}, {0, 0, 0, 255}, {0, 0, 0, 0}, {0, 0, 0, 0}});
    const TextureImage srgb = downsampledTexture(quad, 1, TexelCoding::Srgb);
    REQUIRE(srgb.width == 1);
    REQUIRE(srgb.height == 1);
    CHECK(int(srgb.data[0]) == 137);
    CHECK(int(srgb.data[3]) == 128);  // alpha averaged as it is: 127.5 rounded
    CHECK(int(downsampledTexture(quad, 1, TexelCoding::Linear).data[0]) == 64);
    // Normals +X and +Y (encoded 2n - 1): their mean renormalised, (0.707, 0.707, 0).
    const TextureImage normals = image8(2, 1, {{255, 128, 128, 255}, {128, 255, 128, 255}});
    const TextureImage n = downsampledTexture(normals, 1, TexelCoding::Normal);
    glm::dvec3 v;
    for (int c = 0; c < 3; ++c) v[c] = 2.0 * n.data[std::size_t(c)] / 255.0 - 1.0;
    CHECK(glm::length(v) == doctest::Approx(1.0).epsilon(0.01));
    CHECK(v.x == doctest::Approx(std::sqrt(0.5)).epsilon(0.01));
    // An odd side: 3 x 1 halves to 2 x 1, its last texel alone.
    const TextureImage odd = image8(3, 1, {{0, 0, 0, 0}, {0, 0, 0, 0}, {10, 20, 30, 40}});
    const TextureImage h = downsampledTexture(odd, 2, TexelCoding::Linear);
    REQUIRE(h.width == 2);
    CHECK(std::vector<int>(h.data.begin() + 4, h.data.end()) == std::vector<int>{10, 20, 30, 40});
    // Halved until neither side exceeds the size: 64 x 16 at most 10 is 8 x 2.
    TextureImage big = image8(64, 16, std::vector<std::array<int, 4>>(64 * 16, {200, 100, 50, 255}));
    const TextureImage small = downsampledTexture(big, 10, TexelCoding::Srgb);
    CHECK(small.width == 8);
    CHECK(small.height == 2);
    CHECK(int(small.data[0]) == 200);  // a uniform image stays itself
    // --stats: the largest four, how many downsampled, the file's size where it differs.
    nlohmann::json list = nlohmann::json::array();
    for (int k = 0; k < 5; ++k)
        list.push_back({{"name", "t" + std::to_string(k)}, {"width", 8}, {"height", 8}, {"file_width", k == 2 ? 16 : 8},
                        {"file_height", k == 2 ? 16 : 8}, {"bytes", 256 * (k + 1)}});
    CHECK(texturesText({{"images", 5}, {"bytes", 3840}, {"list", list}}) ==
          "5 image(s), 3840 bytes on the device, 1 downsampled: t4 8x8 (1280 bytes), t3 8x8 (1024 bytes), t2 8x8 "
          "(768 bytes, 16x16 in the file), t1 8x8 (512 bytes) and 1 more");
    // 16 bits stay 16 bits.
    big.bits = 16;
    big.data.assign(std::size_t(64) * 16 * 8, 0xff);
    const TextureImage wide = downsampledTexture(big, 32, TexelCoding::Linear);
    CHECK(wide.bits == 16);
    CHECK(wide.data.size() == std::size_t(32) * 8 * 8);
}

// The share of bilinear lookups (repeat wrap) of an 8-bit image whose
// alpha is at least 128 (cutoff 0.5), at 8 x 8 points a texel.
double bilinearCoverage(const TextureImage& im) {
    const int w = im.width, h = im.height;
    auto alpha = [&](int x, int y) { return double(im.data[(std::size_t((y + h) % h) * std::size_t(w) + std::size_t((x + w) % w)) * 4 + 3]); };
    std::size_t passed = 0, total = 0;
    for (int y = 0; y < h * 8; ++y)
        for (int x = 0; x < w * 8; ++x) {
            const double u = (x + 0.5) / 8.0 - 0.5, v = (y + 0.5) / 8.0 - 0.5;
            const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
            const double fx = u - x0, fy = v - y0;
            const double a = (1 - fx) * (1 - fy) * alpha(x0, y0) + fx * (1 - fy) * alpha(x0 + 1, y0) +
                             (1 - fx) * fy * alpha(x0, y0 + 1) + fx * fy * alpha(x0 + 1, y0 + 1);
            passed += a >= 127.5;
            ++total;
        }
    return double(passed) / double(total);
}

// A MASK texture downsampled keeps its coverage (the share of bilinear
// lookups at or above the cutoff) within 2% down to 8 x 8, where plain
// means lose it; its mip levels take colour over the leaves alone; BLEND
// weights colour by alpha.
TEST_CASE("texture: cut-outs downsampled keep MASK coverage, their levels take colour over what is seen") {
    // 64 x 64: green leaves (alpha 255) where a smooth pattern is high, about
    // 23% of the lookups, on red holes (alpha 0).
    std::vector<std::array<int, 4>> texels;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const bool leaf = std::sin(0.7 * x) * std::cos(0.45 * y) + 0.3 * std::sin(0.2 * (x + y)) > 0.4;
            texels.push_back(leaf ? std::array<int, 4>{0, 255, 0, 255} : std::array<int, 4>{255, 0, 0, 0});
        }
    const TextureImage base = image8(64, 64, texels);
    const double share = bilinearCoverage(base);
    REQUIRE(share > 0.2);
    REQUIRE(share < 0.4);
    AlphaUse mask;
    mask.mode = AlphaUse::Mode::Mask;
    mask.cutoff = 0.5f;
    double plainWorst = 0.0;
    for (std::uint32_t size = 32; size >= 8; size /= 2) {
        CAPTURE(size);
        const TextureImage small = downsampledTexture(base, size, TexelCoding::Srgb, mask);
        const TextureImage plain = downsampledTexture(base, size, TexelCoding::Srgb);
        const double kept = bilinearCoverage(small);
        MESSAGE(size << "x" << size << ": coverage " << kept << " (base " << share << ", plain means "
                     << bilinearCoverage(plain) << ")");
        CHECK(std::abs(kept - share) <= 0.02);
        plainWorst = std::max(plainWorst, std::abs(bilinearCoverage(plain) - share));
    }
    CHECK(plainWorst > 0.1);  // what the test guards against
    const std::vector<TextureImage> chain = textureMips(base, TexelCoding::Srgb, mask);
    REQUIRE(chain.size() == 6);
    for (const TextureImage& level : chain)
        for (std::size_t i = 0; i < std::size_t(level.width) * std::size_t(level.height); ++i)
            if (level.data[i * 4 + 3] > 0) CHECK(int(level.data[i * 4]) == 0);  // no red where any leaf is
    // BLEND: transparent red and opaque green are green at half alpha.
    AlphaUse blend;
    blend.mode = AlphaUse::Mode::Blend;
    const std::vector<TextureImage> b = textureMips(image8(2, 1, {{255, 0, 0, 0}, {0, 255, 0, 255}}), TexelCoding::Srgb, blend);
    REQUIRE(b.size() == 1);
    CHECK(std::vector<int>(b[0].data.begin(), b[0].data.end()) == std::vector<int>{0, 255, 0, 128});
}

TEST_SUITE_END();
