// glTF loader: the material layer extensions (KHR_materials_clearcoat,
// KHR_materials_sheen, KHR_materials_specular's colour and textures) load to the file's values and textures; a bad value is one error line
// naming the file, the material and the value. Data:
// scripts/make_material_tests.py (tests/data/materials/layers.gltf, broken/).
#include <doctest/doctest.h>

#include <string>

#include "cli_util.h"
#include "gltf_util.h"
#include "pack/gpu_scene.h"
#include "pack/textures.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("unit");

namespace {

const MaterialDesc& materialNamed(const Scene& scene, const std::string& name) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == name) return m;
    FAIL("no material " << name);
    return scene.materials.front();
}

}  // namespace

TEST_CASE("gltf materials: the layer extensions are supported: no warning names them") {
    CerrCapture capture;
    const Scene scene = loadGltf(dataPath("materials/layers.gltf"));
    CHECK(scene.extensionsUsed.size() == 4);
    CHECK(capture.text().find("KHR_materials") == std::string::npos);
}

TEST_CASE("gltf materials: KHR_materials_clearcoat factors, textures (texCoord, transform) and normal scale") {
    const Scene scene = loadGltf(dataPath("materials/layers.gltf"));
    const MaterialDesc& coat = materialNamed(scene, "Coat");
    CHECK(coat.clearcoat == doctest::Approx(0.8));
    CHECK(coat.clearcoatRoughness == doctest::Approx(0.3));
    CHECK(coat.clearcoatTexture.texture == 0);
    CHECK(coat.clearcoatTexture.texCoord == 0);
    CHECK(coat.clearcoatRoughnessTexture.texture == 1);
    CHECK(coat.clearcoatRoughnessTexture.texCoord == 1);
    CHECK(coat.clearcoatNormalTexture.texture == 1);
    CHECK(coat.clearcoatNormalScale == doctest::Approx(0.5));
    CHECK(coat.clearcoatNormalTexture.transform.offset == glm::vec2(0.5f, 0.25f));
    CHECK(coat.clearcoatNormalTexture.transform.scale == glm::vec2(2.0f));
    CHECK(coat.coated());
    // The coat's normal map needs tangents (generated: the file has none).
    CHECK(!scene.tangents.empty());
    // The extension with no members: the spec's defaults, no coat.
    const MaterialDesc& defaults = materialNamed(scene, "Defaults");
    CHECK(defaults.clearcoat == 0.0f);
    CHECK(defaults.clearcoatRoughness == 0.0f);
    CHECK_FALSE(defaults.clearcoatTexture.used());
    CHECK_FALSE(defaults.clearcoatNormalTexture.used());
    CHECK(defaults.clearcoatNormalScale == 1.0f);
    CHECK_FALSE(defaults.coated());
    // Packed: the coat's flag, factors and three texture slots; the feature bits.
    const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
    CHECK((gpu.features.bits & gpu::kFeatureClearcoat) != 0u);
    CHECK((gpu.features.bits & gpu::kFeatureNormalMap) != 0u);
    const auto names = gpu.features.names();
    CHECK(std::find(names.begin(), names.end(), "clearcoat") != names.end());
    const gpu::Material& packed = gpu.materials.at(0);
    CHECK((packed.flags & gpu::kMaterialClearcoat) != 0u);
    CHECK(packed.clearcoat == doctest::Approx(0.8));
    CHECK(packed.clearcoatNormalScale == doctest::Approx(0.5));
    CHECK(packed.clearcoatTex != gpu::kNoTexture);
    CHECK(packed.clearcoatRoughnessTex != gpu::kNoTexture);
    CHECK(packed.clearcoatNormalTex != gpu::kNoTexture);
    CHECK((gpu.textureRefs.at(packed.clearcoatRoughnessTex).flags & gpu::kTexCoord1) != 0u);
    CHECK((gpu.materials.at(1).flags & gpu::kMaterialClearcoat) == 0u);
}

TEST_CASE("gltf materials: KHR_materials_sheen colour, roughness and their textures (sRGB colour, texCoord 1)") {
    const Scene scene = loadGltf(dataPath("materials/layers.gltf"));
    const MaterialDesc& sheen = materialNamed(scene, "Sheen");
    CHECK(sheen.sheenColor == glm::vec3(0.9f, 0.6f, 0.3f));
    CHECK(sheen.sheenRoughness == doctest::Approx(0.4));
    CHECK(sheen.sheenColorTexture.texture == 0);
    CHECK(sheen.sheenRoughnessTexture.texture == 1);
    CHECK(sheen.sheenRoughnessTexture.texCoord == 1);
    CHECK(sheen.sheened());
    const MaterialDesc& defaults = materialNamed(scene, "Defaults");
    CHECK(defaults.sheenColor == glm::vec3(0.0f));
    CHECK(defaults.sheenRoughness == 0.0f);
    CHECK_FALSE(defaults.sheened());
    const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
    CHECK((gpu.features.bits & gpu::kFeatureSheen) != 0u);
    const auto names = gpu.features.names();
    CHECK(std::find(names.begin(), names.end(), "sheen") != names.end());
    const gpu::Material& packed = gpu.materials.at(1);
    CHECK((packed.flags & gpu::kMaterialSheen) != 0u);
    CHECK(packed.sheenColor == glm::vec3(0.9f, 0.6f, 0.3f));
    CHECK(packed.sheenRoughness == doctest::Approx(0.4));
    REQUIRE(packed.sheenColorTex != gpu::kNoTexture);
    REQUIRE(packed.sheenRoughnessTex != gpu::kNoTexture);
    CHECK((gpu.textureRefs.at(packed.sheenColorTex).flags & gpu::kTexSrgb) != 0u);
    CHECK((gpu.textureRefs.at(packed.sheenRoughnessTex).flags & gpu::kTexSrgb) == 0u);
    CHECK((gpu.textureRefs.at(packed.sheenRoughnessTex).flags & gpu::kTexCoord1) != 0u);
    // The texel words start with the sheen albedo table (lib/sheen.glsl reads it there).
    const auto table = sheenAlbedoWords();
    REQUIRE(gpu.texels.size() > table.size());
    CHECK(std::equal(table.begin(), table.end(), gpu.texels.begin()));
    CHECK(gpu.textureRefs.at(packed.sheenColorTex).offset >= table.size());
}

TEST_CASE("gltf materials: KHR_materials_specular colour (above 1 allowed) and textures (sRGB colour, A factor)") {
    const Scene scene = loadGltf(dataPath("materials/layers.gltf"));
    const MaterialDesc& m = materialNamed(scene, "Specular");
    CHECK(m.specular == doctest::Approx(0.7));
    CHECK(m.specularColor == glm::vec3(2.0f, 0.5f, 1.0f));
    CHECK(m.specularTexture.texture == 1);
    CHECK(m.specularColorTexture.texture == 0);
    CHECK(m.specularColorTexture.texCoord == 1);
    CHECK(m.tinted());
    const MaterialDesc& defaults = materialNamed(scene, "Defaults");
    CHECK(defaults.specular == 1.0f);
    CHECK(defaults.specularColor == glm::vec3(1.0f));
    CHECK_FALSE(defaults.tinted());
    const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
    CHECK((gpu.features.bits & gpu::kFeatureSpecularColor) != 0u);
    const auto names = gpu.features.names();
    CHECK(std::find(names.begin(), names.end(), "specular-color") != names.end());
    const gpu::Material& packed = gpu.materials.at(2);
    CHECK((packed.flags & gpu::kMaterialSpecularColor) != 0u);
    CHECK(packed.specularColor == glm::vec3(2.0f, 0.5f, 1.0f));
    REQUIRE(packed.specularColorTex != gpu::kNoTexture);
    REQUIRE(packed.specularTex != gpu::kNoTexture);
    CHECK((gpu.textureRefs.at(packed.specularColorTex).flags & gpu::kTexSrgb) != 0u);
    CHECK((gpu.textureRefs.at(packed.specularColorTex).flags & gpu::kTexCoord1) != 0u);
    CHECK((gpu.textureRefs.at(packed.specularTex).flags & gpu::kTexSrgb) == 0u);
    CHECK((gpu.materials.at(3).flags & gpu::kMaterialSpecularColor) == 0u);
}

TEST_CASE("gltf materials: scenes without the layer extensions have none of their feature bits") {
    for (const char* file : {"scenes/materials-board.gltf", "scenes/cornell-box.gltf", "scenes/cornell-glass.gltf"}) {
        CAPTURE(file);
        const Scene scene = loadGltf(sourcePath(file));
        for (const MaterialDesc& m : scene.materials) CHECK_FALSE((m.coated() || m.sheened() || m.tinted()));
        const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
        CHECK((gpu.features.bits & (gpu::kFeatureClearcoat | gpu::kFeatureSheen | gpu::kFeatureSpecularColor)) == 0u);
    }
}

TEST_CASE("gltf materials: KHR_materials_iridescence's factors, with the extension's defaults") {
    const Scene scene = loadGltf(dataPath("materials/iridescence-metal.gltf"), LoadOptions{false, false});
    REQUIRE(scene.materials.size() >= 1);
    const MaterialDesc& m = scene.materials[0];
    CHECK(m.iridescent());
    CHECK(m.iridescence == 1.0f);
    CHECK(m.iridescenceIor == doctest::Approx(1.3));
    CHECK(m.iridescenceThicknessMin == 100.0f);  // the default
    CHECK(m.iridescenceThicknessMax == 250.0f);
    CHECK_FALSE(m.iridescenceTexture.used());
    const GpuScene gpu = packScene(scene, buildSceneBvh(scene));
    CHECK((gpu.features.bits & gpu::kFeatureIridescence) != 0u);
    CHECK((gpu.materials[0].flags & gpu::kMaterialIridescence) != 0u);
}

TEST_CASE("gltf materials: every broken layer value is one error line naming file, material and value") {
    struct Case {
        const char* file;
        const char* expected;
    };
    const Case cases[] = {
        {"clearcoat-negative.gltf", "material 0 (\"Bad\"): KHR_materials_clearcoat.clearcoatFactor -0.5 is not in [0, 1]"},
        {"clearcoat-roughness-above-1.gltf",
         "material 0 (\"Bad\"): KHR_materials_clearcoat.clearcoatRoughnessFactor 1.5 is not in [0, 1]"},
        {"clearcoat-missing-texture.gltf",
         "material 0 (\"Bad\") clearcoatTexture: texture 5 does not exist (2 textures)"},
        {"sheen-color-above-1.gltf", "material 0 (\"Bad\"): KHR_materials_sheen.sheenColorFactor is not three numbers in [0, 1]"},
        {"sheen-color-two-numbers.gltf",
         "material 0 (\"Bad\"): KHR_materials_sheen.sheenColorFactor is not three numbers in [0, 1]"},
        {"specular-color-negative.gltf",
         "material 0 (\"Bad\"): KHR_materials_specular.specularColorFactor is not three numbers in [0, inf)"},
        {"specular-texture-missing.gltf", "material 0 (\"Bad\") specularColorTexture: texture 9 does not exist (2 textures)"},
        {"sheen-roughness-negative.gltf",
         "material 0 (\"Bad\"): KHR_materials_sheen.sheenRoughnessFactor -0.1 is not in [0, 1]"},
        {"iridescence-factor-above-1.gltf",
         "material 0 (\"Bad\"): KHR_materials_iridescence.iridescenceFactor 1.5 is not in [0, 1]"},
        {"iridescence-ior-below-1.gltf", "material 0 (\"Bad\"): KHR_materials_iridescence.iridescenceIor 0.5 is below 1"},
        {"iridescence-thickness-negative.gltf",
         "material 0 (\"Bad\"): KHR_materials_iridescence.iridescenceThicknessMaximum -10 is not a finite number >= 0"},
        {"diffuse-transmission-above-1.gltf",
         "material 0 (\"Bad\"): KHR_materials_diffuse_transmission.diffuseTransmissionFactor 1.5 is not in [0, 1]"},
        {"diffuse-transmission-string.gltf",
         "material 0 (\"Bad\"): KHR_materials_diffuse_transmission.diffuseTransmissionFactor is not a number"},
        {"diffuse-transmission-color-negative.gltf",
         "material 0 (\"Bad\"): KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor is not three numbers "
         "in [0, 1]"},
        {"diffuse-transmission-texture-missing.gltf",
         "material 0 (\"Bad\") diffuseTransmissionColorTexture: texture 7 does not exist (2 textures)"},
        {"anisotropy-strength-above-1.gltf",
         "material 0 (\"Bad\"): KHR_materials_anisotropy.anisotropyStrength 1.5 is not in [0, 1]"},
        {"anisotropy-rotation-string.gltf",
         "material 0 (\"Bad\"): KHR_materials_anisotropy.anisotropyRotation is not a number"},
        {"anisotropy-texture-missing.gltf",
         "material 0 (\"Bad\") anisotropyTexture: texture 3 does not exist (2 textures)"},
    };
    std::vector<std::pair<std::string, std::string>> list;
    for (const Case& c : cases) list.emplace_back(c.file, c.expected);
    checkBrokenFolder("materials/broken", list);
}

TEST_SUITE_END();
