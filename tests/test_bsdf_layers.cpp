// The layers over the glTF BSDF in GLSL (shaders/lib/bsdf.glsl), run by the
// shader itself (sample_test.comp): KHR_materials_clearcoat's coat.
// Chi-square of the whole BSDF's sampling with each layer against the
// density evalBsdf reports, sampled weights against eval / pdf, and white
// furnaces of the directional albedo.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bsdf_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

double schlick(double f0, double mu) { return f0 + (1.0 - f0) * std::pow(1.0 - mu, 5.0); }

double cosDeg(double deg) { return std::cos(deg * std::numbers::pi / 180.0); }

// Bases under the coat.
TestMaterial lambert(float base) {
    TestMaterial m;
    m.specular = 0.0f;
    m.base = base;
    return m;
}

TestMaterial coated(TestMaterial m, const std::string& base, float coatRoughness, float deg, float tilt = 0.0f,
                    float clearcoat = 1.0f) {
    m.clearcoat = clearcoat;
    m.clearcoatRoughness = coatRoughness;
    m.incidenceDeg = deg;
    m.coatTilt = tilt;
    m.name = "clearcoat " + std::to_string(clearcoat) + " roughness " + std::to_string(coatRoughness) +
             " tilt " + std::to_string(tilt) + " over " + base + " at " + std::to_string(int(deg)) + " deg";
    return m;
}

// Coats of roughness 0.1 to 1 (alpha 0.01 to 1) over Lambert, rough
// plastic, a GGX conductor and rough glass from both sides, at incidence 0
// to 85 degrees, the coat normal along the shading normal or tilted.
std::vector<TestMaterial> coatMaterials() {
    TestMaterial plastic;
    plastic.roughness = std::sqrt(0.1f);
    plastic.base = 0.5f;
    TestMaterial conductor;
    conductor.metallic = 1.0f;
    conductor.roughness = std::sqrt(0.2f);
    TestMaterial glassIn;
    glassIn.transmission = 1.0f;
    glassIn.roughness = std::sqrt(0.2f);
    TestMaterial glassOut = glassIn;
    glassOut.entering = false;
    glassOut.roughness = std::sqrt(0.3f);
    return {coated(lambert(0.8f), "Lambert 0.8", 0.3f, 0.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.3f, 45.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.3f, 80.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.7f, 60.0f, 0.4f, 0.5f),
            coated(lambert(0.8f), "Lambert 0.8", 1.0f, 30.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.1f, 45.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.3f, 85.0f, 0.4f),
            coated(plastic, "plastic alpha 0.1", 0.5f, 60.0f),
            coated(conductor, "conductor alpha 0.2", 0.3f, 30.0f, 0.3f),
            coated(glassIn, "rough glass alpha 0.2 entering", 0.3f, 30.0f),
            coated(glassOut, "rough glass alpha 0.3 leaving", 0.5f, 45.0f, 0.3f)};
}

}  // namespace

TEST_CASE("clearcoat: sampling the coated BSDF matches its pdf (chi-square over coat roughness, base, incidence and coat normal)") {
    const auto materials = coatMaterials();
    const double p = checkBsdfChiSquare(materials, materials.size(), 300);
    MESSAGE("smallest p-value " << p);
}

TEST_CASE("clearcoat: sample weights equal eval / pdf, smooth coats and smooth bases included") {
    auto materials = coatMaterials();
    TestMaterial mirror;
    mirror.metallic = 1.0f;
    mirror.roughness = 0.0f;
    TestMaterial conductor;
    conductor.metallic = 1.0f;
    conductor.roughness = 0.5f;
    materials.push_back(coated(lambert(0.8f), "Lambert 0.8", 0.0f, 45.0f));
    materials.push_back(coated(conductor, "conductor roughness 0.5", 0.0f, 30.0f, 0.3f));
    materials.push_back(coated(mirror, "mirror", 0.3f, 60.0f));
    checkBsdfWeights(materials);
}

TEST_CASE("clearcoat: white furnace over white Lambert: a smooth coat keeps exactly 1, a rough one loses at most its Fresnel share") {
    // base * (1 - Fc) + coat: over a white Lambert (albedo 1) a smooth coat
    // reflects Fc and the base 1 - Fc, so every sample weighs 1 (float
    // rounding: 1e-5); a rough coat reflects Fc E(mu) <= Fc, so the albedo
    // lies in [1 - Fc, 1] (4 standard errors of 2^18 samples).
    for (float r : {0.0f, 0.3f, 0.6f, 1.0f}) {
        for (float deg : {0.0f, 45.0f, 75.0f, 89.0f}) {
            const TestMaterial m = coated(lambert(1.0f), "white Lambert", r, deg);
            CAPTURE(m.name);
            const auto [mean, se] = bsdfAlbedo(m, 1u << 18, 51);
            const double fc = schlick(0.04, cosDeg(deg));
            MESSAGE(m.name << ": albedo " << mean << " +- " << se << " (Fc " << fc << ")");
            if (r == 0.0f) {
                CHECK(std::abs(mean - 1.0) < 1e-5);
            } else {
                CHECK(mean <= 1.0 + 4.0 * se);
                CHECK(mean >= 1.0 - fc - 4.0 * se);
            }
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("clearcoat: over a base that reflects nothing, the albedo is Fc(mu) times the GGX albedo E(mu)") {
    // A black dielectric with specular 0 under a coat of alpha 0.5 and 0.1:
    // the coat alone, clearcoat * Schlick(0.04, mu) * E(mu), with E(mu) the
    // white GGX conductor's single-scattering albedo (test_bsdf.cpp's
    // references, 3 digits).
    struct Case { float alpha, mu; double e; };
    const Case cases[] = {{0.5f, 1.0f, 0.688}, {0.5f, 0.5f, 0.698}, {0.1f, 1.0f, 0.988}};
    for (const auto& c : cases) {
        const float deg = static_cast<float>(std::acos(c.mu) * 180.0 / std::numbers::pi);
        const TestMaterial m = coated(lambert(0.0f), "black", std::sqrt(c.alpha), deg, 0.0f, 0.75f);
        const auto [mean, se] = bsdfAlbedo(m, 1u << 20, 52);
        const double expected = 0.75 * schlick(0.04, c.mu) * c.e;
        MESSAGE(m.name << ": albedo " << mean << " +- " << se << " (expected " << expected << ")");
        CHECK(std::abs(mean - expected) < 0.75 * schlick(0.04, c.mu) * 0.0005 + 4.0 * se);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
