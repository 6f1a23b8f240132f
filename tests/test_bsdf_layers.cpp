// The layers over the glTF BSDF in GLSL (shaders/lib/bsdf.glsl), run by the
// shader itself (sample_test.comp): KHR_materials_clearcoat's coat,
// KHR_materials_sheen's sheen and KHR_materials_specular's colour.
// Chi-square of the whole BSDF's sampling with each layer against the
// density evalBsdf reports, sampled weights against eval / pdf, and white
// furnaces of the directional albedo.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bsdf_util.h"
#include "sheen_albedo.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

double schlick(double f0, double mu) { return f0 + (1.0 - f0) * std::pow(1.0 - mu, 5.0); }

double cosDeg(double deg) { return std::cos(deg * std::numbers::pi / 180.0); }

// Bases under the layers: Lambert (specular 0), plastic (GGX alpha 0.1,
// base 0.5), a white GGX conductor of alpha 0.2, rough glass.
TestMaterial lambert(float base) {
    TestMaterial m;
    m.specular = 0.0f;
    m.base = base;
    return m;
}

TestMaterial plastic() {
    TestMaterial m;
    m.roughness = std::sqrt(0.1f);
    m.base = 0.5f;
    return m;
}

TestMaterial conductor() {
    TestMaterial m;
    m.metallic = 1.0f;
    m.roughness = std::sqrt(0.2f);
    return m;
}

TestMaterial roughGlass(float alpha, bool entering) {
    TestMaterial m;
    m.transmission = 1.0f;
    m.roughness = std::sqrt(alpha);
    m.entering = entering;
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
    return {coated(lambert(0.8f), "Lambert 0.8", 0.3f, 0.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.3f, 45.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.3f, 80.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.7f, 60.0f, 0.4f, 0.5f),
            coated(lambert(0.8f), "Lambert 0.8", 1.0f, 30.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.1f, 45.0f),
            coated(lambert(0.8f), "Lambert 0.8", 0.3f, 85.0f, 0.4f),
            coated(plastic(), "plastic alpha 0.1", 0.5f, 60.0f),
            coated(conductor(), "conductor alpha 0.2", 0.3f, 30.0f, 0.3f),
            coated(roughGlass(0.2f, true), "rough glass alpha 0.2 entering", 0.3f, 30.0f),
            coated(roughGlass(0.3f, false), "rough glass alpha 0.3 leaving", 0.5f, 45.0f, 0.3f)};
}

}  // namespace

TEST_CASE("clearcoat: sampling the coated BSDF matches its pdf (chi-square over coat roughness, base, incidence and coat normal)") {
    checkBsdfChiSquare(coatMaterials(), 300);
}

TEST_CASE("clearcoat: sample weights equal eval / pdf, smooth coats and smooth bases included") {
    auto materials = coatMaterials();
    TestMaterial mirror = conductor();
    mirror.roughness = 0.0f;
    materials.push_back(coated(lambert(0.8f), "Lambert 0.8", 0.0f, 45.0f));
    materials.push_back(coated(conductor(), "conductor alpha 0.2", 0.0f, 30.0f, 0.3f));
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

namespace {

TestMaterial sheened(TestMaterial m, const std::string& base, float sheen, float roughness, float deg) {
    m.sheen = sheen;
    m.sheenRoughness = roughness;
    m.incidenceDeg = deg;
    m.name = "sheen " + std::to_string(sheen) + " roughness " + std::to_string(roughness) + " over " + base +
             (m.clearcoat > 0.0f ? " under a coat" : "") + " at " + std::to_string(int(deg)) + " deg";
    return m;
}

// Sheens of roughness 0.2 to 1 over black, Lambert, a conductor and, under
// a coat, plastic, at incidence 0 to 80 degrees.
std::vector<TestMaterial> sheenMaterials() {
    TestMaterial coatedPlastic = plastic();
    coatedPlastic.clearcoat = 1.0f;
    coatedPlastic.clearcoatRoughness = 0.3f;
    std::vector<TestMaterial> out;
    for (float r : {0.3f, 0.6f, 1.0f})
        for (float deg : {0.0f, 45.0f, 80.0f}) out.push_back(sheened(lambert(0.0f), "black", 1.0f, r, deg));
    out.push_back(sheened(lambert(0.0f), "black", 1.0f, 0.2f, 60.0f));
    out.push_back(sheened(lambert(0.8f), "Lambert 0.8", 0.7f, 0.5f, 30.0f));
    out.push_back(sheened(lambert(0.8f), "Lambert 0.8", 1.0f, 0.8f, 75.0f));
    out.push_back(sheened(conductor(), "conductor alpha 0.2", 0.5f, 0.4f, 45.0f));
    out.push_back(sheened(coatedPlastic, "plastic alpha 0.1", 0.6f, 0.7f, 50.0f));
    return out;
}

// E(mu, r) at node (i, j) of the build-time table (tools/sheen-albedo).
double tableNodeMu(int i) {
    const double t = double(i) / (kSheenAlbedoMuCount - 1);
    return std::max(t * t * t, double(kSheenAlbedoMuMin));
}

double tableNodeRoughness(int j) {
    const double s0 = std::sqrt(double(kSheenRoughnessMin));
    const double s = s0 + (1.0 - s0) * j / (kSheenAlbedoRoughnessCount - 1);
    return s * s;
}

}  // namespace

TEST_CASE("sheen: sampling the sheened BSDF matches its pdf (chi-square over roughness, base and incidence)" * doctest::test_suite("slow")) {
    checkBsdfChiSquare(sheenMaterials(), 400);
}

TEST_CASE("sheen: sample weights equal eval / pdf, small roughness and grazing views included") {
    auto materials = sheenMaterials();
    materials.push_back(sheened(lambert(0.0f), "black", 1.0f, 0.0f, 85.0f));
    materials.push_back(sheened(lambert(0.5f), "Lambert 0.5", 1.0f, 0.05f, 89.0f));
    TestMaterial mirror = conductor();
    mirror.roughness = 0.0f;
    materials.push_back(sheened(mirror, "mirror", 0.8f, 0.5f, 40.0f));
    checkBsdfWeights(materials);
}

TEST_CASE("sheen: the build-time albedo table equals the GLSL lobe's directional albedo at its nodes") {
    // Sheen colour 1 over a base that reflects nothing: the mean sample
    // weight is the lobe's albedo, which the table holds at its nodes (where
    // the lookup is the node's value): within 4 standard errors of 2^20
    // samples plus the quadrature's 1e-3 relative (tools/sheen-albedo
    // agrees with itself at twice the resolution to 5e-4). Nodes where E > 1
    // are left out: there the lobe is divided by E (it reflects 1).
    const int mus[] = {8, 16, 24, 31}, roughs[] = {6, 12, 20, 31};
    for (int j : roughs) {
        for (int i : mus) {
            const double mu = tableNodeMu(i), r = tableNodeRoughness(j);
            const double e = kSheenAlbedo[j * kSheenAlbedoMuCount + i];
            if (e > 1.0 || e < 1e-3) continue;
            const float deg = static_cast<float>(std::acos(mu) * 180.0 / std::numbers::pi);
            const TestMaterial m = sheened(lambert(0.0f), "black", 1.0f, static_cast<float>(r), deg);
            const auto [mean, se] = bsdfAlbedo(m, 1u << 20, 61);
            MESSAGE("mu " << mu << " roughness " << r << ": table " << e << ", lobe " << mean << " +- " << se);
            CHECK(std::abs(mean - e) < 1e-3 * e + 4.0 * se);
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("sheen: white furnace: a sheen over black never gains energy, over white Lambert it keeps 1") {
    // Over white Lambert the base keeps 1 - E and the sheen reflects E, so
    // the albedo is 1 up to the table's bilinear interpolation (off its
    // nodes here: 0.004) and 4 standard errors of 2^18 samples. Over black
    // the sheen alone reflects E (at most 1: the lobe is divided by E where
    // the extension's exceeds 1), so at most 1 + 0.004 + 4 se.
    const double interpolation = 0.004;
    double worstBlack = 0.0, worstWhite = 0.0;
    for (float r : {0.0f, 0.05f, 0.2f, 0.5f, 0.75f, 1.0f}) {
        for (float deg : {0.0f, 37.0f, 63.0f, 80.0f, 88.0f}) {
            for (float base : {0.0f, 1.0f}) {
                const TestMaterial m = sheened(lambert(base), base > 0.0f ? "white Lambert" : "black", 1.0f, r, deg);
                CAPTURE(m.name);
                const auto [mean, se] = bsdfAlbedo(m, 1u << 18, 62);
                INFO("albedo " << mean << " +- " << se);
                if (base > 0.0f) {
                    worstWhite = std::max(worstWhite, std::abs(mean - 1.0));
                    CHECK(std::abs(mean - 1.0) < interpolation + 4.0 * se);
                } else {
                    worstBlack = std::max(worstBlack, mean);
                    CHECK(mean <= 1.0 + interpolation + 4.0 * se);
                }
            }
        }
    }
    MESSAGE("largest albedo over black " << worstBlack << ", largest |albedo - 1| over white Lambert " << worstWhite);
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

TestMaterial tinted(TestMaterial m, const std::string& base, glm::vec3 color, float deg) {
    m.specularColor = color;
    m.incidenceDeg = deg;
    m.name = "specular colour (" + std::to_string(color.r) + ", " + std::to_string(color.g) + ", " +
             std::to_string(color.b) + ") on " + base + " at " + std::to_string(int(deg)) + " deg";
    return m;
}

// Tinted dielectrics: rough plastic, rough glass from both sides, a half
// specular, and everything at once (a tinted plastic under a sheen and a
// coat).
std::vector<TestMaterial> tintMaterials() {
    TestMaterial half = plastic();
    half.specular = 0.6f;
    half.roughness = 0.5f;
    TestMaterial all = plastic();
    all.clearcoat = 0.7f;
    all.clearcoatRoughness = 0.4f;
    all.sheen = 0.5f;
    all.sheenRoughness = 0.6f;
    return {tinted(plastic(), "plastic alpha 0.1", {2.0f, 0.5f, 1.0f}, 30.0f),
            tinted(plastic(), "plastic alpha 0.1", {20.0f, 5.0f, 1.0f}, 70.0f),
            tinted(roughGlass(0.2f, true), "rough glass alpha 0.2 entering", {3.0f, 1.0f, 0.5f}, 40.0f),
            tinted(roughGlass(0.2f, false), "rough glass alpha 0.2 leaving", {3.0f, 1.0f, 0.5f}, 30.0f),
            tinted(half, "specular 0.6 plastic roughness 0.5", {0.2f, 4.0f, 1.0f}, 50.0f),
            tinted(all, "plastic under a sheen and a coat", {2.0f, 0.5f, 1.0f}, 60.0f)};
}

}  // namespace

TEST_CASE("specular colour: sampling the tinted BSDF matches its pdf (chi-square, coat and sheen included)") {
    checkBsdfChiSquare(tintMaterials(), 500);
}

TEST_CASE("specular colour: sample weights equal eval / pdf, smooth tinted dielectrics and glass included") {
    auto materials = tintMaterials();
    TestMaterial smooth;
    smooth.roughness = 0.0f;
    smooth.base = 0.5f;
    TestMaterial glass = smooth;
    glass.transmission = 1.0f;
    materials.push_back(tinted(smooth, "smooth plastic", {5.0f, 0.5f, 1.0f}, 45.0f));
    materials.push_back(tinted(glass, "smooth glass", {5.0f, 0.5f, 1.0f}, 45.0f));
    checkBsdfWeights(materials);
}

TEST_CASE("specular colour: a smooth tinted dielectric over black reflects specular x mix(min(F0 c, 1), 1, w(mu)) at every angle") {
    // The spec's F0 at normal incidence, 0.8 x min(0.04 x 5, 1) = 0.16 in
    // red, rising to 0.8 at grazing along the exact Fresnel's shape
    // w = (F(mu) - F0) / (1 - F0): every sample weighs that (1e-5).
    for (float deg : {0.0f, 30.0f, 60.0f, 80.0f, 89.0f}) {
        TestMaterial m = lambert(0.0f);
        m.specular = 0.8f;
        m.roughness = 0.0f;
        m = tinted(m, "smooth black", {5.0f, 0.5f, 1.0f}, deg);
        CAPTURE(m.name);
        const double mu = cosDeg(deg), f0 = 0.04;
        const double fresnel = fresnelDielectric(mu, 1.5);
        const double expected = 0.8 * (0.2 + 0.8 * std::clamp((fresnel - f0) / (1.0 - f0), 0.0, 1.0));
        const auto [mean, se] = bsdfAlbedo(m, 1u << 12, 72);
        MESSAGE(m.name << ": " << mean << " (expected " << expected << ")");
        CHECK(std::abs(mean - expected) < 1e-5 * expected);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("specular colour: a colour of 1 compiled in gives the BSDF without the extension, sample by sample") {
    // F = specular x mix(F0, 1, (F - F0) / (1 - F0)) is the exact Fresnel:
    // the same samples with the same weights and pdfs (relative 1e-5), the
    // probabilities being equal up to rounding (a sample on a strategy's
    // boundary may go the other way: at most 1 in 10^4 allowed).
    for (TestMaterial m : tintMaterials()) {
        m.specularColor = glm::vec3(1.0f);
        CAPTURE(m.name);
        const std::uint32_t n = 1u << 16;
        const std::size_t differ = samplesDiffering(m, gpu::kFeatureSpecularColor, n, 73);
        MESSAGE(m.name << ": " << differ << " of " << n << " samples differ");
        CHECK(differ <= n / 10000);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
