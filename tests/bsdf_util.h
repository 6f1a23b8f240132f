// The GLSL BSDF (shaders/lib/bsdf.glsl) as it runs on the device, through
// shaders/sample_test.comp: the test materials and the checks that
// test_bsdf.cpp and test_bsdf_layers.cpp share (chi-square of sampleBsdf
// against the density evalBsdf reports, sampled weights against eval / pdf,
// directional albedos).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "measure/sample_dump.h"
#include "stats/stats.h"
#include "test_util.h"

namespace strata::test {

struct TestMaterial {
    std::string name;
    float incidenceDeg = 0.0f;
    float roughness = 1.0f;
    float metallic = 0.0f;
    float transmission = 0.0f;
    float ior = 1.5f;
    float specular = 1.0f;
    float base = 1.0f;        // grey base colour
    bool entering = true;
    // KHR_materials_clearcoat
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f;
    float coatTilt = 0.0f;    // radians: the coat normal (0.6 sin t, 0.8 sin t, cos t)
    // KHR_materials_sheen
    float sheen = 0.0f;       // grey sheen colour
    float sheenRoughness = 0.0f;
    glm::vec3 specularColor{1.0f};  // KHR_materials_specular
    float diffuseTransmission = 0.0f;       // KHR_materials_diffuse_transmission
    float diffuseTransmissionColor = 1.0f;  // grey
    float anisotropy = 0.0f;                // KHR_materials_anisotropy strength, along x
    float azimuthDeg = 0.0f;                // wo's azimuth from x
    std::uint32_t extraFeatures = 0;  // compiled in although the material does not need them

    // The feature bits the layers need compiled in.
    std::uint32_t features() const {
        return (clearcoat > 0.0f ? gpu::kFeatureClearcoat : 0u) | (sheen > 0.0f ? gpu::kFeatureSheen : 0u) |
               (specularColor != glm::vec3(1.0f) ? gpu::kFeatureSpecularColor : 0u) |
               (diffuseTransmission > 0.0f ? gpu::kFeatureDiffuseTransmission : 0u) |
               (anisotropy > 0.0f ? gpu::kFeatureAnisotropy : 0u) | extraFeatures;
    }
};

inline gpu::SampleTestParams bsdfParams(const TestMaterial& m, std::uint32_t routine, std::uint32_t count,
                                        std::uint32_t seed) {
    gpu::SampleTestParams p{};
    p.count = count;
    p.routine = routine;
    p.seed = seed;
    const float c = static_cast<float>(std::cos(m.incidenceDeg * std::numbers::pi / 180.0));
    p.bsdf0 = glm::vec4(c, m.roughness, m.metallic, m.transmission);
    p.bsdf1 = glm::vec4(m.ior, m.specular, m.base, m.entering ? 1.0f : 0.0f);
    p.bsdf2 = glm::vec4(m.clearcoat, m.clearcoatRoughness, m.sheen, m.sheenRoughness);
    p.bsdf3 = glm::vec4(m.specularColor, m.coatTilt);
    p.diffTrans = m.diffuseTransmission;
    p.diffTransColor = m.diffuseTransmissionColor;
    p.bsdf4 = glm::vec4(m.anisotropy, float(m.azimuthDeg * std::numbers::pi / 180.0), 0.0f, 0.0f);
    return p;
}

inline std::vector<glm::vec4> runBsdfKernel(const gpu::SampleTestParams& p, const TestMaterial& m) {
    return runSampleKernel(context(), p, 0, {}, {}, nullptr, m.features());
}

inline std::vector<glm::vec4> runBsdf(const TestMaterial& m, std::uint32_t routine, std::uint32_t count,
                                      std::uint32_t seed) {
    return runBsdfKernel(bsdfParams(m, routine, count, seed), m);
}

// Chi-square of 2^20 sampled directions of each material against the
// density evalBsdf reports, on a 64 x 128 (theta, phi) grid whose cells the
// shader integrates by Gauss-Legendre quadrature, plus one cell for invalid
// samples; Sidak-corrected over the materials at level 0.01. Reports the
// smallest p-value.
inline void checkBsdfChiSquare(const std::vector<TestMaterial>& materials, std::uint32_t seed) {
    const std::size_t testCount = materials.size();
    const std::uint32_t n = 1u << 20;
    const int rt = 64, rp = 128;  // theta in [0, pi], phi in [0, 2 pi)
    double smallest = 1.0;
    for (const auto& m : materials) {
        CAPTURE(m.name);
        const auto s = runBsdf(m, gpu::kSampleBsdf, n, seed++);
        std::vector<double> observed(rt * rp + 1, 0.0);  // last cell: invalid samples
        for (const auto& d : s) {
            if (d.w == 0.0f) {
                observed.back() += 1.0;
                continue;
            }
            REQUIRE(std::abs(glm::length(glm::vec3(d)) - 1.0f) < 1e-4f);
            const double theta = std::acos(std::clamp(double(d.z), -1.0, 1.0));
            double phi = std::atan2(double(d.y), double(d.x));
            if (phi < 0.0) phi += 2.0 * std::numbers::pi;
            const int it = std::min(rt - 1, int(theta / std::numbers::pi * rt));
            const int ip = std::min(rp - 1, int(phi / (2.0 * std::numbers::pi) * rp));
            observed[it * rp + ip] += 1.0;
        }
        gpu::SampleTestParams cells = bsdfParams(m, gpu::kBsdfPdfCells, rt * rp, 0);
        cells.pixelX = rt;
        cells.pixelY = rp;
        const auto integrals = runBsdfKernel(cells, m);
        std::vector<double> expected(rt * rp + 1);
        double total = 0.0;
        for (int i = 0; i < rt * rp; ++i) {
            expected[i] = double(integrals[i].x) * n;
            total += integrals[i].x;
        }
        // The density integrates to the probability of a valid sample.
        CHECK(total <= 1.0 + 2e-3);
        expected.back() = std::max(0.0, 1.0 - total) * n;
        const auto r = stats::chiSquareTest(observed, expected, 0.01, testCount);
        MESSAGE(m.name << ": " << r.detail << "; pdf integral " << total << ", invalid "
                       << observed.back() / n);
        smallest = std::min(smallest, r.pValue);
        CHECK(r.passed);
    }
    MESSAGE("smallest p-value " << smallest);
    CHECK(vk::validationMessageCount() == 0);
}

// 2^16 samples of each material: every valid sample's weight is finite,
// non-negative where asked, and equals eval / pdf with the sample's pdf
// equal to the evaluated one (relative 1e-4); delta samples are skipped.
inline void checkBsdfWeights(const std::vector<TestMaterial>& materials) {
    const std::uint32_t n = 1u << 16;
    for (const auto& m : materials) {
        CAPTURE(m.name);
        const auto s = runBsdf(m, gpu::kSampleBsdfWeight, n, 7);
        std::size_t bad = 0, mismatched = 0;
        for (const auto& v : s) {
            if (v.x < 0.0f) continue;  // invalid sample (weight 0)
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w)) {
                ++bad;
                continue;
            }
            if (v.y == -1.0f && v.z == -1.0f) continue;  // delta sample: weight checked elsewhere
            const bool same = std::abs(v.x - v.y) <= 1e-4f * std::max(1.0f, v.x) &&
                              std::abs(v.z - v.w) <= 1e-4f * std::max(1.0f, v.z) && v.z > 0.0f;
            if (!same) ++mismatched;
        }
        CHECK(bad == 0);
        CHECK(mismatched == 0);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// How many of n samples of `m` differ (any of weight, eval / pdf, pdf,
// evaluated pdf beyond 1e-5 relative) with `feature` compiled in and
// without it.
inline std::size_t samplesDiffering(TestMaterial m, std::uint32_t feature, std::uint32_t n, std::uint32_t seed) {
    m.extraFeatures = feature;
    const auto with = runBsdf(m, gpu::kSampleBsdfWeight, n, seed);
    m.extraFeatures = 0;
    const auto without = runBsdf(m, gpu::kSampleBsdfWeight, n, seed);
    std::size_t differ = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        for (int k = 0; k < 4; ++k) {
            const double a = with[i][k], b = without[i][k];
            if (std::abs(a - b) > 1e-5 * std::max({1.0, std::abs(a), std::abs(b)})) {
                ++differ;
                break;
            }
        }
    }
    return differ;
}

// Mean sample weight (the directional albedo) and its standard error.
inline std::pair<double, double> bsdfAlbedo(const TestMaterial& m, std::uint32_t n, std::uint32_t seed) {
    const auto s = runBsdf(m, gpu::kSampleBsdfWeight, n, seed);
    double sum = 0.0, sum2 = 0.0;
    for (const auto& v : s) {
        const double w = v.x < 0.0f ? 0.0 : v.x;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    const double var = std::max(0.0, sum2 / n - mean * mean);
    return {mean, std::sqrt(var / n)};
}

}  // namespace strata::test
