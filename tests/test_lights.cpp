// Lights with closed-form answers: KHR_lights_punctual (point, spot,
// directional) and the environment (constant, and an equirectangular map).
// Scenes: tests/data/make_lights.py. Statistical tolerances are stated at
// each test; every render is on lavapipe with validation on under ctest.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pack/env_tables.h"
#include "scene/environment.h"
#include "stats/stats.h"
#include "test_util.h"
#include "util/error.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

constexpr double kPi = std::numbers::pi;

std::string lightsPath(const std::string& name) { return sourcePath("tests/data/lights/" + name); }


RenderSettings settings(int size, std::uint32_t spp, std::uint32_t depth, std::uint32_t seed) {
    RenderSettings s;
    s.width = s.height = size;
    s.spp = spp;
    s.maxDepth = depth;
    s.seed = seed;
    return s;
}

// Where the camera ray (image position sx, sy) meets the plane y = 0 from above.
glm::dvec3 onGround(const CameraRays& rays, double sx, double sy) {
    const glm::dvec3 d = rays.dir(sx, sy);
    return rays.origin + (-rays.origin.y / d.y) * d;
}

// Of a closed mesh around the origin: the smallest distance from the origin
// to a face's plane (the inscribed sphere's radius) and the largest to a vertex.
std::pair<double, double> sphereBounds(const Scene& scene) {
    double hMin = 1e30, rMax = 0.0;
    for (const Triangle& t : scene.triangles) {
        const glm::dvec3 a(t.v[0]), b(t.v[1]), c(t.v[2]);
        hMin = std::min(hMin, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a)));
        for (const glm::vec3& v : t.v) rMax = std::max(rMax, glm::length(glm::dvec3(v)));
    }
    return {hMin, rMax};
}


}  // namespace

TEST_CASE("lights: KHR_lights_punctual lights are loaded in world space" * doctest::test_suite("unit")) {
    const Scene spot = loadGltf(lightsPath("spot-plane.gltf"));
    REQUIRE(spot.lights.size() == 1);
    const PunctualLight& l = spot.lights[0];
    CHECK(l.type == PunctualLight::Type::Spot);
    CHECK(l.intensity == 20.0f);
    CHECK(l.innerConeAngle == 0.25f);
    CHECK(l.outerConeAngle == 0.5f);
    CHECK(glm::length(l.position - glm::vec3(0, 2, 0)) < 1e-6f);
    CHECK(glm::length(l.direction - glm::vec3(0, -1, 0)) < 1e-6f);  // local -Z turned down
    const Scene sun = loadGltf(lightsPath("directional-plane.gltf"));
    REQUIRE(sun.lights.size() == 1);
    CHECK(sun.lights[0].type == PunctualLight::Type::Directional);
    CHECK(glm::length(sun.lights[0].direction - glm::normalize(glm::vec3(1, -2, 0.5f))) < 1e-6f);
    CHECK(glm::length(sun.lights[0].intensityRgb() - glm::vec3(3, 2.4f, 1.8f)) < 1e-6f);
}

TEST_CASE("lights: bad KHR_lights_punctual values are one-line errors naming the file" * doctest::test_suite("unit")) {
    struct Case {
        const char* file;
        const char* phrase;
    };
    const Case cases[] = {
        {"negative-intensity.gltf", "light 0 (\"Bad\"): intensity -1 is not a finite number >= 0"},
        {"outer-cone-too-wide.gltf", "light 0 (\"Bad\"): spot.outerConeAngle 2 is outside (0, pi/2]"},
        {"inner-not-below-outer.gltf", "spot.innerConeAngle 0.5 is outside [0, outerConeAngle 0.5)"},
        {"unknown-type.gltf", "type \"area\" is not point, spot or directional"},
        {"light-out-of-range.gltf", "node 0 (\"Bad\"): light 3 does not exist (1 lights)"},
        {"spot-without-cone.gltf", "invalid glTF: "},
        {"zero-intensity-only-light.gltf", "no light: "},
    };
    for (const Case& c : cases) {
        const std::string path = lightsPath(std::string("broken/") + c.file);
        CAPTURE(path);
        std::string message;
        try {
            loadGltf(path);
        } catch (const Error& e) {
            message = e.what();
        }
        CAPTURE(message);
        CHECK(message.find('\n') == std::string::npos);
        CHECK(message.rfind(path + ": error: ", 0) == 0);
        CHECK(message.find(c.phrase) != std::string::npos);
    }
}

TEST_CASE("lights: the alias table weighs every kind of light by its estimated power" * doctest::test_suite("unit")) {
    Scene scene = loadGltf(lightsPath("spot-plane.gltf"));  // plane [-10, 10]^2: R = sqrt(200)
    PunctualLight point;
    point.color = glm::vec3(1.0f, 0.5f, 0.25f);
    point.intensity = 2.0f;
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.intensity = 0.01f;
    scene.lights.push_back(point);
    scene.lights.push_back(sun);
    EnvironmentOptions env;
    env.hasColor = true;
    env.color = glm::vec3(0.001f);
    scene.environment = makeEnvironment(env);
    const GpuScene g = buildAndPack(scene);
    REQUIRE(g.emitters.size() == 4);
    const double r2 = 200.0, yPoint = luminance(glm::dvec3(2.0, 1.0, 0.5));
    const double w[4] = {2.0 * kPi * (1.0 - 0.5 * (std::cos(0.25) + std::cos(0.5))) * 20.0, 4.0 * kPi * yPoint,
                         kPi * r2 * 0.01, kPi * r2 * 4.0 * kPi * 0.001};
    const double total = w[0] + w[1] + w[2] + w[3];
    const std::uint32_t kinds[4] = {gpu::kLightSpot, gpu::kLightPoint, gpu::kLightDirectional, gpu::kLightEnvironment};
    for (int i = 0; i < 4; ++i) {
        CAPTURE(i);
        CHECK(g.emitters[i].kind == kinds[i]);
        CHECK(g.emitters[i].pmf == doctest::Approx(w[i] / total).epsilon(1e-5));
    }
    CHECK(g.environment == 3u);
    CHECK((g.features.bits & gpu::kFeaturePunctual) != 0u);
    CHECK((g.features.bits & gpu::kFeatureEnvironment) != 0u);
    CHECK((g.features.bits & gpu::kFeatureEnvMap) == 0u);
}

// A point light of intensity I = pi at the centre of a closed sphere of
// radius 1 facing inward, albedo a = 0.5. Ideal sphere: the direct radiance
// is a I / (pi R^2) = a everywhere, and each further bounce multiplies a
// uniform radiance by a (the wall sees only itself: irradiance pi L), so at
// max depth d the radiance is S(d) = a (1 - a^d) / (1 - a), 1 in the limit;
// counting emission twice, or missing a bounce, moves it by >= 3%.
// The mesh is an icosphere (level 5) with vertices on the unit sphere: a
// point at distance r from the centre on a face whose plane is at distance h
// gets irradiance I h / r^3, between I h_min / r_max^3 and I / h_min^2, so
// every bounce term, and the image mean, lies in [h_min / r_max^3,
// 1 / h_min^2] x S(d) (a band of 0.05% measured from the mesh). The test:
// the image mean lies in that band widened by 4 standard errors.
TEST_CASE("lights: point light in a closed sphere gives the depth-capped series a(1 - a^d)/(1 - a)") {
    const Scene scene = loadGltf(lightsPath("point-in-sphere.gltf"));
    const auto [hMin, rMax] = sphereBounds(scene);
    const double lo = hMin / (rMax * rMax * rMax), hi = 1.0 / (hMin * hMin);
    MESSAGE("geometric band [" << lo << ", " << hi << "]");
    CHECK(hi - lo < 1e-3);
    {
        const RenderResult r = renderScene(scene, settings(16, 4, 0, 1));
        for (float v : r.film.mean()) CHECK(v == 0.0f);  // a delta light is never seen directly
    }
    const double a = 0.5;
    for (const std::uint32_t depth : {1u, 2u, 16u}) {
        CAPTURE(depth);
        const RenderResult r = renderScene(scene, settings(16, 512, depth, 10 + depth));
        const ImageMean m = imageMean(r.film);
        const double exact = a * (1.0 - std::pow(a, depth)) / (1.0 - a);
        MESSAGE("depth " << depth << ": mean " << m.mean << " +- " << m.stdError << ", series " << exact
                         << ", z against the series " << (m.mean - exact) / m.stdError);
        CHECK(m.stdError > 0.0);
        CHECK(m.stdError < 2e-3 * exact);
        CHECK(m.mean >= lo * exact - 4.0 * m.stdError);
        CHECK(m.mean <= hi * exact + 4.0 * m.stdError);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// Spot light at (0, h = 2, 0) pointing down, I = 20, cone 0.25 / 0.5 rad,
// over the plane y = 0 (albedo a = 0.5). At a plane point at distance d from
// the light, cos = h / d both at the surface and off the axis, and
//   L = a / pi * I * cos / d^2 * clamp(cos * scale + offset, 0, 1)^2
// (KHR_lights_punctual's falloff), at any max depth >= 1 (the plane cannot
// see itself). Pixels: the box-filtered value by a 16 x 16 midpoint rule.
// Each pixel's footprint on the plane is a quadrilateral (a perspective
// image of the pixel square); pixels whose footprint lies outside the outer
// cone's disk must be exactly 0, pixels inside the ring between the cones
// are reported on their own.
TEST_CASE("lights: spot light over a plane matches the closed form per pixel, ring included, zero outside") {
    const Scene scene = loadGltf(lightsPath("spot-plane.gltf"));
    constexpr int kSize = 32, kSub = 16;
    const double a = 0.5, intensity = 20.0, h = 2.0, inner = 0.25, outer = 0.5;
    const double scale = 1.0 / std::max(0.001, std::cos(inner) - std::cos(outer)), offset = -std::cos(outer) * scale;
    auto radiance = [&](const glm::dvec3& p) {
        const double d = std::sqrt(p.x * p.x + p.z * p.z + h * h), cos = h / d;
        const double t = std::clamp(cos * scale + offset, 0.0, 1.0);
        return a / kPi * intensity * cos / (d * d) * t * t;
    };
    const CameraRays rays(scene.cameras.at(0), kSize, kSize);
    const double rInner = h * std::tan(inner), rOuter = h * std::tan(outer);
    std::vector<double> expected(kSize * kSize);
    std::vector<char> all(kSize * kSize, 1), ring(kSize * kSize, 0), outside(kSize * kSize, 0);
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const std::size_t i = static_cast<std::size_t>(py) * kSize + px;
            double sum = 0.0;
            for (int j = 0; j < kSub; ++j)
                for (int k = 0; k < kSub; ++k) sum += radiance(onGround(rays, px + (k + 0.5) / kSub, py + (j + 0.5) / kSub));
            expected[i] = sum / (kSub * kSub);
            // Distance from the cone axis (the origin) to the footprint and to its farthest corner.
            const glm::dvec3 c[4] = {onGround(rays, px, py), onGround(rays, px + 1, py), onGround(rays, px + 1, py + 1),
                                     onGround(rays, px, py + 1)};
            double nearest = 1e30, farthest = 0.0;
            for (int e = 0; e < 4; ++e) {
                const glm::dvec2 p0(c[e].x, c[e].z), p1(c[(e + 1) % 4].x, c[(e + 1) % 4].z);
                const double t = std::clamp(-glm::dot(p0, p1 - p0) / glm::dot(p1 - p0, p1 - p0), 0.0, 1.0);
                nearest = std::min(nearest, glm::length(p0 + t * (p1 - p0)));
                farthest = std::max(farthest, glm::length(p0));
            }
            outside[i] = nearest > rOuter;
            ring[i] = nearest > rInner && farthest < rOuter;
        }
    std::size_t outsideCount = 0, ringCount = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) outsideCount += outside[i], ringCount += ring[i];
    MESSAGE(outsideCount << " pixels outside the cone, " << ringCount << " in the falloff ring");
    REQUIRE(outsideCount >= 100);
    REQUIRE(ringCount >= 50);

    const RenderResult r = renderScene(scene, settings(kSize, 256, 1, 3));
    const auto mean = r.film.mean();
    for (std::size_t i = 0; i < expected.size(); ++i)
        if (outside[i])
            for (int k = 0; k < 3; ++k) CHECK(mean[i * 3 + k] == 0.0f);
    report("all pixels", checkPixels(r, expected, all));
    report("falloff ring", checkPixels(r, expected, ring));
    // The test can fail: without the falloff (a plain cone), the ring is far off.
    std::vector<double> noFalloff(expected.size());
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const glm::dvec3 p = onGround(rays, px + 0.5, py + 0.5);
            const double d = std::sqrt(p.x * p.x + p.z * p.z + h * h);
            noFalloff[static_cast<std::size_t>(py) * kSize + px] = a / kPi * intensity * h / (d * d * d);
        }
    CHECK_FALSE(checkPixels(r, noFalloff, ring).mean.passed);
    CHECK(vk::validationMessageCount() == 0);
}

// Directional light of irradiance E = 3 (1, 0.8, 0.6) travelling along
// normalize(1, -2, 0.5) onto the plane y = 0 (albedo 0.5): L = a / pi * E *
// cos, cos = 2 / sqrt(5.25), on every pixel at every max depth >= 1. Every
// sample evaluates the same expression, so the test is per channel to float
// rounding (relative 1e-5).
TEST_CASE("lights: directional light on a plane gives a/pi * E * cos on every pixel") {
    const Scene scene = loadGltf(lightsPath("directional-plane.gltf"));
    const double cos = 2.0 / std::sqrt(5.25);
    const glm::dvec3 expected = 0.5 / kPi * 3.0 * glm::dvec3(1.0, 0.8, 0.6) * cos;
    for (const std::uint32_t depth : {1u, 3u}) {
        CAPTURE(depth);
        const RenderResult r = renderScene(scene, settings(16, 16, depth, 5));
        const auto mean = r.film.mean();
        double worst = 0.0;
        for (std::size_t i = 0; i < mean.size(); ++i)
            worst = std::max(worst, std::abs(mean[i] / expected[static_cast<int>(i % 3)] - 1.0));
        MESSAGE("depth " << depth << ": largest relative error " << worst);
        CHECK(worst < 1e-5);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// Furnace: a convex Lambertian polyhedron (icosphere, albedo a = 0.8) in a
// uniform environment of radiance 1 (--env-color 1,1,1) reflects a at every
// point (it never sees itself; irradiance pi) at every max depth >= 1, and
// the background is exactly 1. Pixels are classified from the mesh: fully on
// the sphere when all four corner rays hit its inscribed sphere (the rays of
// a pixel are the convex hull of its corner rays, the rays that hit a sphere
// a convex cone), background when a 9 x 9 grid of rays over the pixel misses
// the circumscribed sphere by more than the grid spacing.
TEST_CASE("lights: constant environment furnace: a convex sphere of albedo a is a, the background exactly 1") {
    Scene scene = loadWithWhiteEnvironment(lightsPath("sphere.gltf"));
    REQUIRE(scene.environment.enabled);
    const auto [hMin, rMax] = sphereBounds(scene);
    constexpr int kSize = 32;
    const CameraRays rays(scene.cameras.at(0), kSize, kSize);
    auto missDistance = [&](const glm::dvec3& d) {  // distance of the ray's line from the centre
        return glm::length(rays.origin - glm::dot(rays.origin, d) * d);
    };
    std::vector<char> sphere(kSize * kSize, 0), background(kSize * kSize, 0);
    const double spacing = glm::length(rays.dir(0.5, 0.5) - rays.dir(0.625, 0.5)) * glm::length(rays.origin);
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const std::size_t i = static_cast<std::size_t>(py) * kSize + px;
            bool in = true, out = true;
            for (int j = 0; j <= 1; ++j)
                for (int k = 0; k <= 1; ++k) in = in && missDistance(rays.dir(px + k, py + j)) < hMin;
            for (int j = 0; j <= 8; ++j)
                for (int k = 0; k <= 8; ++k) out = out && missDistance(rays.dir(px + k / 8.0, py + j / 8.0)) > rMax + spacing;
            sphere[i] = in;
            background[i] = out;
        }
    std::size_t nSphere = 0, nBackground = 0;
    for (std::size_t i = 0; i < sphere.size(); ++i) nSphere += sphere[i], nBackground += background[i];
    MESSAGE(nSphere << " sphere pixels, " << nBackground << " background pixels");
    REQUIRE(nSphere >= 200);
    REQUIRE(nBackground >= 200);
    const std::vector<double> albedo(sphere.size(), 0.8);
    for (const std::uint32_t depth : {1u, 8u}) {
        CAPTURE(depth);
        const RenderResult r = renderScene(scene, settings(kSize, 256, depth, 7 + depth));
        const auto mean = r.film.mean();
        for (std::size_t i = 0; i < background.size(); ++i)
            if (background[i])
                for (int k = 0; k < 3; ++k) CHECK(mean[i * 3 + k] == 1.0f);
        report(depth == 1 ? "sphere pixels, depth 1" : "sphere pixels, depth 8", checkPixels(r, albedo, sphere));
    }
    CHECK(vk::validationMessageCount() == 0);
}

// The map tests/data/lights/sky.hdr (64 x 32: a sky gradient, a ground, and
// a 2 x 2 texel sun with ~92% of the power) turned by 30 degrees, over a
// plane facing n = normalize(1, 1.5, -0.5) (albedo a = 0.5, nothing else in
// the scene). At max depth 1 every plane point reflects
//   L = a / pi * sum over texels of L_texel * integral over the texel of max(0, n.w) dw,
// computed here from the texels OpenImageIO read, with the mapping of
// scene.h (envDirection) and a 32 x 32 midpoint rule per texel in (u, v)
// (dw = 2 pi^2 sin theta du dv). This checks the light-sampled and the
// BSDF-sampled estimates together (MIS) against the map's own integral, and
// the mapping convention: a mirrored u, or the map unrotated, give answers
// far outside the tolerance (checked).
TEST_CASE("lights: an environment map over a tilted plane gives the map's cosine-weighted integral") {
    EnvironmentOptions env;
    env.file = lightsPath("sky.hdr");
    env.rotateDegrees = 30.0f;
    const Scene scene = loadSceneWithEnvironment(lightsPath("env-plane.gltf"), env);
    const Environment& e = scene.environment;
    REQUIRE(e.width == 64);
    REQUIRE(e.height == 32);
    const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 1.5, -0.5));
    auto reflected = [&](double rotation, bool mirror) {
        constexpr int kSub = 32;
        double sum = 0.0;
        for (int y = 0; y < e.height; ++y)
            for (int x = 0; x < e.width; ++x) {
                const std::size_t t = static_cast<std::size_t>(y) * e.width + x;
                const double channelSum = e.rgb[3 * t] + e.rgb[3 * t + 1] + e.rgb[3 * t + 2];  // grey plane
                double integral = 0.0;
                for (int j = 0; j < kSub; ++j)
                    for (int i = 0; i < kSub; ++i) {
                        const double u = (x + (i + 0.5) / kSub) / e.width, v = (y + (j + 0.5) / kSub) / e.height;
                        const glm::dvec3 w = envDirection(mirror ? 1.0 - u : u, v, rotation);
                        integral += std::max(0.0, glm::dot(n, w)) * 2.0 * kPi * kPi * std::sin(kPi * v);
                    }
                sum += channelSum / 3.0 * integral / (kSub * kSub * e.width * e.height);
            }
        return 0.5 / kPi * sum;
    };
    const double rotation = 30.0 * kPi / 180.0;
    const double exact = reflected(rotation, false);
    constexpr int kSize = 16;
    const RenderResult r = renderScene(scene, settings(kSize, 1024, 1, 17));
    const std::vector<double> expected(kSize * kSize, exact);
    const std::vector<char> all(kSize * kSize, 1);
    const PixelCheck c = checkPixels(r, expected, all);
    report("env-lit plane", c);
    CHECK(c.mean.stdError < 2e-3 * exact);
    for (const auto& [rot, mirror] : {std::pair{rotation, true}, std::pair{0.0, false}}) {
        const double wrong = reflected(rot, mirror);
        MESSAGE("with " << std::string(mirror ? "u mirrored" : "no rotation") << ": " << wrong << " against " << exact
                        << " (" << (wrong - exact) / c.mean.stdError << " standard errors)");
        CHECK(std::abs(wrong - exact) > 10.0 * c.mean.stdError);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// The environment sharing the light choice: a constant environment of
// radiance c = 1 and a directional light of irradiance E = 4 pi (travelling
// along -normalize(n + (0.3, 0, 0.2))) over the plane facing n of
// env-plane.gltf (albedo a = 0.5). Estimated powers 4 pi^2 R^2 c and
// pi R^2 E give each a choice pmf of 1/2. At max depth 1:
//   L = a c + a / pi * E * cos.
// Light and BSDF densities are of the same order here (1 / 4 pi against
// cos / pi), so the MIS weights of the escaped ray and of the light sample
// must both use the pmf to sum to 1: leaving it out of lightPdfEnvironment
// biases L by 2.3% (z = -15 measured), a failure of this test.
TEST_CASE("lights: a constant environment and a directional light share the choice and MIS (pmf 1/2)") {
    Scene scene = loadWithWhiteEnvironment(lightsPath("env-plane.gltf"));
    const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 1.5, -0.5));
    PunctualLight sun;
    sun.type = PunctualLight::Type::Directional;
    sun.intensity = static_cast<float>(4.0 * kPi);
    sun.direction = glm::vec3(-glm::normalize(n + glm::dvec3(0.3, 0.0, 0.2)));
    scene.lights.push_back(sun);
    const GpuScene gpu = buildAndPack(scene);
    CHECK(gpu.emitters.at(gpu.environment).pmf == doctest::Approx(0.5).epsilon(1e-5));
    const double exact = 0.5 + 0.5 / kPi * 4.0 * kPi * glm::dot(n, -glm::dvec3(sun.direction));
    constexpr int kSize = 16;
    const RenderResult r = renderScene(scene, settings(kSize, 1024, 1, 19));
    const PixelCheck c = checkPixels(r, std::vector<double>(kSize * kSize, exact), std::vector<char>(kSize * kSize, 1));
    report("plane under a constant environment and a directional light", c);
    CHECK(c.mean.stdError < 2e-3 * exact);  // measured 1.5e-3: the 2.3% bias above is 15 standard errors
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
