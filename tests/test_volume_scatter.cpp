// KHR_materials_volume_scatter: homogeneous media inside closed meshes
// (shaders/lib/medium.glsl, the volscatter axis). The GLSL phase function
// and free flights run by sample_test.comp (chi-square against their
// densities, the flights' weights against the transmittance), render tests
// against known answers (scenes from scripts/make_medium_tests.py:
// tests/data/media/), and the loader.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "cli_util.h"
#include "gltf_util.h"
#include "test_util.h"
#include "measure/sample_dump.h"
#include "pack/gpu_scene.h"
#include "scene/media_check.h"
#include "stats/stats.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::size_t kChiTests = 5;  // chi-square tests in this file (Sidak correction)

// The extension's phase function, wo towards the viewer, wi towards the light.
double phaseHG(double cosOI, double g) {
    const double d = 1.0 + g * g + 2.0 * g * cosOI;
    return (1.0 - g * g) / (4.0 * kPi * d * std::sqrt(d));
}

// The draft's single-scatter albedo from the multi-scatter albedo (Kulla and Conty 2017).
double singleScatter(double ms) {
    const double r = 4.09712 + 4.20863 * ms - std::sqrt(9.59217 + 41.6808 * ms + 17.7126 * ms * ms);
    return 1.0 - r * r;
}

std::vector<glm::vec4> drawMedium(std::uint32_t routine, std::uint32_t count, std::uint32_t seed,
                                  float g, glm::vec3 sigmaT = {}, glm::vec3 albedo = {}, float tMax = 0.0f,
                                  glm::vec3 share = {}) {
    gpu::SampleTestParams p{};
    p.count = count;
    p.routine = routine;
    p.seed = seed;
    p.bsdf1 = glm::vec4(share, 0.0f);
    p.bsdf2 = glm::vec4(albedo, 0.0f);
    p.bsdf3 = glm::vec4(sigmaT, 0.0f);
    p.bsdf4 = glm::vec4(0.0f, 0.0f, g, tMax);
    return runSampleKernel(context(), p, 0);
}

struct ChannelMean {
    glm::dvec3 mean{0.0}, se{0.0};
};

// The image mean of each channel and its standard error.
ChannelMean imageMean(const RenderResult& r) {
    const auto m = r.film.mean();
    const auto v = r.film.varianceOfMean();
    ChannelMean out;
    const std::size_t n = m.size() / 3;
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) out.mean[c] += m[i * 3 + c], out.se[c] += v[i * 3 + c];
    for (int c = 0; c < 3; ++c) out.mean[c] /= double(n), out.se[c] = std::sqrt(out.se[c]) / double(n);
    return out;
}

// tests/data/media/: the camera's distance and half view at z = 0, and the scenes' media.
constexpr double kCameraZ = 30.0, kHalfView = 0.9;
const glm::dvec3 kFogColor(0.2, 0.5, 0.8);
const glm::dvec3 kLanternColor(0.5, 0.6, 0.7), kLanternMs(0.8, 0.6, 0.9);
constexpr double kLanternG = 0.4, kLanternI = 5.0;

RenderResult renderMedia(const Scene& scene, std::uint32_t size, std::uint32_t spp, std::uint32_t maxDepth,
                         IntegratorKind kind = IntegratorKind::Megakernel, std::uint32_t mis = gpu::kMisPower) {
    const GpuScene gpu = buildAndPack(scene);
    CHECK((gpu.features.bits & gpu::kFeatureVolumeScatter) != 0u);
    RenderSettings s;
    s.width = s.height = size;
    s.spp = spp;
    s.maxDepth = maxDepth;
    s.integrator = kind;
    s.mis = mis;
    RenderResult r = uploadAndRender(gpu, scene.cameras.at(0), s);
    CHECK(r.nonFinite == 0);
    return r;
}

// Checks each pixel of `r` (size x size, the media scenes' camera) against
// `radiance(X, Y)`, the radiance along the ray through (X, Y, 0), averaged
// over the pixel by 4 x 4 Gauss-Legendre nodes (image rows run down: row j
// at Y = kHalfView - (j + 0.5) px); pixels whose centre is within `skip`
// of the axis are left out. Per pixel within 5 standard errors, the sum of
// each channel within 4.5 of its standard error.
void checkPixelIntegrals(const RenderResult& r, std::uint32_t size,
                         const std::function<glm::dvec3(double, double)>& radiance, double skip) {
    std::vector<double> nodes, weights;
    stats::gaussLegendre(4, nodes, weights);
    const auto m = r.film.mean();
    const auto v = r.film.varianceOfMean();
    double worstZ = 0.0;
    glm::dvec3 sum(0.0), want(0.0), var(0.0);
    const double px = 2.0 * kHalfView / size;
    for (std::uint32_t j = 0; j < size; ++j)
        for (std::uint32_t i = 0; i < size; ++i) {
            const double x0 = -kHalfView + i * px, y0 = kHalfView - (j + 1) * px;
            if (std::hypot(x0 + 0.5 * px, y0 + 0.5 * px) < skip) continue;
            glm::dvec3 e(0.0);
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    e += weights[a] * weights[b] * 0.25 *
                         radiance(x0 + 0.5 * px * (1.0 + nodes[a]), y0 + 0.5 * px * (1.0 + nodes[b]));
            const std::size_t p = (std::size_t(j) * size + i) * 3;
            for (int c = 0; c < 3; ++c) {
                worstZ = std::max(worstZ, std::abs(m[p + c] - e[c]) / std::sqrt(v[p + c]));
                sum[c] += m[p + c], want[c] += e[c], var[c] += v[p + c];
            }
        }
    MESSAGE("largest per-pixel z " << worstZ);
    CHECK(worstZ < 5.0);
    for (int c = 0; c < 3; ++c) {
        MESSAGE("channel " << c << ": " << sum[c] << " +- " << std::sqrt(var[c]) << ", integral " << want[c]);
        CHECK(std::abs(sum[c] - want[c]) < 4.5 * std::sqrt(var[c]));
    }
}

}  // namespace

TEST_CASE("volume scatter: Henyey-Greenstein sampling matches the phase function for g in (-1, 1) (chi-square), and returns it as its pdf") {
    for (const float g : {-0.7f, 0.0f, 0.45f, 0.9f}) {
        const std::uint32_t n = 400000;
        const auto s = drawMedium(gpu::kSamplePhase, n, 31 + static_cast<std::uint32_t>(g * 10.0f + 10.0f), g);
        // (phi / 2pi, (z + 1) / 2) over [0, 1]^2: density 4 pi phase(-z), the
        // travel direction +Z (wo = -Z).
        std::vector<std::pair<double, double>> xy;
        double worstPdf = 0.0;
        for (const auto& d : s) {
            double phi = std::atan2(double(d.y), double(d.x));
            if (phi < 0.0) phi += 2.0 * kPi;
            xy.emplace_back(phi / (2.0 * kPi), (double(d.z) + 1.0) / 2.0);
            const double want = phaseHG(-double(d.z), g);
            worstPdf = std::max(worstPdf, std::abs(double(d.w) / want - 1.0));
        }
        const int rx = 17, ry = 33;
        const auto observed = stats::histogram2D(xy, rx, ry, 0.0, 1.0, 0.0, 1.0);
        const auto expected = stats::integrateExpected(
            [g](double, double u) { return 4.0 * kPi * phaseHG(-(2.0 * u - 1.0), g); }, rx, ry, 0.0, 1.0, 0.0, 1.0, n);
        const auto r = stats::chiSquareTest(observed, expected, 0.01, kChiTests);
        MESSAGE("g " << g << ": " << r.detail << "; largest relative pdf error " << worstPdf);
        CHECK(r.passed);
        CHECK(worstPdf < 1e-4);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("volume scatter: free flights in a chromatic medium follow the channels' mixture by throughput (chi-square) and weigh each channel's transmittance exactly") {
    const glm::vec3 sigma(0.3f, 1.5f, 4.0f), albedo(0.9f, 0.5f, 0.7f), share(1.0f, 2.5f, 0.5f);
    const float tMax = 1.2f;
    const std::uint32_t n = 600000;
    const auto s = drawMedium(gpu::kSampleFreeFlight, n, 41, 0.0f, sigma, albedo, tMax, share);
    // Distances in 40 bins of [0, tMax) and the end itself: channel c is
    // chosen with probability share_c / sum(share), then its exponential:
    // F(t) = 1 - sum_c p_c exp(-sigma_c t).
    const int bins = 40;
    const glm::dvec3 prob = glm::dvec3(share) / double(share.x + share.y + share.z);
    auto cdf = [&](double t) {
        double f = 0.0;
        for (int c = 0; c < 3; ++c) f += prob[c] * std::exp(-double(sigma[c]) * t);
        return 1.0 - f;
    };
    std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);
    glm::dvec3 scatterSum(0.0), passSum(0.0), scatterSq(0.0), passSq(0.0);
    for (const auto& d : s) {
        const double t = d.x;
        const glm::dvec3 w(d.y, d.z, d.w);
        if (t >= tMax) {
            observed[bins] += 1.0;
            passSum += w, passSq += w * w;
        } else {
            observed[std::min(bins - 1, static_cast<int>(t / tMax * bins))] += 1.0;
            scatterSum += w, scatterSq += w * w;
        }
    }
    for (int b = 0; b < bins; ++b)
        expected[b] = double(n) * (cdf(tMax * (b + 1) / bins) - cdf(tMax * b / bins));
    expected[bins] = double(n) * (1.0 - cdf(tMax));
    const auto r = stats::chiSquareTest(observed, expected, 0.01, kChiTests);
    MESSAGE(r.detail);
    CHECK(r.passed);
    // Each channel: E[weight; scattered] = albedo (1 - exp(-sigma tMax)) and
    // E[weight; reached the end] = exp(-sigma tMax).
    for (int c = 0; c < 3; ++c) {
        const double tr = std::exp(-double(sigma[c]) * tMax);
        const double ms = scatterSum[c] / n, mp = passSum[c] / n;
        const double ses = std::sqrt((scatterSq[c] / n - ms * ms) / n), sep = std::sqrt((passSq[c] / n - mp * mp) / n);
        MESSAGE("channel " << c << ": scattered " << ms << " +- " << ses << " (want " << albedo[c] * (1.0 - tr)
                           << "), reached " << mp << " +- " << sep << " (want " << tr << ")");
        CHECK(std::abs(ms - albedo[c] * (1.0 - tr)) < 4.5 * ses);
        CHECK(std::abs(mp - tr) < 4.5 * sep);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("volume scatter: a medium of single-scatter albedo 1 in a white furnace is 1, for any g, behind an index-matched or a glass boundary") {
    // Behind fog-cube.gltf's index-matched boundary (ior 1) the megakernel's
    // next-event estimates from the medium see the environment through it,
    // MIS-weighted against the phase function; behind smooth glass (ior
    // 1.5) the boundary stops them, and both integrators find the light by
    // the phase function and the boundary's refraction alone.
    Scene scene = loadWithWhiteEnvironment(sourcePath("tests/data/media/fog-cube.gltf"));
    REQUIRE(scene.materials.size() == 1);
    for (const float ior : {1.0f, 1.5f}) {
        scene.materials[0].ior = ior;
        for (const float g : {0.3f, 0.0f, 0.9f, -0.6f}) {
            scene.materials[0].scatterAnisotropy = g;
            for (const IntegratorKind kind : {IntegratorKind::Megakernel, IntegratorKind::Wavefront}) {
                if (ior == 1.0f && kind == IntegratorKind::Wavefront) continue;  // refused: below
                const RenderResult r = renderMedia(scene, 12, 64, 1000, kind);
                const ChannelMean m = imageMean(r);
                for (int c = 0; c < 3; ++c) {
                    const std::string integrator = kind == IntegratorKind::Wavefront ? "wavefront" : "megakernel";
                    MESSAGE("ior " << ior << ", g " << g << ", " << integrator << ", channel " << c << ": " << m.mean[c]
                                   << " +- " << m.se[c]);
                    CHECK(m.se[c] > 0.0);
                    CHECK(std::abs(m.mean[c] - 1.0) < 4.5 * m.se[c] + 1e-6);
                }
            }
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("volume scatter: seen through the boundary's two crossings alone, a scattering medium transmits exp(-sigma_t x) (Beer-Lambert of absorption and scattering)") {
    const Scene scene = loadWithWhiteEnvironment(sourcePath("tests/data/media/fog-cube.gltf"));
    const std::uint32_t size = 16;
    // BSDF sampling alone: a scattering event's next-event estimate would
    // see the environment through the index-matched boundary.
    const RenderResult r = renderMedia(scene, size, 128, 2, IntegratorKind::Megakernel, gpu::kMisBsdf);
    // Pixel (i, j)'s ray crosses 2 sqrt(1 + x^2 + y^2) units, x and y its
    // slopes (the pixel's centre: the slope varies by 1e-3 across one).
    const double slope = kHalfView / kCameraZ;
    const auto m = r.film.mean();
    const auto v = r.film.varianceOfMean();
    glm::dvec3 sum(0.0), want(0.0), var(0.0);
    for (std::uint32_t j = 0; j < size; ++j)
        for (std::uint32_t i = 0; i < size; ++i) {
            const double x = (2.0 * (i + 0.5) / size - 1.0) * slope, y = (2.0 * (j + 0.5) / size - 1.0) * slope;
            const double len = 2.0 * std::sqrt(1.0 + x * x + y * y);
            const std::size_t p = (std::size_t(j) * size + i) * 3;
            for (int c = 0; c < 3; ++c) {
                sum[c] += m[p + c], var[c] += v[p + c];
                want[c] += std::pow(kFogColor[c], len);
            }
        }
    for (int c = 0; c < 3; ++c) {
        const double n = double(size) * size, mean = sum[c] / n, se = std::sqrt(var[c]) / n, w = want[c] / n;
        MESSAGE("channel " << c << ": " << mean << " +- " << se << ", Beer-Lambert " << w);
        CHECK(std::abs(mean - w) < 4.5 * se);
        CHECK(std::abs(mean / w - 1.0) < 0.02);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("volume scatter: single scattering of a point light inside the medium matches the integral along each pixel's ray") {
    const Scene scene = loadGltf(sourcePath("tests/data/media/lantern.gltf"));
    const std::uint32_t size = 20;
    // Max depth 2: the boundary's crossing, then one scattering event whose
    // next-event estimate reaches the light (the phase-sampled ray finds
    // nothing: no environment, a delta light).
    const RenderResult r = renderMedia(scene, size, 256, 2);
    glm::dvec3 sigmaT, sigmaS;
    for (int c = 0; c < 3; ++c) sigmaT[c] = -std::log(kLanternColor[c]), sigmaS[c] = sigmaT[c] * singleScatter(kLanternMs[c]);
    // The radiance along the ray from the camera (0, 0, kCameraZ) through
    // (X, Y, 0): the integral over z in [-1, 1] of Tr(entry to p) sigma_s
    // phase(wo, wi) I / r^2 Tr(r), p on the ray, r = |p| (the light at the
    // origin), by the midpoint rule.
    auto radiance = [&](double X, double Y) {
        const glm::dvec3 cam(0.0, 0.0, kCameraZ), d = glm::normalize(glm::dvec3(X, Y, 0.0) - cam);
        const double dsdz = 1.0 / std::abs(d.z);
        const int steps = 4000;
        glm::dvec3 L(0.0);
        for (int k = 0; k < steps; ++k) {
            const double z = 1.0 - 2.0 * (k + 0.5) / steps;
            const glm::dvec3 p = cam + d * ((kCameraZ - z) * dsdz);
            const double r2 = glm::dot(p, p), rr = std::sqrt(r2);
            const double inside = (1.0 - z) * dsdz;
            const double phase = phaseHG(glm::dot(-d, -p / rr), kLanternG);
            for (int c = 0; c < 3; ++c)
                L[c] += std::exp(-sigmaT[c] * inside) * sigmaS[c] * phase * kLanternI / r2 * std::exp(-sigmaT[c] * rr);
        }
        return L * (2.0 * dsdz / steps);
    };
    checkPixelIntegrals(r, size, radiance, 0.3);  // near the light: 1/r^2
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("volume scatter: single scattering of the sun through the index-matched boundary matches the integral along each pixel's ray") {
    // sunlit-fog.gltf: the lantern's medium under a directional light of
    // irradiance E travelling down -Y, nothing else. Max depth 2: a
    // scattering event's shadow ray leaves through the top face
    // (pathMediumShadow) with the transmittance of 1 - y; the phase
    // function between the view and +Y. Integrated as in the lantern test.
    const Scene scene = loadGltf(sourcePath("tests/data/media/sunlit-fog.gltf"));
    const GpuScene gpu = buildAndPack(scene);
    CHECK(gpu.features.indexMatchedMedia);
    const std::uint32_t size = 16;
    const RenderResult r = renderMedia(scene, size, 256, 2);
    constexpr double kSunE = 3.0;
    glm::dvec3 sigmaT, sigmaS;
    for (int c = 0; c < 3; ++c) sigmaT[c] = -std::log(kLanternColor[c]), sigmaS[c] = sigmaT[c] * singleScatter(kLanternMs[c]);
    auto radiance = [&](double X, double Y) {
        const glm::dvec3 cam(0.0, 0.0, kCameraZ), d = glm::normalize(glm::dvec3(X, Y, 0.0) - cam);
        const double dsdz = 1.0 / std::abs(d.z);
        const double phase = phaseHG(glm::dot(-d, glm::dvec3(0.0, 1.0, 0.0)), kLanternG);
        const int steps = 2000;
        glm::dvec3 L(0.0);
        for (int k = 0; k < steps; ++k) {
            const double z = 1.0 - 2.0 * (k + 0.5) / steps;
            const glm::dvec3 p = cam + d * ((kCameraZ - z) * dsdz);
            const double inside = (1.0 - z) * dsdz, up = 1.0 - p.y;
            for (int c = 0; c < 3; ++c)
                L[c] += std::exp(-sigmaT[c] * inside) * sigmaS[c] * phase * kSunE * std::exp(-sigmaT[c] * up);
        }
        return L * (2.0 * dsdz / steps);
    };
    checkPixelIntegrals(r, size, radiance, 0.0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("volume scatter: light sampling, phase sampling and their MIS agree for a lamp seen through the index-matched boundary") {
    // lamp-fog.gltf: the lantern's medium under a 3 x 3 lamp above it. Each
    // technique alone and the power heuristic estimate the same image; the
    // lamp found by a phase-sampled ray after the boundary's crossing is
    // weighed against light sampling from the scattering event before it
    // (its distance includes the crossing's, PathVertex::travelled).
    const Scene scene = loadGltf(sourcePath("tests/data/media/lamp-fog.gltf"));
    const std::uint32_t size = 12;
    ChannelMean m[3];
    const std::uint32_t mis[3] = {gpu::kMisPower, gpu::kMisLight, gpu::kMisBsdf};
    for (int k = 0; k < 3; ++k)
        m[k] = imageMean(renderMedia(scene, size, 256, 6, IntegratorKind::Megakernel, mis[k]));
    for (int k = 1; k < 3; ++k)
        for (int c = 0; c < 3; ++c) {
            const double se = std::sqrt(m[0].se[c] * m[0].se[c] + m[k].se[c] * m[k].se[c]);
            MESSAGE((k == 1 ? "light" : "phase") << " sampling, channel " << c << ": " << m[k].mean[c] << " +- "
                                                 << m[k].se[c] << ", MIS " << m[0].mean[c] << " +- " << m[0].se[c]);
            CHECK(m[0].mean[c] > 0.0);
            CHECK(std::abs(m[k].mean[c] - m[0].mean[c]) < 4.5 * se);
        }
    CHECK(vk::validationMessageCount() == 0);
}

// The refusal comes once the device is open (the integrator is made for
// it), so this is a render test, not a unit one.
TEST_CASE("volume scatter: the wavefront integrator refuses a medium behind an index-matched boundary in one line") {
    expectError("render " + sourcePath("tests/data/media/sunlit-fog.gltf") + " --integrator wavefront",
                "strata: error: a scattering medium behind an index-matched boundary");
}

TEST_CASE("gltf materials: KHR_materials_volume_scatter multiscatterColor and scatterAnisotropy, packed as single-scatter albedo" * doctest::test_suite("unit")) {
    const Scene scene = loadGltf(sourcePath("tests/data/media/lantern.gltf"));
    REQUIRE(scene.materials.size() == 1);
    const MaterialDesc& m = scene.materials[0];
    CHECK(m.scatterAnisotropy == doctest::Approx(kLanternG));
    CHECK(m.multiscatterColor.y == doctest::Approx(kLanternMs.y));
    const GpuScene gpu = buildAndPack(scene);
    const gpu::Material& g = gpu.materials.at(0);
    CHECK((g.flags & gpu::kMaterialVolumeScatter) != 0u);
    for (int c = 0; c < 3; ++c) CHECK(g.scatterAlbedo[c] == doctest::Approx(singleScatter(kLanternMs[c])).epsilon(1e-5));
    // The mapping's ends: 0 absorbs only, 1 scatters only.
    CHECK(std::abs(singleScatter(0.0)) < 1e-5);
    CHECK(singleScatter(1.0) == doctest::Approx(1.0).epsilon(1e-5));
    // multiscatterColor 0 (the default) is absorption only: no scattering flag, no feature.
    Scene absorbing = scene;
    absorbing.materials[0].multiscatterColor = glm::vec3(0.0f);
    const GpuScene a = buildAndPack(absorbing);
    CHECK((a.materials.at(0).flags & gpu::kMaterialVolumeScatter) == 0u);
    CHECK((a.materials.at(0).flags & gpu::kMaterialVolume) != 0u);
    CHECK((a.features.bits & gpu::kFeatureVolumeScatter) == 0u);
    // A scene without it: no feature bit.
    CHECK((buildAndPack(loadGltf(sourcePath("scenes/materials-board.gltf"))).features.bits &
           gpu::kFeatureVolumeScatter) == 0u);
    // Its clear boundary of ior 1 is index-matched; of ior 1.5, or rough, not.
    CHECK((g.flags & gpu::kMaterialIndexMatched) != 0u);
    CHECK(gpu.features.indexMatchedMedia);
    for (const float ior : {1.5f, 1.0f}) {
        Scene other = scene;
        other.materials[0].ior = ior;
        other.materials[0].roughness = ior == 1.0f ? 0.2f : 0.0f;
        const GpuScene o = buildAndPack(other);
        CHECK((o.materials.at(0).flags & gpu::kMaterialIndexMatched) == 0u);
        CHECK_FALSE(o.features.indexMatchedMedia);
    }
    // multiscatterColorFactor, as some exporters write it, reads the same.
    const Scene alias = loadGltf(sourcePath("tests/data/media/factor-spelling.gltf"));
    CHECK(alias.materials.at(0).multiscatterColor == m.multiscatterColor);
}

TEST_CASE("gltf materials: bad KHR_materials_volume_scatter values are refused in one line, and render writes nothing" * doctest::test_suite("unit")) {
    checkBrokenFolder("media/broken",
                      {{"scatter-anisotropy-1.gltf",
                        "material 0 (\"Medium\"): KHR_materials_volume_scatter.scatterAnisotropy 1 is not in (-1, 1)"},
                       {"scatter-anisotropy-string.gltf",
                        "material 0 (\"Medium\"): KHR_materials_volume_scatter.scatterAnisotropy is not a number"},
                       {"scatter-color-negative.gltf", "material 0 (\"Medium\"): KHR_materials_volume_scatter."
                                                       "multiscatterColor is not three numbers in [0, 1]"},
                       {"scatter-color-two.gltf", "material 0 (\"Medium\"): KHR_materials_volume_scatter."
                                                  "multiscatterColor is not three numbers in [0, 1]"}});
}

TEST_CASE("gltf media: surfaces, emitters and other media inside a medium get one warning line, as does multiscatterTexture, but not a floor on its boundary or a point light inside" * doctest::test_suite("unit")) {
    const std::string inside = " lie inside the volume of material 0 (\"Medium\") (first: one of material 1 (";
    const std::string tail = ")): strata does not nest media or render surfaces inside one; a path segment ending on them "
                             "crosses no medium\n";
    const auto warning = [](const std::string& name) {
        const std::string path = sourcePath("tests/data/media/" + name);
        CAPTURE(path);
        CerrCapture capture;
        (void)loadGltf(path);
        const std::string text = capture.text();
        CHECK(std::count(text.begin(), text.end(), '\n') <= 1);
        const std::string prefix = path + ": warning: ";
        return text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
    };
    CHECK(warning("lamp-inside-fog.gltf") == "2 triangle(s)" + inside + "\"Bulb\"" + tail);
    CHECK(warning("glass-inside-fog.gltf") == "12 triangle(s)" + inside + "\"Glass\"" + tail);
    // The floor's 8 triangles under the cube lie on its bottom face.
    CHECK(warning("fog-on-floor.gltf").empty());
    CHECK(warning("lantern.gltf").empty());
    CHECK(warning("lamp-fog.gltf").empty());
    CHECK(warning("scatter-texture.gltf") ==
          "1 material(s) have KHR_materials_volume_scatter.multiscatterTexture, which strata does not read: their "
          "media scatter by multiscatterColor alone\n");
}

TEST_CASE("gltf media: the check for surfaces inside a medium poses instanced meshes at each placement" * doctest::test_suite("unit")) {
    Scene scene = loadGltf(sourcePath("tests/data/media/lamp-fog.gltf"));
    REQUIRE(surfacesInsideMedia(scene).empty());
    // The lamp's two triangles become a shared mesh placed three times: at
    // its own place (outside), lowered into the cube, and mirrored into it.
    const std::uint32_t lamp = 1;
    REQUIRE(scene.materials.at(lamp).name == "Lamp");
    std::vector<Triangle> world, shared;
    for (const Triangle& t : scene.triangles) (t.material == lamp ? shared : world).push_back(t);
    REQUIRE(shared.size() == 2);
    scene.triangles = world;
    scene.triangles.insert(scene.triangles.end(), shared.begin(), shared.end());
    scene.sharedMeshes = {SharedMesh{world.size(), 2, "lamp", false}};
    const glm::mat4 down = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.5f, 0.0f));
    const glm::mat4 mirrored = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -0.5f, 1.0f));
    scene.instances = {MeshInstance{0, glm::mat4(1.0f), {}}, MeshInstance{0, down, {}}, MeshInstance{0, mirrored, {}}};
    CHECK(surfacesInsideMedia(scene).rfind("4 triangle(s) lie inside the volume of material 0 (\"Medium\") (first: "
                                           "one of material 1 (\"Lamp\"))", 0) == 0);
    // Without a medium the check looks at nothing.
    scene.materials[0].thickness = 0.0f;
    CHECK(surfacesInsideMedia(scene).empty());
}

TEST_SUITE_END();
