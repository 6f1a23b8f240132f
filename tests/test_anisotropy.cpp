// KHR_materials_anisotropy: the anisotropic GGX (shaders/lib/ggx.glsl,
// lib/bsdf.glsl, the aniso axis). The GLSL BSDF run by sample_test.comp
// (chi-square of its sampling against its density, weights against
// eval / pdf, white furnaces, strength 0 against the isotropic lobe), a
// render test of the direction and rotation against the BSDF's own
// albedo (scenes from scripts/make_material_tests.py: anisotropy-*.gltf),
// and the loader (tests/data/materials/anisotropy.gltf).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "bsdf_util.h"
#include "gltf_util.h"
#include "pack/gpu_scene.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

TestMaterial anisotropic(const std::string& name, float strength, float roughness, float deg, float azimuth) {
    TestMaterial m;
    m.name = name + " strength " + std::to_string(strength) + " roughness " + std::to_string(roughness) + " at " +
             std::to_string(int(deg)) + " deg, azimuth " + std::to_string(int(azimuth));
    m.anisotropy = strength;
    m.roughness = roughness;
    m.incidenceDeg = deg;
    m.azimuthDeg = azimuth;
    return m;
}

TestMaterial metal(float strength, float roughness, float deg, float azimuth) {
    TestMaterial m = anisotropic("white metal", strength, roughness, deg, azimuth);
    m.metallic = 1.0f;
    return m;
}

// Metals, plastic, rough glass from both sides and a coated metal, from
// nearly isotropic to fully stretched, viewed along, across and between
// the stretched axis. The chi-square's cells (pi / 64 wide, 8 quadrature
// nodes a side) do not resolve a lobe much thinner than alpha 0.01 across
// the stretch (at 80 degrees, alpha 0.0025 and 0.01 across 0.81 along gave
// p 0 and 1.5e-4, the largest terms in the lobe's brightest cells): the
// grazing case takes alpha 0.04, and the weights test the sharper ones.
std::vector<TestMaterial> anisotropicMaterials() {
    std::vector<TestMaterial> out = {metal(1.0f, 0.3f, 30.0f, 0.0f), metal(1.0f, 0.3f, 60.0f, 90.0f),
                                     metal(0.6f, 0.5f, 75.0f, 45.0f), metal(0.3f, 0.1f, 10.0f, 130.0f),
                                     metal(0.9f, 0.2f, 80.0f, 20.0f)};
    TestMaterial m = anisotropic("plastic", 0.8f, 0.3f, 45.0f, 60.0f);
    m.base = 0.5f;
    out.push_back(m);
    m = anisotropic("rough glass entering", 0.7f, 0.4f, 30.0f, 100.0f);
    m.transmission = 1.0f;
    out.push_back(m);
    m = anisotropic("rough glass leaving", 0.7f, 0.4f, 20.0f, 10.0f);
    m.transmission = 1.0f;
    m.entering = false;
    out.push_back(m);
    m = metal(0.8f, 0.3f, 50.0f, 70.0f);
    m.name = "coated " + m.name;
    m.clearcoat = 1.0f;
    m.clearcoatRoughness = 0.2f;
    out.push_back(m);
    return out;
}

}  // namespace

TEST_CASE("anisotropy: sampling the anisotropic GGX matches its pdf (chi-square over strength, roughness, view and azimuth)") {
    checkBsdfChiSquare(anisotropicMaterials(), 1200);
}

TEST_CASE("anisotropy: sample weights equal eval / pdf, a mirror across the stretched axis included") {
    auto materials = anisotropicMaterials();
    materials.push_back(metal(1.0f, 0.0f, 40.0f, 30.0f));  // alpha 0 across, 1 along: not a delta
    materials.push_back(metal(0.02f, 0.0f, 40.0f, 30.0f));  // both below 1e-3: the mirror
    checkBsdfWeights(materials);
}

TEST_CASE("anisotropy: white furnace: an anisotropic metal of albedo 1 never gains energy") {
    // A white metal reflects everything its single-scattering lobe does:
    // at most 1 (4 standard errors of 2^18 samples), whatever the strength,
    // roughness, view and azimuth.
    double worst = 0.0;
    for (float strength : {0.5f, 1.0f}) {
        for (float roughness : {0.1f, 0.5f, 1.0f}) {
            for (float deg : {0.0f, 60.0f, 85.0f}) {
                for (float azimuth : {0.0f, 45.0f, 90.0f}) {
                    const TestMaterial m = metal(strength, roughness, deg, azimuth);
                    CAPTURE(m.name);
                    const auto [mean, se] = bsdfAlbedo(m, 1u << 18, 1201);
                    worst = std::max(worst, mean);
                    CHECK(mean <= 1.0 + 4.0 * se);
                    CHECK(mean > 0.3);
                }
            }
        }
    }
    MESSAGE("largest albedo " << worst);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("anisotropy: strength 0 compiled in gives the isotropic lobe, sample by sample") {
    // alpha along = alpha across: the anisotropic D, Lambda and visible
    // normals are the isotropic ones written differently (relative 1e-5;
    // a sample on a strategy's boundary may go the other way: at most 1 in
    // 10^4 allowed).
    for (TestMaterial m : anisotropicMaterials()) {
        m.anisotropy = 0.0f;
        CAPTURE(m.name);
        const std::uint32_t n = 1u << 16;
        const std::size_t differ = samplesDiffering(m, gpu::kFeatureAnisotropy, n, 1202);
        MESSAGE(m.name << ": " << differ << " of " << n << " samples differ");
        CHECK(differ <= n / 10000);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("anisotropy: a brushed plate seen across and along its stretched axis shows the lobe's albedo in each, the texture's direction too") {
    // anisotropy-0.gltf stretches the lobe along the tangent (+Y, the
    // direction of u) and the camera looks 60 degrees off the normal in the
    // Y-Z plane: along the stretched axis (azimuth 0 in the lobe's frame).
    // anisotropyRotation pi/2 turns the stretch to the bitangent (X): the
    // view is across it (azimuth 90). Each image mean must be the BSDF's
    // albedo there (4 combined standard errors plus 2e-3 for the 1-degree
    // view), and the two must differ: the loader's tangents, the rotation
    // and the shading frame all reach the lobe (without tangents the frame
    // about +Z would put the stretch along X in both).
    const FurnaceMean fAlong = whiteFurnaceMean("tests/data/materials/anisotropy-0.gltf", gpu::kFeatureAnisotropy);
    const FurnaceMean fAcross = whiteFurnaceMean("tests/data/materials/anisotropy-90.gltf", gpu::kFeatureAnisotropy);
    const double along = fAlong.mean.x, seAlong = fAlong.se.x, across = fAcross.mean.x, seAcross = fAcross.se.x;
    const auto [eAcross, seEAcross] = bsdfAlbedo(metal(1.0f, 0.3f, 60.0f, 90.0f), 1u << 18, 1203);
    const auto [eAlong, seEAlong] = bsdfAlbedo(metal(1.0f, 0.3f, 60.0f, 0.0f), 1u << 18, 1204);
    MESSAGE("across: image " << across << " +- " << seAcross << ", lobe " << eAcross << " +- " << seEAcross);
    MESSAGE("along: image " << along << " +- " << seAlong << ", lobe " << eAlong << " +- " << seEAlong);
    CHECK(std::abs(across - eAcross) < 4.0 * std::hypot(seAcross, seEAcross) + 2e-3);
    CHECK(std::abs(along - eAlong) < 4.0 * std::hypot(seAlong, seEAlong) + 2e-3);
    CHECK(std::abs(eAcross - eAlong) > 0.05);
    // anisotropyTexture's RG turns the stretch as the rotation does: the
    // texel (128, 255) points along the bitangent (make_material_tests.py).
    const FurnaceMean fTextured = whiteFurnaceMean("tests/data/materials/anisotropy-textured.gltf", gpu::kFeatureAnisotropy);
    MESSAGE("textured: image " << fTextured.mean.x << " +- " << fTextured.se.x);
    CHECK(std::abs(fTextured.mean.x - eAcross) < 4.0 * std::hypot(fTextured.se.x, seEAcross) + 2e-3);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

TEST_CASE("gltf materials: KHR_materials_anisotropy strength, rotation and texture (texCoord 1), and tangents generated") {
    const Scene scene = loadGltf(dataPath("materials/anisotropy.gltf"));
    const MaterialDesc& a = scene.materials.at(0);
    REQUIRE(a.name == "Brushed");
    CHECK(a.anisotropyStrength == doctest::Approx(0.8));
    CHECK(a.anisotropyRotation == doctest::Approx(0.5));
    CHECK(a.anisotropyTexture.texture == 0);
    CHECK(a.anisotropyTexture.texCoord == 1);
    CHECK(a.anisotropic());
    CHECK(!scene.tangents.empty());  // the file has no TANGENT
    const MaterialDesc& d = scene.materials.at(1);
    CHECK(d.anisotropyStrength == 0.0f);
    CHECK(d.anisotropyRotation == 0.0f);
    CHECK_FALSE(d.anisotropic());
    const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
    CHECK((gpu.features.bits & gpu::kFeatureAnisotropy) != 0u);
    CHECK(!gpu.tangents.empty());
    const auto names = gpu.features.names();
    CHECK(std::find(names.begin(), names.end(), "anisotropy") != names.end());
    const gpu::Material& packed = gpu.materials.at(0);
    CHECK((packed.flags & gpu::kMaterialAnisotropy) != 0u);
    CHECK(packed.anisotropyStrength == doctest::Approx(0.8));
    CHECK(packed.anisotropyRotation == doctest::Approx(0.5));
    REQUIRE(packed.anisotropyTex != gpu::kNoTexture);
    CHECK((gpu.textureRefs.at(packed.anisotropyTex).flags & gpu::kTexCoord1) != 0u);
    CHECK((gpu.textureRefs.at(packed.anisotropyTex).flags & gpu::kTexSrgb) == 0u);
    CHECK((gpu.materials.at(1).flags & gpu::kMaterialAnisotropy) == 0u);
}

TEST_SUITE_END();
