// The light tree (pack/light_tree.h, shaders/lib/light_tree.glsl): its build
// (every bounded light one leaf reached by its trail, nodes bounding their
// lights, depth within the trail's 32 bits), its sampling on the device
// against its own probabilities (chi-square at random shading points; the
// probabilities sum to 1), and renders with the tree, its light samples
// resampled from several descents (--light-candidates), agreeing with
// renders choosing by power (per-pixel Z-test).
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <cmath>
#include <numbers>
#include <random>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "measure/sample_dump.h"
#include "pack/gpu_scene.h"
#include "pack/light_tree.h"
#include "stages/stages.h"
#include "stats/stats.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

namespace {

constexpr double kAlpha = 0.01;

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
}

// n small emissive triangles scattered in a box, facing random ways, with
// random powers; then point lights, spot lights and (outside the tree) one
// directional light.
std::vector<gpu::Emitter> randomLights(std::size_t triangles, std::size_t points, std::size_t spots,
                                       std::vector<double>& weights, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto dir = [&] {
        const float z = 2.0f * u(rng) - 1.0f, phi = 2.0f * float(std::numbers::pi) * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    std::vector<gpu::Emitter> out;
    for (std::size_t i = 0; i < triangles; ++i) {
        gpu::Emitter e{};
        e.kind = gpu::kLightTriangle;
        e.v0 = glm::vec3(10.0f * u(rng), 4.0f * u(rng), 10.0f * u(rng));
        const glm::vec3 n = dir();
        const glm::vec3 t = glm::normalize(glm::cross(n, std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
        const glm::vec3 b = glm::cross(n, t);
        const float size = 0.05f + 0.3f * u(rng);
        e.e1 = size * t;
        e.e2 = size * b;
        e.area = 0.5f * glm::length(glm::cross(e.e1, e.e2));
        e.triangle = static_cast<std::uint32_t>(i);
        e.flags = i % 5 == 0 ? gpu::kMaterialDoubleSided : 0u;
        out.push_back(e);
        weights.push_back(e.area * (0.1 + 10.0 * u(rng)));
    }
    for (std::size_t i = 0; i < points + spots; ++i) {
        gpu::Emitter e{};
        e.kind = i < points ? gpu::kLightPoint : gpu::kLightSpot;
        e.v0 = glm::vec3(10.0f * u(rng), 4.0f * u(rng), 10.0f * u(rng));
        if (e.kind == gpu::kLightSpot) {
            e.e1 = dir();
            const double cosOuter = std::cos(0.3 + 0.8 * u(rng)), cosInner = std::cos(0.1 + 0.2 * u(rng));
            const double scale = 1.0 / std::max(0.001, cosInner - cosOuter);
            e.e2 = glm::vec3(float(scale), float(-cosOuter * scale), 0.0f);
        }
        out.push_back(e);
        weights.push_back(1.0 + 20.0 * u(rng));
    }
    gpu::Emitter sun{};
    sun.kind = gpu::kLightDirectional;
    sun.e1 = glm::vec3(0.0f, -1.0f, 0.0f);
    out.push_back(sun);
    weights.push_back(50.0);
    return out;
}

// The leaf that `trail` leads to from the root.
std::uint32_t followTrail(const LightTree& tree, std::uint32_t trail) {
    std::uint32_t i = 0;
    while ((tree.nodes[i].link & gpu::kLightNodeLeaf) == 0u) {
        i = (trail & 1u) == 0u ? i + 1 : tree.nodes[i].link & gpu::kLightNodeIndex;
        trail >>= 1u;
    }
    return i;
}

void checkTree(const LightTree& tree, const std::vector<gpu::Emitter>& emitters, std::size_t bounded) {
    REQUIRE(tree.nodes.size() == 2 * bounded - 1);
    CHECK(tree.depth <= kLightTreeMaxDepth);
    std::vector<int> seen(emitters.size(), 0);
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        const gpu::Emitter& e = emitters[i];
        if (isInfiniteLight(e)) continue;
        // Every node on the light's path holds its points in its sphere.
        std::uint32_t node = 0, trail = e.trail;
        for (;;) {
            const gpu::LightNode& n = tree.nodes[node];
            const glm::dvec3 v0(e.v0), c(n.centre);
            const glm::dvec3 corners[3] = {v0, v0 + glm::dvec3(e.e1), v0 + glm::dvec3(e.e2)};
            for (int k = 0; k < (e.kind == gpu::kLightTriangle ? 3 : 1); ++k)
                CHECK(glm::dot(corners[k] - c, corners[k] - c) <= double(n.radius) * double(n.radius));
            // ... and its orientation in its cone: a triangle's normal, a
            // spot's axis with its inner cone; a point light needs them all.
            const double thetaO = std::acos(double(n.cosTheta_o));
            const glm::dvec3 axis(n.axis);
            if (e.kind == gpu::kLightTriangle)
                CHECK(angleBetween(axis, glm::cross(glm::dvec3(e.e1), glm::dvec3(e.e2))) <= thetaO);
            if (e.kind == gpu::kLightSpot) CHECK(angleBetween(axis, glm::dvec3(e.e1)) <= thetaO);
            if (e.kind == gpu::kLightPoint) CHECK(n.cosTheta_o == -1.0f);
            if ((n.link & gpu::kLightNodeLeaf) != 0u) break;
            node = (trail & 1u) == 0u ? node + 1 : n.link & gpu::kLightNodeIndex;
            trail >>= 1u;
        }
        const std::uint32_t leaf = followTrail(tree, e.trail);
        CHECK((tree.nodes[leaf].link & gpu::kLightNodeIndex) == i);
        ++seen[i];
    }
    for (std::size_t i = 0; i < bounded; ++i) CHECK(seen[i] == 1);
    // Each interior node bounds its children.
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        const gpu::LightNode& n = tree.nodes[i];
        if ((n.link & gpu::kLightNodeLeaf) != 0u) continue;
        CAPTURE(i);
        const gpu::LightNode& second = tree.nodes[n.link & gpu::kLightNodeIndex];
        for (const gpu::LightNode& c : {tree.nodes[i + 1], second}) {
            CHECK(n.cosTheta_e <= c.cosTheta_e);
            CHECK(std::abs(n.sinTheta_o * n.sinTheta_o + n.cosTheta_o * n.cosTheta_o - 1.0f) < 1e-5f);
            if ((c.link & gpu::kLightNodeTwoSided) != 0u) CHECK((n.link & gpu::kLightNodeTwoSided) != 0u);
        }
        CHECK(n.power == doctest::Approx(tree.nodes[i + 1].power + second.power).epsilon(1e-5));
    }
}

// Whether light e can send anything to p with normal n (0: any direction):
// p in front of a one-sided triangle, not all of it in p's tangent plane;
// inside a spot's outer cone.
bool canLight(const gpu::Emitter& e, const glm::vec3& p, const glm::vec3& n) {
    const glm::dvec3 pd(p), nd(n), v0(e.v0);
    if (e.kind == gpu::kLightPoint) return true;
    if (e.kind == gpu::kLightSpot) {
        const double cosOuter = -double(e.e2.y) / double(e.e2.x);
        return glm::dot(glm::normalize(pd - v0), glm::dvec3(e.e1)) > cosOuter + 1e-6;
    }
    const glm::dvec3 corners[3] = {v0, v0 + glm::dvec3(e.e1), v0 + glm::dvec3(e.e2)};
    const glm::dvec3 normal = glm::cross(glm::dvec3(e.e1), glm::dvec3(e.e2));
    const bool front = glm::dot(pd - v0, normal) > 1e-9;
    if (!front && (e.flags & gpu::kMaterialDoubleSided) == 0u) return false;
    if (glm::dot(nd, nd) == 0.0) return glm::dot(pd - v0, normal) != 0.0;
    for (const glm::dvec3& c : corners)
        if (std::abs(glm::dot(c - pd, nd)) > 1e-6) return true;
    return false;
}

// A GpuScene of these lights alone, packed with the tree as packScene does.
GpuScene lightsScene(std::vector<gpu::Emitter> emitters, const std::vector<double>& weights) {
    GpuScene g;
    buildAliasTable(weights, emitters);
    g.lightTree = buildLightTree(emitters, weights).nodes;
    double total = 0.0, bounded = 0.0;
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        total += weights[i];
        if (!isInfiniteLight(emitters[i])) bounded += weights[i];
    }
    g.lightTreeProb = bounded / total;
    g.emitters = std::move(emitters);
    g.features.emitters = true;
    g.features.bits = gpu::kFeatureLightTree | gpu::kFeaturePunctual;
    return g;
}

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("light tree: every bounded light is the leaf its trail leads to, and each node bounds its children") {
    std::vector<double> weights;
    std::vector<gpu::Emitter> emitters = randomLights(700, 20, 20, weights, 7);
    const LightTree tree = buildLightTree(emitters, weights);
    checkTree(tree, emitters, 740);
    CHECK(tree.depth <= 24);  // balanced enough: log2(740) is 9.5
    MESSAGE("depth " << tree.depth);
    double total = 0.0;
    for (std::size_t i = 0; i + 1 < weights.size(); ++i) total += weights[i];
    CHECK(tree.nodes[0].power == doctest::Approx(total).epsilon(1e-5));
    // One light: a leaf root.
    std::vector<double> w1{2.0};
    std::vector<gpu::Emitter> one(emitters.begin(), emitters.begin() + 1);
    CHECK(buildLightTree(one, w1).nodes.size() == 1);
    // Only lights at infinity: no tree.
    std::vector<double> w2{1.0};
    std::vector<gpu::Emitter> sun(emitters.end() - 1, emitters.end());
    CHECK_THROWS_AS(buildLightTree(sun, w2), std::invalid_argument);
}

TEST_CASE("light tree: lights the split would peel off one by one still get trails of at most 32 levels") {
    // Point lights at x = 1.5^i: each split's buckets put all but the
    // farthest light in the first, so the cost alone would make a chain.
    std::vector<gpu::Emitter> emitters;
    std::vector<double> weights;
    for (int i = 0; i < 300; ++i) {
        gpu::Emitter e{};
        e.kind = gpu::kLightPoint;
        e.v0 = glm::vec3(std::pow(1.5f, float(i % 150)) * (i < 150 ? 1.0f : -1.0f), 0.0f, 0.0f);
        emitters.push_back(e);
        weights.push_back(1.0);
    }
    const LightTree tree = buildLightTree(emitters, weights);
    checkTree(tree, emitters, emitters.size());
    MESSAGE("depth " << tree.depth);
    CHECK(tree.depth <= kLightTreeMaxDepth);
}

TEST_CASE("light tree: lights at the float range's ends, whose bounds overflow, still get one leaf each") {
    std::vector<gpu::Emitter> emitters;
    std::vector<double> weights;
    for (int i = 0; i < 40; ++i) {
        gpu::Emitter e{};
        e.kind = gpu::kLightTriangle;
        const float big = (i % 2 ? 1.0f : -1.0f) * 3.0e38f;
        e.v0 = glm::vec3(big, float(i), 0.0f);
        e.e1 = glm::vec3(-2.0f * big, 0.0f, 0.0f);  // inf: the far vertex past the range
        e.e2 = glm::vec3(0.0f, 1.0f, float(i % 3));
        emitters.push_back(e);
        weights.push_back(i % 5 == 0 ? std::numeric_limits<double>::infinity() : 1.0);
    }
    const LightTree tree = buildLightTree(emitters, weights);
    REQUIRE(tree.nodes.size() == 2 * emitters.size() - 1);
    for (std::size_t i = 0; i < emitters.size(); ++i)
        CHECK((tree.nodes[followTrail(tree, emitters[i].trail)].link & gpu::kLightNodeIndex) == i);
}

TEST_CASE("light tree: a swept light (a moving lamp) is bounded over its sweep, its cone every direction where it turns") {
    gpu::Emitter e{};
    e.kind = gpu::kLightTriangle;
    e.v0 = glm::vec3(0.0f);
    e.e1 = glm::vec3(0.1f, 0.0f, 0.0f);
    e.e2 = glm::vec3(0.0f, 0.1f, 0.0f);
    std::vector<gpu::Emitter> one{e};
    const std::vector<double> w{1.0};
    const LightTree still = buildLightTree(one, w);
    REQUIRE(still.nodes.size() == 1);
    CHECK(still.nodes[0].radius < 0.1f);
    CHECK(still.nodes[0].cosTheta_o == doctest::Approx(1.0f));
    SweptLight swept{0, {-2.0, 0.0, 0.0}, {2.0, 0.1, 0.0}, false};
    const LightTree sliding = buildLightTree(one, w, {swept});
    const gpu::LightNode& n = sliding.nodes.at(0);
    for (const glm::vec3 corner : {glm::vec3(-2.0f, 0.0f, 0.0f), glm::vec3(2.0f, 0.1f, 0.0f)})
        CHECK(glm::length(corner - n.centre) <= n.radius);
    CHECK(n.cosTheta_o == doctest::Approx(1.0f));  // it slides: its normal stays
    swept.turns = true;
    CHECK(buildLightTree(one, w, {swept}).nodes.at(0).cosTheta_o == -1.0f);
    swept.emitter = 1;  // not an emitter
    CHECK_THROWS_AS(buildLightTree(one, w, {swept}), std::invalid_argument);
}

TEST_CASE("light sampler: auto keeps the tree from kLightTreeMinClusters clusters on, power never, tree always") {
    CHECK(!useLightTree(LightSampler::Auto, kLightTreeMinClusters - 1));
    CHECK(useLightTree(LightSampler::Auto, kLightTreeMinClusters));
    CHECK(!useLightTree(LightSampler::Power, 1000));
    CHECK(useLightTree(LightSampler::Tree, 1));
    CHECK(!useLightTree(LightSampler::Tree, 0));
    // Clusters: 512 point lights in 4 tight groups far apart are 4; spread
    // out on an 8 x 8 x 8 grid, more than kLightTreeMinClusters.
    std::vector<gpu::Emitter> grouped, spread;
    std::vector<double> weights(512, 1.0);
    for (int i = 0; i < 512; ++i) {
        gpu::Emitter e{};
        e.kind = gpu::kLightPoint;
        const glm::vec3 cell(float(i % 8), float(i / 8 % 8), float(i / 64));
        e.v0 = glm::vec3(100.0f * float(i / 128), 0.0f, 0.0f) + 0.01f * cell;
        grouped.push_back(e);
        e.v0 = cell;
        spread.push_back(e);
    }
    CHECK(lightClusters(buildLightTree(grouped, weights)) == 4);
    CHECK(lightClusters(buildLightTree(spread, weights)) >= kLightTreeMinClusters);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("render");

// At random shading points (inside the lights' box and outside, random
// normals) sampleLightTree's choices follow the probabilities lightTreePmf
// gives every bounded light, and no light with the rest (chi-square, one
// test per point), and the pmf it returns with a choice is the one
// evaluated for it.
TEST_CASE("GLSL light tree: its choices follow its own probabilities (chi-square), which sum to at most 1") {
    std::vector<double> weights;
    const std::vector<gpu::Emitter> lights = randomLights(300, 6, 6, weights, 11);
    const GpuScene g = lightsScene(lights, weights);
    const std::size_t bounded = lights.size() - 1;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-2.0f, 12.0f);
    constexpr int kPoints = 6;
    for (int k = 0; k < kPoints; ++k) {
        const glm::vec3 p(u(rng), 0.5f * u(rng), u(rng));
        glm::vec3 n = glm::normalize(glm::vec3(u(rng) - 5.0f, u(rng) - 5.0f, u(rng) - 5.0f));
        if (k == 0) n = glm::vec3(0.0f);  // no receiver cosine
        CAPTURE(k);
        gpu::SampleTestParams params{};
        params.bsdf0 = glm::vec4(p, 0.0f);
        params.bsdf1 = glm::vec4(n, 0.0f);
        params.routine = gpu::kLightTreePmf;
        params.count = static_cast<std::uint32_t>(bounded);
        const auto pmfs = runSampleKernel(context(), params, gpu::kSamplerIndependent, {}, {}, &g);
        // A descent can end with no light where both children of a node it
        // entered bound 0 (the parent's bound is looser): that share is the
        // last bin, and the lights' probabilities with it sum to 1.
        double sum = 0.0;
        for (const auto& v : pmfs) sum += v.x;
        CHECK(sum <= 1.0 + 1e-5);
        MESSAGE("probability of no light: " << 1.0 - sum);
        params.routine = gpu::kSampleLightTree;
        params.count = 400000;
        params.seed = 100 + static_cast<std::uint32_t>(k);
        const auto s = runSampleKernel(context(), params, gpu::kSamplerIndependent, {}, {}, &g);
        std::vector<double> observed(bounded + 1, 0.0), expected(bounded + 1);
        std::size_t agree = 0;
        for (const auto& v : s) {
            if (v.x < 0.0f) {
                observed[bounded] += 1.0;
                agree += v.y == 0.0f;
                continue;
            }
            const std::size_t light = static_cast<std::size_t>(v.x);
            REQUIRE(light < bounded);
            observed[light] += 1.0;
            agree += v.y == v.z && std::abs(v.y / pmfs[light].x - 1.0f) < 1e-5f;
        }
        CHECK(agree == s.size());
        for (std::size_t i = 0; i < bounded; ++i) {
            expected[i] = params.count * double(pmfs[i].x);
            if (pmfs[i].x == 0.0f) CHECK(observed[i] == 0.0);
            // A light that can light p has a probability: unbiased.
            CAPTURE(i);
            if (canLight(lights[i], p, n)) CHECK(pmfs[i].x > 0.0f);
        }
        expected[bounded] = params.count * std::max(0.0, 1.0 - sum);
        const auto r = stats::chiSquareTest(observed, expected, kAlpha, kPoints);
        MESSAGE(r.detail);
        CHECK(r.passed);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// The tree read through its storage buffer (--reads texel: only the BVH
// through texel views) and through its texel view (every array): the same
// bits.
TEST_CASE("the light tree gives the same image read through storage buffers as through texel views") {
    RenderSettings s;
    s.width = 16;
    s.height = 16;
    s.spp = 4;
    s.lightSampler = LightSampler::Tree;
    s.reads = ReadMode::Texel;
    const Rendered storage = renderFile("scenes/many-lights.gltf", s);
    s.reads = ReadMode::Auto;  // lavapipe: every array through texel views
    const Rendered texel = renderFile("scenes/many-lights.gltf", s);
    CHECK(storage.result.reads != texel.result.reads);
    CHECK(sameImage(storage.result.film, texel.result.film));
    CHECK(vk::validationMessageCount() == 0);
}

// The many-light room (256 small lamps) with the tree, one descent a light
// sample and 2 (the default) and 3 resampled, and by power: the same image
// by the per-pixel Z-test (at least 99.75% of pixels accepted at alpha 0.01
// with Sidak correction, as the invariance suite).
TEST_CASE("the many-light room renders the same image with the light tree, its candidates resampled, as by power (per-pixel Z-test)") {
    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.spp = 64;
    s.maxDepth = 4;
    s.seed = 3;
    s.lightSampler = LightSampler::Power;
    Rendered power = renderFile("scenes/many-lights.gltf", s);
    CHECK((power.gpu.features.bits & gpu::kFeatureLightTree) == 0u);
    const auto refMean = power.result.film.mean(), refVar = power.result.film.varianceOfMean();
    s.lightSampler = LightSampler::Tree;
    double previous = 0.0;  // the last summed relative variance of the mean
    for (const std::uint32_t candidates : {1u, 0u, 3u}) {  // 0: the default, 2
        CAPTURE(candidates);
        s.lightCandidates = candidates;
        s.seed = 4 + candidates;
        Rendered tree = renderFile("scenes/many-lights.gltf", s);
        CHECK((tree.gpu.features.bits & gpu::kFeatureLightTree) != 0u);
        const auto mean = tree.result.film.mean(), var = tree.result.film.varianceOfMean();
        const stats::ZTestResult z =
            stats::perPixelZTest(mean.data(), var.data(), refMean.data(), refVar.data(), mean.size());
        CAPTURE(z.acceptedFraction);
        CAPTURE(z.zThreshold);
        CHECK(z.passed);
        // The tree's point, and resampling's: less variance at the same spp,
        // each pixel's variance of the mean relative to its mean squared
        // (relMSE's terms, eps 0.01).
        double vTree = 0.0, vPower = 0.0;
        for (std::size_t i = 0; i < var.size(); ++i) {
            vTree += var[i] / (double(refMean[i]) * refMean[i] + 0.01);
            vPower += refVar[i] / (double(refMean[i]) * refMean[i] + 0.01);
        }
        MESSAGE("summed relative variance of the mean, tree / power: " << vTree / vPower);
        CHECK(vTree < (previous > 0.0 ? previous : vPower));
        previous = vTree;
        CHECK(vk::validationMessageCount() == 0);
    }
}

// Resampling where the tree holds point and spot lights besides the lamps'
// triangles, and where an environment takes the alias table's step first
// (FrameUniforms::scene.y below 1): the room with a point and a spot light
// added, a constant sky about it (closed off: its samples find the walls),
// with two candidates and by power: the same image by the per-pixel Z-test.
TEST_CASE("resampled tree candidates among point, spot and triangle lights, after the sky's step, match power (per-pixel Z-test)") {
    nlohmann::json g = nlohmann::json::parse(std::ifstream(sourcePath("scenes/many-lights.gltf")));
    g["extensionsUsed"].push_back("KHR_lights_punctual");
    g["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::array(
        {{{"type", "point"}, {"color", {1.0, 0.9, 0.8}}, {"intensity", 40.0}},
         {{"type", "spot"}, {"color", {0.8, 0.9, 1.0}}, {"intensity", 80.0},
          {"spot", {{"innerConeAngle", 0.3}, {"outerConeAngle", 0.6}}}}});
    const std::size_t first = g["nodes"].size();
    g["nodes"].push_back({{"translation", {-1.5, 2.0, -1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    // The spot looks down: -Z turned -90 degrees about X.
    g["nodes"].push_back({{"translation", {1.0, 2.6, -0.5}},
                          {"rotation", {-0.70710678, 0.0, 0.0, 0.70710678}},
                          {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    g["scenes"][0]["nodes"].push_back(first);
    g["scenes"][0]["nodes"].push_back(first + 1);
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("strata-test-room-punctual-" + std::to_string(::getpid()) + ".gltf");
    std::ofstream(file) << g.dump();

    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.spp = 64;
    s.maxDepth = 4;
    auto renderRoom = [&](LightSampler sampler, std::uint32_t seed) {
        s.lightSampler = sampler;
        s.seed = seed;
        SceneRequest request = keptRequest(s);
        request.file = file.string();
        request.env.hasColor = true;
        request.env.color = glm::vec3(0.2f);
        const HostScene host = prepareScene(request);
        CHECK(((host.gpu.features.bits & gpu::kFeatureLightTree) != 0u) == (sampler == LightSampler::Tree));
        CHECK((host.gpu.features.bits & gpu::kFeaturePunctual) != 0u);
        RenderResult r = render(context(), uploadPrepared(context(), request, host.gpu), host.camera, s);
        CHECK(r.nonFinite == 0);
        return r;
    };
    const RenderResult power = renderRoom(LightSampler::Power, 11);
    const RenderResult tree = renderRoom(LightSampler::Tree, 12);  // two candidates, the default
    std::filesystem::remove(file);
    const auto mean = tree.film.mean(), var = tree.film.varianceOfMean();
    const auto refMean = power.film.mean(), refVar = power.film.varianceOfMean();
    const stats::ZTestResult z = stats::perPixelZTest(mean.data(), var.data(), refMean.data(), refVar.data(), mean.size());
    CAPTURE(z.acceptedFraction);
    CAPTURE(z.zThreshold);
    CHECK(z.passed);
    // The strong point and spot lights leave each pixel too noisy to see a
    // bias of a few tens of percent in their share; the image's sum (the
    // pixels independent) sees one of a few percent: |z| below 4 (alpha
    // 6e-5). Seen to fail at z 70 with the punctual lights' resampling
    // weight 1.3 times what it should be, and at z 35 with it left at 1.
    double sum = 0.0, refSum = 0.0, sumVar = 0.0;
    for (std::size_t i = 0; i < mean.size(); ++i) {
        sum += mean[i];
        refSum += refMean[i];
        sumVar += double(var[i]) + double(refVar[i]);
    }
    const double zSum = (sum - refSum) / std::sqrt(sumVar);
    MESSAGE("image sums, tree / power: " << sum / refSum << " (z " << zSum << ")");
    CHECK(std::abs(zSum) < 4.0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
