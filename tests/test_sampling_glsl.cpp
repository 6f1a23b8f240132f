// Chi-square goodness-of-fit of the GLSL sampling routines, run on the device
// (shaders/sample_test.comp), against their densities (host/stats).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "../shaders/shared/bindings.h"
#include "settings/filter.h"
#include "pack/env_tables.h"
#include "pack/gpu_scene.h"
#include "measure/sample_dump.h"
#include "scene/environment.h"
#include "stats/stats.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

constexpr double kAlpha = 0.01;
constexpr std::size_t kTests = 10;  // chi-square tests in this file (Sidak correction)

std::vector<glm::vec4> drawSamples(std::uint32_t routine, std::uint32_t count, std::uint32_t seed,
                                   const std::vector<gpu::Emitter>& emitters = {},
                                   const PixelFilter& filter = {}) {
    gpu::SampleTestParams p{};
    p.count = count;
    p.routine = routine;
    p.seed = seed;
    p.emitterCount = static_cast<std::uint32_t>(emitters.size());
    return runSampleKernel(context(), p, gpu::kSamplerIndependent, emitters, filter);
}

}  // namespace

TEST_CASE("GLSL cosine-weighted hemisphere sampling matches cos(theta)/pi (chi-square)") {
    const std::uint32_t n = 1000000;
    const auto s = drawSamples(gpu::kSampleCosineHemisphere, n, 11);
    // Coordinates (phi / 2pi, cos theta) in [0,1]^2: the density there is 2 cos theta.
    std::vector<std::pair<double, double>> xy;
    for (const auto& d : s) {
        CHECK(std::abs(glm::length(glm::vec3(d)) - 1.0f) < 1e-5f);
        double phi = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x));
        if (phi < 0.0) phi += 2.0 * std::numbers::pi;
        xy.emplace_back(phi / (2.0 * std::numbers::pi), d.z);
    }
    const int rx = 33, ry = 17;  // odd resolutions
    const auto observed = stats::histogram2D(xy, rx, ry, 0.0, 1.0, 0.0, 1.0);
    const auto expected = stats::integrateExpected([](double, double c) { return 2.0 * c; }, rx, ry, 0.0, 1.0,
                                                   0.0, 1.0, n);
    const auto r = stats::chiSquareTest(observed, expected, kAlpha, kTests);
    MESSAGE(r.detail);
    CHECK(r.passed);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("GLSL uniform triangle sampling is uniform over the triangle (chi-square)") {
    const std::uint32_t n = 1000000;
    const auto s = drawSamples(gpu::kSampleTriangle, n, 12);
    std::vector<std::pair<double, double>> xy;
    for (const auto& b : s) xy.emplace_back(b.x, b.y);
    const int r = 31;
    const auto observed = stats::histogram2D(xy, r, r, 0.0, 1.0, 0.0, 1.0);
    // Density 2 on b1 + b2 <= 1. Quadrature of that discontinuous density is
    // wrong on the cells the diagonal cuts, so each cell's probability is its
    // exact area under the diagonal: the integral over x of the covered length
    // clamp(1 - x - y0, 0, y1 - y0), piecewise linear in x with breaks at
    // x = 1 - y1 and x = 1 - y0, which the trapezoid rule integrates exactly.
    std::vector<double> expected(r * r);
    for (int iy = 0; iy < r; ++iy)
        for (int ix = 0; ix < r; ++ix) {
            const double x0 = double(ix) / r, x1 = double(ix + 1) / r;
            const double y0 = double(iy) / r, y1 = double(iy + 1) / r;
            auto len = [&](double x) { return std::clamp(1.0 - x - y0, 0.0, y1 - y0); };
            std::vector<double> xs = {x0, x1};
            for (double b : {1.0 - y1, 1.0 - y0})
                if (b > x0 && b < x1) xs.push_back(b);
            std::sort(xs.begin(), xs.end());
            double area = 0.0;
            for (std::size_t k = 1; k < xs.size(); ++k) area += 0.5 * (len(xs[k - 1]) + len(xs[k])) * (xs[k] - xs[k - 1]);
            expected[iy * r + ix] = n * 2.0 * area;
        }
    const auto res = stats::chiSquareTest(observed, expected, kAlpha, kTests);
    MESSAGE(res.detail);
    CHECK(res.passed);
    CHECK(vk::validationMessageCount() == 0);
}

// sampleLight on one emissive triangle seen from the origin, of 0.26 and of
// 2.4 sr (in sampleBySolidAngle's range): the directions are uniform over its solid
// angle (chi-square over the triangle, its points mapped to the unit
// square by the inverse of the square-root map, where the density is the
// smooth A cos / (d^2 Omega)), and each sample's pdf is 1 / Omega.
TEST_CASE("GLSL emitter triangles are sampled uniformly over their solid angle (chi-square) with pdf 1 / Omega") {
  for (const double near : {1.0, 0.25}) {
    CAPTURE(near);
    const glm::dvec3 v0(-0.3, -0.2, near), v1(0.5, -0.1, 1.2 * near), v2(0.0, 0.6, 0.9 * near);
    const glm::dvec3 cr = glm::cross(v1 - v0, v2 - v0);
    const double area = 0.5 * glm::length(cr);
    const glm::dvec3 normal = glm::normalize(cr);
    const glm::dvec3 a = glm::normalize(v0), b = glm::normalize(v1), c = glm::normalize(v2);
    const double omega = 2.0 * std::atan2(std::abs(glm::dot(a, glm::cross(b, c))),
                                          1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a));
    MESSAGE("solid angle " << omega);
    REQUIRE(omega > 3e-4);
    GpuScene g;
    gpu::Emitter e{};
    e.kind = gpu::kLightTriangle;
    e.v0 = glm::vec3(v0);
    e.e1 = glm::vec3(v1 - v0);
    e.e2 = glm::vec3(v2 - v0);
    e.area = float(area);
    e.radiance = glm::vec3(1.0f);
    e.flags = gpu::kMaterialDoubleSided;
    g.emitters = {e};
    buildAliasTable({1.0}, g.emitters);
    g.features.emitters = true;
    gpu::SampleTestParams p{};
    p.count = 1000000;
    p.routine = gpu::kSampleLight;
    p.seed = 41;
    const auto s = runSampleKernel(context(), p, gpu::kSamplerIndependent, {}, {}, &g);
    std::vector<std::pair<double, double>> xy;
    std::size_t pdfAgrees = 0;
    for (const auto& v : s) {
        const glm::dvec3 wi(v.x, v.y, v.z);
        const glm::dvec3 x = wi * (glm::dot(v0, normal) / glm::dot(wi, normal));
        // Barycentrics of x, then the square-root map's inverse.
        const glm::dvec3 d = x - v0, e1 = v1 - v0, e2 = v2 - v0;
        const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
        const double d20 = glm::dot(d, e1), d21 = glm::dot(d, e2), den = d00 * d11 - d01 * d01;
        const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den;
        const double sum = b1 + b2;
        xy.emplace_back(sum * sum, sum > 0.0 ? b2 / sum : 0.0);
        pdfAgrees += std::abs(double(v.w) * omega - 1.0) < 1e-3;
    }
    CHECK(pdfAgrees == s.size());
    const int r = 24, q = 8;  // cells a side, quadrature points a cell side
    const auto observed = stats::histogram2D(xy, r, r, 0.0, 1.0, 0.0, 1.0);
    std::vector<double> expected(r * r, 0.0);
    double total = 0.0;
    for (int iy = 0; iy < r; ++iy)
        for (int ix = 0; ix < r; ++ix) {
            double sum = 0.0;
            for (int j = 0; j < q; ++j)
                for (int k = 0; k < q; ++k) {
                    const double sx = (ix + (k + 0.5) / q) / r, sy = (iy + (j + 0.5) / q) / r;
                    const double su = std::sqrt(sx);
                    const glm::dvec3 x = v0 + su * (1.0 - sy) * (v1 - v0) + su * sy * (v2 - v0);
                    const double d2 = glm::dot(x, x);
                    sum += std::abs(glm::dot(x, normal)) / (d2 * std::sqrt(d2));
                }
            expected[iy * r + ix] = p.count * area / omega * sum / (q * q * r * r);
            total += expected[iy * r + ix];
        }
    CHECK(total == doctest::Approx(double(p.count)).epsilon(1e-3));  // the density integrates to 1
    const auto res = stats::chiSquareTest(observed, expected, kAlpha, kTests);
    MESSAGE(res.detail);
    CHECK(res.passed);
  }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("GLSL emitter choice through the alias table follows the power pmf (chi-square)") {
    std::vector<double> weights = {5.0, 1.0, 0.5, 3.0, 0.0, 8.0, 0.25, 2.0, 1.5};
    std::vector<gpu::Emitter> emitters(weights.size());
    buildAliasTable(weights, emitters);
    for (std::size_t i = 0; i < emitters.size(); ++i) emitters[i].radiance.x = static_cast<float>(i);
    const std::uint32_t n = 500000;
    const auto s = drawSamples(gpu::kSampleEmitterChoice, n, 13, emitters);
    std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
    double total = 0.0;
    for (double w : weights) total += w;
    for (std::size_t i = 0; i < weights.size(); ++i) expected[i] = n * weights[i] / total;
    for (const auto& v : s) observed.at(static_cast<std::size_t>(v.x)) += 1.0;
    CHECK(observed[4] == 0.0);  // zero power: never chosen
    const auto r = stats::chiSquareTest(observed, expected, kAlpha, kTests);
    MESSAGE(r.detail);
    CHECK(r.passed);
    CHECK(vk::validationMessageCount() == 0);
}

// Filter importance sampling: offsets drawn by the shader from the host's
// inverse-CDF table follow f(x) f(y) / (integral of f)^2.
TEST_CASE("GLSL pixel filter sampling follows the filter (chi-square: box, tent, gaussian, blackman-harris)") {
    for (const char* name : {"box", "tent", "gaussian", "blackman-harris"}) {
        const PixelFilter f = filterByName(name);
        const std::string filterName = name;
        CAPTURE(filterName);
        const std::uint32_t n = 500000;
        const auto s = drawSamples(gpu::kSampleFilter, n, 21, {}, f);
        std::vector<std::pair<double, double>> xy;
        for (const auto& v : s) {
            CHECK(std::abs(v.x) <= f.radius);
            CHECK(std::abs(v.y) <= f.radius);
            xy.emplace_back(v.x, v.y);
        }
        double norm = 0.0;  // integral of the 1D profile (fine midpoint rule)
        const int steps = 200000;
        for (int i = 0; i < steps; ++i)
            norm += filterValue(f, -f.radius + 2.0 * f.radius * (i + 0.5) / steps) * 2.0 * f.radius / steps;
        const double r = f.radius;
        const int res = 25;
        const auto observed = stats::histogram2D(xy, res, res, -r, r, -r, r);
        const auto expected = stats::integrateExpected(
            [&](double x, double y) { return filterValue(f, x) * filterValue(f, y) / (norm * norm); }, res, res,
            -r, r, -r, r, n, 16);
        const auto result = stats::chiSquareTest(observed, expected, kAlpha, kTests);
        MESSAGE(filterName << ": " << result.detail);
        CHECK(result.passed);
    }
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// tests/data/lights/sky.hdr (64 x 32: sky gradient, ground, a 2 x 2 texel sun
// with ~92% of the power) turned by 30 degrees about +Y, the only light.
struct SkyLight {
    Scene scene;
    GpuScene gpu;
    double rotation = 30.0 * std::numbers::pi / 180.0;
    std::vector<double> texelProb;  // lum * sin(row centre), normalised: the intended distribution
    SkyLight() {
        EnvironmentOptions o;
        o.file = sourcePath("tests/data/lights/sky.hdr");
        o.rotateDegrees = 30.0f;
        scene.environment = makeEnvironment(o);
        gpu = buildAndPack(scene);
        const Environment& e = scene.environment;
        double total = 0.0;
        for (int y = 0; y < e.height; ++y)
            for (int x = 0; x < e.width; ++x) {
                const std::size_t t = static_cast<std::size_t>(y) * e.width + x;
                const glm::dvec3 c(e.rgb[3 * t], e.rgb[3 * t + 1], e.rgb[3 * t + 2]);
                texelProb.push_back(luminance(c) * std::sin(std::numbers::pi * (y + 0.5) / e.height));
                total += texelProb.back();
            }
        for (double& p : texelProb) p /= total;
    }
    // Texel of world direction d by the host's mapping (pack/env_tables.h).
    std::size_t texel(const glm::dvec3& d) const {
        const glm::dvec2 uv = envUv(d, rotation);
        const int w = scene.environment.width, h = scene.environment.height;
        const int x = std::min(static_cast<int>(uv.x * w), w - 1), y = std::min(static_cast<int>(uv.y * h), h - 1);
        return static_cast<std::size_t>(y) * w + x;
    }
    // The intended solid-angle density: p_texel * W * H / (2 pi^2 sin theta).
    double pdf(const glm::dvec3& d) const {
        const double sinTheta = std::sqrt(d.x * d.x + d.z * d.z) / glm::length(d);
        const double texels = static_cast<double>(texelProb.size());
        return texelProb[texel(d)] * texels / (2.0 * std::numbers::pi * std::numbers::pi * sinTheta);
    }
};

}  // namespace

// sampleLight (lights.glsl) on a scene lit only by the map: the chosen texels
// follow luminance x sin(theta) (chi-square over the 2048 texels, the host
// mapping the directions back), and the pdf returned with each sample is the
// intended density, to float precision, except on texel borders.
TEST_CASE("GLSL environment map sampling follows luminance x sin(theta) (chi-square) and returns its pdf") {
    const SkyLight sky;
    REQUIRE(sky.gpu.emitters.size() == 1);
    gpu::SampleTestParams p{};
    p.count = 1000000;
    p.routine = gpu::kSampleLight;
    p.seed = 31;
    const auto s = runSampleKernel(context(), p, gpu::kSamplerIndependent, {}, {}, &sky.gpu);
    std::vector<double> observed(sky.texelProb.size(), 0.0), expected(sky.texelProb.size());
    std::size_t pdfAgrees = 0;
    double worst = 0.0;
    for (const auto& v : s) {
        const glm::dvec3 d(v.x, v.y, v.z);
        CHECK(std::abs(glm::length(d) - 1.0) < 1e-5);
        observed[sky.texel(d)] += 1.0;
        const double rel = std::abs(v.w / sky.pdf(d) - 1.0);
        pdfAgrees += rel < 1e-3;
        worst = std::max(worst, rel);
    }
    for (std::size_t t = 0; t < expected.size(); ++t) expected[t] = p.count * sky.texelProb[t];
    const auto r = stats::chiSquareTest(observed, expected, kAlpha, kTests);
    MESSAGE(r.detail);
    CHECK(r.passed);
    MESSAGE(pdfAgrees << " of " << p.count << " sample pdfs within 1e-3 of the intended density; largest relative difference " << worst);
    CHECK(static_cast<double>(pdfAgrees) >= 0.999 * p.count);
    CHECK(vk::validationMessageCount() == 0);
}

// lightPdfEnvironment integrates to 1 over the sphere: midpoint rule on a
// 1024 x 1024 grid in (phi, z) about +Z (dw = dphi dz; cells of equal solid
// angle 4 pi / 2^20), unaligned with the map's rows and columns. Texel
// borders cutting cells (chiefly the sun's, where the density is ~600x the
// sky's) make the rule's error: measured 1.27e-3 for the shader's pdf and
// 1.24e-3 for the intended density (which integrates to exactly 1) on the
// same grid. Tolerances: 3e-3 from 1, 3e-4 from the intended density's sum.
// A wrong Jacobian (sin theta, 2 pi^2) or normalisation is off by >= 10%.
// The pdf is also the intended density point by point (but on texel borders).
TEST_CASE("GLSL environment pdf integrates to 1 over the sphere and is the intended density") {
    const SkyLight sky;
    gpu::SampleTestParams p{};
    p.width = 1024;
    p.count = 1024 * 1024;
    p.routine = gpu::kSampleEnvironmentPdf;
    const auto s = runSampleKernel(context(), p, gpu::kSamplerIndependent, {}, {}, &sky.gpu);
    double integral = 0.0, hostIntegral = 0.0;
    std::size_t agrees = 0;
    for (const auto& v : s) {
        const double intended = sky.pdf(glm::dvec3(v.x, v.y, v.z));
        integral += static_cast<double>(v.w) * 4.0 * std::numbers::pi / p.count;
        hostIntegral += intended * 4.0 * std::numbers::pi / p.count;
        agrees += std::abs(v.w / intended - 1.0) < 1e-3;
    }
    MESSAGE("integral " << integral << " (the intended density on the same grid: " << hostIntegral << "); " << agrees
                        << " of " << p.count << " points agree with the intended density");
    CHECK(std::abs(integral - 1.0) < 3e-3);
    CHECK(std::abs(integral - hostIntegral) < 3e-4);
    CHECK(static_cast<double>(agrees) >= 0.999 * p.count);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
