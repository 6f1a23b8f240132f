// Texture level of detail (issue 44): the ray cone's level measured
// against its analytic footprint (camera rays, a mirror, a curved mirror,
// the tent filter, KHR_texture_transform's scale, each sample's bias), a
// receding checker's variance, and alpha cut-outs' coverage minified and
// downsampled. The real shaders on lavapipe, validation on. Scenes:
// tests/data/textures/, written by scripts/make_texture_scenes.py.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "measure/tracer.h"
#include "settings/filter.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {
const std::string kDir = "tests/data/textures/";
}  // namespace

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

// Sample s's level bias, as lib/material.glsl lodScale2ForSample takes it
// (there as exp2(2 x the bias)).
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

// The level measured against the analytic one: within a quarter, over at
// least `minPixels` pixels.
void checkLevel(const std::string& what, const MeasuredLevel& m, std::size_t minPixels = 200) {
    MESSAGE(what << ": level " << m.measured << " measured, " << m.analytic << " analytic (" << m.pixels
                 << " pixels)");
    REQUIRE(m.pixels >= minPixels);
    CHECK(std::abs(m.measured - m.analytic) <= 0.25);
}

// The level measured on lod-plane.gltf's checker (the plane z = 0) at max
// depth 0, seen from `from` looking at its centre through a 20-degree field
// of view, against the footprint of a cone `pixels` pixels wide there;
// `file` another such plane with `texelsPerUnit` texels a world unit.
MeasuredLevel measurePlaneLevel(RenderSettings s, glm::vec3 from, double pixels, std::uint32_t first = 0,
                                const std::string& file = "lod-plane.gltf", double texelsPerUnit = 32.0) {
    s.maxDepth = 0;
    ViewOptions v;
    v.lookFrom = from;
    v.lookAt = glm::vec3(0.0f);
    v.fovDegrees = 20.0f;
    return measureLevel(
        file, s, v,
        [pixels, texelsPerUnit](const CameraRays& rays, double spread, glm::dvec3 d) {
            const double t = -rays.origin.z / d.z;
            return std::log2(pixels * spread * t * texelsPerUnit);
        },
        first);
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
        s.seed = 9;
        checkLevel(view.what, measurePlaneLevel(s, view.from, 1.0));
    }
    CHECK(vk::validationMessageCount() == 0);
}

// KHR_texture_transform scales the texels a world unit: lod-plane-transform.gltf
// is lod-plane.gltf's checker scaled by 2 (turned and shifted too: |det| 4,
// one level more), so from 2.95 away it reads the level lod-plane.gltf
// reads from 5.9, about 0.6. A level that ignored the transform's scale
// would read the first level only (0), one that counted it twice level 1.
TEST_CASE("texture: LOD counts KHR_texture_transform's scale in the level") {
    RenderSettings s;
    s.seed = 9;
    checkLevel("scaled by 2, 2.95 away",
               measurePlaneLevel(s, glm::vec3(0.0f, 0.0f, 2.95f), 1.0, 0, "lod-plane-transform.gltf", 64.0));
    CHECK(vk::validationMessageCount() == 0);
}

// The level's bias follows the sample index (lodScale2ForSample): samples
// 64-79 read about 1.3 levels sharper than the footprint. From 9.4 away the
// footprint is about 1.75 levels: those samples read a level near 0.45,
// where a fixed bias of half a level (this test's failure when the index
// is ignored) would read level 1 and above, the checker's grey (1).
TEST_CASE("texture: LOD's level bias follows the sample index: later samples read sharper levels") {
    RenderSettings s;
    s.seed = 3;
    checkLevel("samples 64-79, 9.4 away", measurePlaneLevel(s, glm::vec3(0.0f, 0.0f, 9.4f), 1.0, 64));
    CHECK(vk::validationMessageCount() == 0);
}

// The camera cone spans the pixel filter's diameter (FrameUniforms
// scene.z): the tent filter of radius 1 reads one level above the box
// filter's pixel, here from 2.9 away (the box filter's level there is below
// the measured range).
TEST_CASE("texture: LOD with a tent filter of radius 1 reads the level of the filter's two-pixel footprint") {
    RenderSettings s;
    s.seed = 5;
    s.filter = filterByName("tent");
    REQUIRE(s.filter.radius == 1.0f);
    checkLevel("tent, 2.9 away", measurePlaneLevel(s, glm::vec3(0.0f, 0.0f, 2.9f), 2.0));
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
    checkLevel("after the mirror", m);
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
    checkLevel("after the sphere", m, 100);
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

TEST_SUITE_END();
