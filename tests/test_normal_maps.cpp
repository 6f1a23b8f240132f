// Normal maps against Lambert's polygon irradiance, emissive textures read
// by next-event estimation, texture-coordinate decoding and generated
// tangents. The real shaders on lavapipe, validation on. Scenes:
// tests/data/textures/, written by scripts/make_texture_scenes.py, whose
// constants are mirrored here.
#include <doctest/doctest.h>

#include <array>
#include <cmath>

#include "scene/tangents.h"
#include "stats/stats.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

const std::string kDir = "tests/data/textures/";

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
