// KHR_materials_diffuse_transmission: the Lambertian lobe through the
// surface (shaders/lib/bsdf.glsl, the difftrans axis). The GLSL BSDF run by
// sample_test.comp (chi-square of its sampling against its density, weights
// against eval / pdf, white furnaces), render tests against closed forms
// (scenes from scripts/make_material_tests.py: translucent-*.gltf), and the
// loader (tests/data/materials/diffuse-transmission.gltf).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bsdf_util.h"
#include "gltf_util.h"
#include "pack/gpu_scene.h"
#include "pack/textures.h"
#include "stats/stats.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

TestMaterial translucent(const std::string& name, float factor, float color, float base, float deg) {
    TestMaterial m;
    m.name = name + " factor " + std::to_string(factor) + " colour " + std::to_string(color) + " base " +
             std::to_string(base) + " at " + std::to_string(int(deg)) + " deg";
    m.diffuseTransmission = factor;
    m.diffuseTransmissionColor = color;
    m.base = base;
    m.incidenceDeg = deg;
    return m;
}

// Diffuse transmission over Lambert (specular 0), rough plastic,
// a half-metal, rough glass (KHR_materials_transmission takes its share
// first), under a coat, and a back face (leaving a volume), at incidence 0
// to 85 degrees.
std::vector<TestMaterial> translucentMaterials() {
    std::vector<TestMaterial> out;
    TestMaterial m = translucent("Lambert", 0.5f, 0.8f, 0.6f, 0.0f);
    m.specular = 0.0f;
    out.push_back(m);
    m = translucent("Lambert", 1.0f, 0.3f, 0.6f, 70.0f);
    m.specular = 0.0f;
    out.push_back(m);
    m = translucent("plastic alpha 0.1", 0.7f, 0.9f, 0.5f, 45.0f);
    m.roughness = std::sqrt(0.1f);
    out.push_back(m);
    m = translucent("half metal", 0.8f, 0.7f, 0.9f, 60.0f);
    m.metallic = 0.5f;
    m.roughness = 0.6f;
    out.push_back(m);
    m = translucent("rough glass half transmission", 0.6f, 0.9f, 0.9f, 20.0f);
    m.transmission = 0.5f;
    m.roughness = std::sqrt(0.3f);
    out.push_back(m);
    m = translucent("coated", 0.5f, 0.6f, 0.7f, 50.0f);
    m.clearcoat = 1.0f;
    m.clearcoatRoughness = 0.3f;
    out.push_back(m);
    m = translucent("leaving", 0.9f, 0.8f, 0.4f, 85.0f);
    m.entering = false;
    out.push_back(m);
    return out;
}

double cosDeg(double deg) { return std::cos(deg * std::numbers::pi / 180.0); }

}  // namespace

TEST_CASE("diffuse transmission: sampling the BSDF matches its pdf over both hemispheres (chi-square)") {
    checkBsdfChiSquare(translucentMaterials(), 900);
}

TEST_CASE("diffuse transmission: sample weights equal eval / pdf, a smooth (delta) reflection included") {
    auto materials = translucentMaterials();
    TestMaterial m = translucent("smooth plastic", 0.4f, 1.0f, 0.8f, 30.0f);
    m.roughness = 0.0f;
    materials.push_back(m);
    checkBsdfWeights(materials);
}

TEST_CASE("diffuse transmission: white furnace: without Fresnel every sample weighs exactly 1, with it never above 1") {
    // ior 1 (no Fresnel, no specular lobe): white Lambert reflection and
    // white transmission split by the factor, each strategy chosen with its
    // own share, so every sample's weight is 1 (float rounding 1e-5) and
    // the share sent below is the factor. With ior 1.5 the lobes beneath
    // keep 1 - Fd, so the albedo is at most 1 (4 standard errors).
    for (float factor : {0.25f, 0.5f, 1.0f}) {
        for (float deg : {0.0f, 45.0f, 80.0f}) {
            TestMaterial m = translucent("white", factor, 1.0f, 1.0f, deg);
            m.ior = 1.0f;
            CAPTURE(m.name);
            const auto s = runBsdf(m, gpu::kSampleBsdf, 1u << 16, 91);
            const auto w = runBsdf(m, gpu::kSampleBsdfWeight, 1u << 16, 91);
            double below = 0.0, worst = 0.0;
            for (std::size_t i = 0; i < s.size(); ++i) {
                REQUIRE(s[i].w != 0.0f);  // every sample valid
                below += s[i].z < 0.0f ? 1.0 : 0.0;
                worst = std::max(worst, std::abs(double(w[i].x) - 1.0));
            }
            const double share = below / double(s.size()), se = std::sqrt(factor * (1.0 - factor) / double(s.size()));
            MESSAGE(m.name << ": largest |weight - 1| " << worst << ", share below " << share);
            CHECK(worst < 1e-5);
            CHECK(std::abs(share - factor) <= 4.0 * se + 1e-12);
            m.ior = 1.5f;
            const auto [mean, se15] = bsdfAlbedo(m, 1u << 18, 92);
            MESSAGE("ior 1.5: albedo " << mean << " +- " << se15);
            CHECK(mean <= 1.0 + 4.0 * se15);
            CHECK(mean >= 0.85);
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("diffuse transmission: seen from inside a volume the albedo stays at most 1, beyond the critical angle too") {
    // A glossy white dielectric of ior 1.4 that transmits all its diffuse
    // light, seen from inside (the back face of a ball with a volume):
    // beyond 45.6 degrees the GGX lobe reflects almost everything by total
    // internal reflection. Fd taken at the half vector of wo and the
    // mirrored wi left the transmitted lobe up to 1 - Fd there as well:
    // albedo 1.5 to 1.6 at 50 to 75 degrees, and a ball of wax in a furnace
    // glowed. The diffuse lobes now leave the GGX lobe's albedo (its Fresnel
    // over 16 fixed visible normals, `ggxLobeAlbedo`); that quadrature of a
    // Fresnel that jumps to 1 at the critical angle is off by up to 2%, so
    // the bound here is 1.025 (measured: 1.020 at 30 degrees, 1.017 at 50).
    for (float deg : {30.0f, 50.0f, 60.0f, 75.0f}) {
        TestMaterial m = translucent("white inside", 1.0f, 1.0f, 1.0f, deg);
        m.ior = 1.4f;
        m.roughness = 0.35f;
        m.entering = false;
        CAPTURE(m.name);
        const auto [mean, se] = bsdfAlbedo(m, 1u << 18, 93);
        MESSAGE(m.name << ": albedo " << mean << " +- " << se);
        CHECK(mean <= 1.025 + 4.0 * se);
    }
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// Renders `file` (16 x 16, 256 spp, maxDepth 1) in a uniform environment of
// radiance 1 and checks each channel's image mean against expected[c]
// within 4 standard errors plus 1e-4 relative.
void checkTranslucentFurnace(const std::string& file, const glm::dvec3& expected) {
    const FurnaceMean f = whiteFurnaceMean(file, gpu::kFeatureDiffuseTransmission);
    for (int c = 0; c < 3; ++c) {
        MESSAGE(file << " channel " << c << ": " << f.mean[c] << " +- " << f.se[c] << " (expected " << expected[c] << ")");
        CHECK(std::abs(f.mean[c] - expected[c]) < 1e-4 * expected[c] + 4.0 * f.se[c]);
    }
    CHECK(vk::validationMessageCount() == 0);
}

}  // namespace

TEST_CASE("diffuse transmission: a sheet of colour 1 and factor 1 in a white furnace is 1, and factor 0.5 mixes base and colour") {
    checkTranslucentFurnace("tests/data/materials/translucent-white.gltf", glm::dvec3(1.0));
    // (1 - 0.5) baseColor + 0.5 diffuseTransmissionColor (make_material_tests.py).
    const glm::dvec3 base(0.2, 0.6, 1.0), color(1.0, 0.5, 0.25);
    checkTranslucentFurnace("tests/data/materials/translucent-mix.gltf", 0.5 * base + 0.5 * color);
}

TEST_CASE("diffuse transmission: diffuseTransmissionTexture (A) scales the factor and diffuseTransmissionColorTexture (sRGB RGB) the colour") {
    // A black plate of ior 1 (make_material_tests.py: TRANSLUCENT_TEXEL
    // (188, 128, 64, 128)): in a white furnace it transmits 128/255 of the
    // light in the texel's colour, linear.
    const glm::dvec3 color(srgbToLinear(188.0 / 255.0), srgbToLinear(128.0 / 255.0), srgbToLinear(64.0 / 255.0));
    checkTranslucentFurnace("tests/data/materials/translucent-textured.gltf", 128.0 / 255.0 * color);
}

TEST_CASE("diffuse transmission: a sheet lit on its front by the sun, seen from behind, shows factor colour E (1 - Fd) / pi") {
    // Black base (nothing reflected), ior 1.5, the sun's irradiance E = 2 on
    // the front, the camera about 60 degrees off the back's normal. Fd is
    // taken at the half vector of the view and the light mirrored to the
    // view's side (about 30 degrees from the normal), with the outside's ior
    // on both faces (thin-walled: the back face does not see the inside of a
    // volume, whose Fresnel at 1/1.5 would give 0.0552 instead of 0.0415).
    // Every sample is the closed form at its ray (a delta light, nothing
    // else lit), so a pixel is its mean over the pixel (8 x 8 points) to
    // float rounding (1e-5 relative).
    RenderSettings s;
    s.width = s.height = 8;
    s.spp = 16;
    s.maxDepth = 1;
    const Rendered r = renderFile("tests/data/materials/translucent-backlit.gltf", s);
    CHECK((r.gpu.features.bits & gpu::kFeatureDiffuseTransmission) != 0u);
    const glm::dvec3 color(0.9, 0.6, 0.3);
    const Camera& cam = r.scene.cameras.at(0);
    const auto m = r.result.film.mean();
    double worst = 0.0;
    for (int py = 0; py < s.height; ++py) {
        for (int px = 0; px < s.width; ++px) {
            double sum = 0.0;
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) {
                    // The view's direction on the back's side (normal -Z)
                    // and the light's mirrored there: -Z.
                    const glm::dvec3 wo = -cameraRay(cam, s.width, s.height, px + (i + 0.5) / 8.0, py + (j + 0.5) / 8.0);
                    const double c = glm::dot(wo, glm::normalize(wo + glm::dvec3(0.0, 0.0, -1.0)));
                    sum += 1.0 - fresnelDielectric(c, 1.5);
                }
            for (int k = 0; k < 3; ++k) {
                const double expected = 0.7 * color[k] * 2.0 * (sum / 64.0) / std::numbers::pi;
                const double value = m[(std::size_t(py) * s.width + px) * 3 + k];
                worst = std::max(worst, std::abs(value / expected - 1.0));
            }
        }
    }
    MESSAGE("1 - Fd at 30 degrees " << 1.0 - fresnelDielectric(cosDeg(30.0), 1.5) << "; largest relative error " << worst);
    CHECK(worst < 1e-5);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

TEST_CASE("gltf materials: KHR_materials_diffuse_transmission factor, colour and textures (A, sRGB RGB, texCoord 1)") {
    const Scene scene = loadGltf(dataPath("materials/diffuse-transmission.gltf"));
    const MaterialDesc& t = scene.materials.at(0);
    REQUIRE(t.name == "Translucent");
    CHECK(t.diffuseTransmission == doctest::Approx(0.6));
    CHECK(t.diffuseTransmissionColor == glm::vec3(0.9f, 0.5f, 0.2f));
    CHECK(t.diffuseTransmissionTexture.texture == 1);
    CHECK(t.diffuseTransmissionColorTexture.texture == 0);
    CHECK(t.diffuseTransmissionColorTexture.texCoord == 1);
    CHECK(t.diffuselyTransmitting());
    // The extension with no members: the spec's defaults, no lobe.
    const MaterialDesc& d = scene.materials.at(1);
    CHECK(d.diffuseTransmission == 0.0f);
    CHECK(d.diffuseTransmissionColor == glm::vec3(1.0f));
    CHECK_FALSE(d.diffuselyTransmitting());
    const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
    CHECK((gpu.features.bits & gpu::kFeatureDiffuseTransmission) != 0u);
    const auto names = gpu.features.names();
    CHECK(std::find(names.begin(), names.end(), "diffuse-transmission") != names.end());
    const gpu::Material& packed = gpu.materials.at(0);
    CHECK((packed.flags & gpu::kMaterialDiffuseTransmission) != 0u);
    CHECK((packed.flags & gpu::kMaterialThinWalled) != 0u);  // no KHR_materials_volume
    CHECK(packed.diffuseTransmission == doctest::Approx(0.6));
    CHECK(packed.diffuseTransmissionColor == glm::vec3(0.9f, 0.5f, 0.2f));
    REQUIRE(packed.diffuseTransmissionTex != gpu::kNoTexture);
    REQUIRE(packed.diffuseTransmissionColorTex != gpu::kNoTexture);
    CHECK((gpu.textureRefs.at(packed.diffuseTransmissionColorTex).flags & gpu::kTexCoord1) != 0u);
    CHECK((gpu.textureRefs.at(packed.diffuseTransmissionColorTex).flags & gpu::kTexSrgb) != 0u);
    CHECK((gpu.textureRefs.at(packed.diffuseTransmissionTex).flags & gpu::kTexSrgb) == 0u);
    CHECK((gpu.materials.at(1).flags & gpu::kMaterialDiffuseTransmission) == 0u);
    CHECK(gpu.materials.at(1).diffuseTransmissionTex == gpu::kNoTexture);
}

TEST_SUITE_END();
