// The GLSL BSDF (shaders/lib/bsdf.glsl) as it runs on the device:
// chi-square of sampleBsdf against the density evalBsdf reports, agreement
// of sampled weights with eval / pdf, and known directional albedos.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bsdf_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

// GGX materials of the issue: a white conductor at alpha in {0.05, 0.2, 0.5,
// 1} (roughness sqrt(alpha)) and incidence 0, 30, 80 degrees; rough glass
// from outside and from inside (where total internal reflection applies);
// Lambert; rough plastic; a half-metal rough glass.
std::vector<TestMaterial> chiSquareMaterials() {
    std::vector<TestMaterial> out;
    for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f}) {
        for (float deg : {0.0f, 30.0f, 80.0f}) {
            TestMaterial m;
            m.name = "conductor alpha " + std::to_string(alpha) + " at " + std::to_string(int(deg)) + " deg";
            m.incidenceDeg = deg;
            m.roughness = std::sqrt(alpha);
            m.metallic = 1.0f;
            out.push_back(m);
        }
    }
    auto glass = [](const char* name, float deg, float alpha, bool entering) {
        TestMaterial m;
        m.name = name;
        m.incidenceDeg = deg;
        m.roughness = std::sqrt(alpha);
        m.transmission = 1.0f;
        m.entering = entering;
        return m;
    };
    out.push_back(glass("rough glass alpha 0.2 entering at 30 deg", 30.0f, 0.2f, true));
    out.push_back(glass("rough glass alpha 0.5 entering at 70 deg", 70.0f, 0.5f, true));
    out.push_back(glass("rough glass alpha 0.2 leaving at 30 deg", 30.0f, 0.2f, false));
    out.push_back(glass("rough glass alpha 0.3 leaving at 60 deg (beyond the critical angle)", 60.0f, 0.3f, false));
    TestMaterial lambert;
    lambert.name = "Lambert (specular 0) at 40 deg";
    lambert.incidenceDeg = 40.0f;
    lambert.specular = 0.0f;
    lambert.base = 0.7f;
    out.push_back(lambert);
    TestMaterial plastic;
    plastic.name = "rough plastic alpha 0.1, base 0.5, at 60 deg";
    plastic.incidenceDeg = 60.0f;
    plastic.roughness = std::sqrt(0.1f);
    plastic.base = 0.5f;
    out.push_back(plastic);
    TestMaterial mix = glass("half-metal rough glass alpha 0.3, base 0.8, at 45 deg", 45.0f, 0.3f, true);
    mix.metallic = 0.5f;
    mix.base = 0.8f;
    out.push_back(mix);
    return out;
}

}  // namespace

TEST_CASE("GLSL BSDF sampling matches the BSDF's pdf (chi-square: GGX conductor, rough glass, Lambert, plastic, mix)" * doctest::test_suite("slow")) {
    checkBsdfChiSquare(chiSquareMaterials(), 100);
}

TEST_CASE("GLSL BSDF sample weights equal eval / pdf, finite and non-negative") {
    auto materials = chiSquareMaterials();
    for (float r : {0.0f, 1e-4f}) {  // delta lobes
        TestMaterial mirror;
        mirror.name = "mirror roughness " + std::to_string(r);
        mirror.roughness = r;
        mirror.metallic = 1.0f;
        mirror.incidenceDeg = 45.0f;
        materials.push_back(mirror);
        TestMaterial glass = mirror;
        glass.name = "smooth glass roughness " + std::to_string(r);
        glass.metallic = 0.0f;
        glass.transmission = 1.0f;
        materials.push_back(glass);
    }
    checkBsdfWeights(materials);
}

TEST_CASE("GGX conductor directional albedo matches E(mu) and never exceeds 1") {
    // Single-scattering albedo of a white GGX conductor with height-correlated
    // Smith shadowing (Heitz 2016; Kulla & Conty 2017), to 3 digits:
    struct Case { float alpha, mu; double expected; };
    const Case cases[] = {{0.5f, 1.0f, 0.688}, {0.5f, 0.5f, 0.698}, {0.1f, 1.0f, 0.988}};
    for (const auto& c : cases) {
        TestMaterial m;
        m.metallic = 1.0f;
        m.roughness = std::sqrt(c.alpha);
        m.incidenceDeg = static_cast<float>(std::acos(c.mu) * 180.0 / std::numbers::pi);
        const auto [mean, se] = bsdfAlbedo(m, 1u << 20, 31);
        MESSAGE("alpha " << c.alpha << " mu " << c.mu << ": E = " << mean << " +- " << se
                         << " (expected " << c.expected << ")");
        // The reference has 3 digits (+-0.0005); the estimate's error adds in.
        CHECK(std::abs(mean - c.expected) < 0.0005 + 4.0 * se);
    }
    // Over all angles and roughnesses the white conductor loses energy, never gains it.
    for (float alpha : {0.01f, 0.1f, 0.3f, 0.6f, 1.0f}) {
        for (float deg : {0.0f, 45.0f, 75.0f, 89.0f}) {
            TestMaterial m;
            m.metallic = 1.0f;
            m.roughness = std::sqrt(alpha);
            m.incidenceDeg = deg;
            const auto [mean, se] = bsdfAlbedo(m, 1u << 16, 32);
            CAPTURE(alpha);
            CAPTURE(deg);
            CHECK(mean <= 1.0 + 4.0 * se);
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// Mean energy (flux) albedo: sample weights with transmitted ones multiplied
// by etap^2, undoing the radiance scaling. kSampleBsdf and kSampleBsdfWeight
// draw the same sample i for the same seed, so their outputs pair up.
std::pair<double, double> fluxAlbedo(const TestMaterial& m, std::uint32_t n, std::uint32_t seed) {
    const auto dirs = runBsdf(m, gpu::kSampleBsdf, n, seed);
    const auto weights = runBsdf(m, gpu::kSampleBsdfWeight, n, seed);
    const double etap = m.entering ? m.ior : 1.0 / m.ior;
    double sum = 0.0, sum2 = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        double w = weights[i].x < 0.0f ? 0.0 : weights[i].x;
        if (dirs[i].w != 0.0f && dirs[i].z < 0.0f) w *= etap * etap;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

}  // namespace

TEST_CASE("Smooth glass and mirrors conserve energy exactly, and rough glass never gains energy") {
    // Delta lobes: a white mirror reflects everything, and smooth glass
    // reflects with probability F and weight 1 or refracts with weight
    // 1/eta^2 in radiance, that is 1 in flux, at every angle (total internal
    // reflection included).
    for (float deg : {0.0f, 30.0f, 60.0f, 85.0f}) {
        TestMaterial mirror;
        mirror.metallic = 1.0f;
        mirror.roughness = 0.0f;
        mirror.incidenceDeg = deg;
        CAPTURE(deg);
        const auto [mean, se] = bsdfAlbedo(mirror, 1u << 14, 41);
        CHECK(mean == doctest::Approx(1.0).epsilon(1e-6));
        for (bool entering : {true, false}) {
            TestMaterial glass = mirror;
            glass.metallic = 0.0f;
            glass.transmission = 1.0f;
            glass.entering = entering;
            CAPTURE(entering);
            const auto [flux, fse] = fluxAlbedo(glass, 1u << 14, 43);
            CHECK(flux == doctest::Approx(1.0).epsilon(1e-5));
        }
    }
    // Rough glass: single scattering loses energy to the shadowing terms.
    for (float alpha : {0.05f, 0.3f, 1.0f}) {
        for (bool entering : {true, false}) {
            TestMaterial glass;
            glass.transmission = 1.0f;
            glass.roughness = std::sqrt(alpha);
            glass.entering = entering;
            glass.incidenceDeg = 40.0f;
            const auto [mean, se] = fluxAlbedo(glass, 1u << 18, 42);
            CAPTURE(alpha);
            CAPTURE(entering);
            MESSAGE("rough glass alpha " << alpha << std::string(entering ? " entering" : " leaving")
                                         << ": flux albedo " << mean << " +- " << se);
            CHECK(mean <= 1.0 + 4.0 * se);
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
