// glTF loader: feature files load to hand-computed values; every broken file
// fails with one line "<path>: error: <problem>". Data: tests/data/ (made by
// tests/data/make_features.py and make_broken.py) and scenes/.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "gltf_util.h"
#include "scene/scene.h"
#include "util/error.h"

TEST_SUITE_BEGIN("unit");

namespace {

using strata::LoadOptions;
using strata::MaterialDesc;
using strata::Scene;
using namespace strata::test;

const LoadOptions kNoRequirements{false, false};

Scene loadFeature(const std::string& name, const LoadOptions& options = kNoRequirements) {
    return strata::loadGltf(dataPath("features/" + name), options);
}

}  // namespace

TEST_CASE("gltf: node hierarchy with TRS and matrix transforms") {
    const Scene scene = loadFeature("hierarchy.gltf");
    REQUIRE(scene.triangles.size() == 3);
    // Parent T(1,2,3) R_y(90) S(2) * Child matrix T(0,0,1) S(1,2,1); R_y(90)
    // maps (x,y,z) -> (z,y,-x).
    checkTriangle(scene.triangles[0], {3, 2, 3}, {3, 2, 1}, {3, 6, 3});
    checkNormals(scene.triangles[0], {1, 0, 0});
    // Root matrix T(10,0,0), after the Parent subtree (depth-first order).
    checkTriangle(scene.triangles[1], {10, 0, 0}, {11, 0, 0}, {10, 1, 0});
    checkNormals(scene.triangles[1], {0, 0, 1});
    // Non-uniform scale S(2,1,1): normals use the inverse transpose,
    // (1,0,1)/sqrt2 -> (1,0,2)/sqrt5, not (2,0,1).
    checkTriangle(scene.triangles[2], {0, 0, 0}, {2, 0, -1}, {0, 1, 0});
    checkNormals(scene.triangles[2], glm::vec3(1, 0, 2) / std::sqrt(5.0f));
    for (const auto& t : scene.triangles) checkFrontFaceMatchesNormals(t);
    // No primitive names a material: the default one, alone.
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].name == "default");
    CHECK(scene.triangles[0].material == 0);
}

TEST_CASE("gltf: negative determinant flips the winding, keeps the front face") {
    const Scene scene = loadFeature("negative-scale.gltf");
    REQUIRE(scene.triangles.size() == 4);
    // Original: plane x = 1, front face +X.
    checkTriangle(scene.triangles[0], {1, 0, 0}, {1, 1, 0}, {1, 0, 1});
    checkNormals(scene.triangles[0], {1, 0, 0});
    // Mirrored in X: vertices 1 and 2 swapped, the front face is -X.
    checkTriangle(scene.triangles[1], {-1, 0, 0}, {-1, 0, 1}, {-1, 1, 0});
    checkNormals(scene.triangles[1], {-1, 0, 0});
    // Two mirrors (S(-1,1,1) * S(1,-1,1)): determinant > 0, order kept.
    checkTriangle(scene.triangles[2], {-1, 0, 0}, {-1, -1, 0}, {-1, 0, 1});
    checkNormals(scene.triangles[2], {-1, 0, 0});
    // Mirrored without NORMAL: the geometric normal of the swapped triangle.
    checkTriangle(scene.triangles[3], {-1, 0, 0}, {-1, 0, 1}, {-1, 1, 0});
    checkNormals(scene.triangles[3], {-1, 0, 0});
    for (const auto& t : scene.triangles) checkFrontFaceMatchesNormals(t);
}

TEST_CASE("gltf: u8, u16, u32 indices and non-indexed primitives") {
    const Scene scene = loadFeature("indices.gltf");
    REQUIRE(scene.triangles.size() == 8);
    // Quad (0,0,0) (1,0,0) (1,1,0) (0,1,0), indices 0 1 2 0 2 3, primitive k
    // shifted by 2k in x; k = 3 is the same quad without indices.
    for (int k = 0; k < 4; ++k) {
        CAPTURE(k);
        const glm::vec3 o(2.0f * static_cast<float>(k), 0, 0);
        checkTriangle(scene.triangles[static_cast<std::size_t>(2 * k)], o + glm::vec3(0, 0, 0),
                      o + glm::vec3(1, 0, 0), o + glm::vec3(1, 1, 0));
        checkTriangle(scene.triangles[static_cast<std::size_t>(2 * k + 1)], o + glm::vec3(0, 0, 0),
                      o + glm::vec3(1, 1, 0), o + glm::vec3(0, 1, 0));
    }
    // No NORMAL: every vertex repeats the geometric normal.
    for (const auto& t : scene.triangles) checkNormals(t, {0, 0, 1});
}

TEST_CASE("gltf: bufferView byteOffset/byteStride and accessor byteOffset") {
    const Scene scene = loadFeature("stride.gltf");
    REQUIRE(scene.triangles.size() == 1);
    checkTriangle(scene.triangles[0], {0, 0, 0}, {2, 0, 0}, {0, 3, 0});
    const float s = std::sqrt(0.5f);
    checkNormals(scene.triangles[0], {0, 0, 1}, {0, s, s}, {s, 0, s});
}

TEST_CASE("gltf: binary .glb, also when named .gltf") {
    for (const char* name : {"binary.glb", "binary-named-gltf.gltf"}) {
        CAPTURE(name);
        const Scene scene = loadFeature(name, LoadOptions{});
        REQUIRE(scene.triangles.size() == 1);
        checkTriangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
        checkNormals(scene.triangles[0], {0, 0, 1});
        REQUIRE(scene.materials.size() == 1);
        CHECK_VEC(scene.materials[0].emission(), glm::vec3(2.0f, 1.0f, 0.5f));
        CHECK(strata::isEmitter(scene, scene.triangles[0]));
        REQUIRE(scene.cameras.size() == 1);
        CHECK_VEC(scene.cameras[0].position, glm::vec3(0.25f, 0.25f, 4.0f));
        CHECK_VEC(scene.cameras[0].forward, glm::vec3(0, 0, -1));
        CHECK_VEC(scene.cameras[0].up, glm::vec3(0, 1, 0));
        CHECK(scene.cameras[0].yfov == doctest::Approx(0.6f));
        CHECK(scene.extensionsUsed == std::vector<std::string>{"KHR_materials_emissive_strength"});
        CHECK(scene.droppedEmitters == 0);
    }
}

TEST_CASE("gltf: cameras in node order with world transforms") {
    const Scene scene = loadFeature("cameras.gltf");
    REQUIRE(scene.cameras.size() == 2);
    // Camera index 1 sits on the first node reached depth-first:
    // Rig T(0,0,5) S(3) * FirstCam T(1,0,0) R_y(90).
    const auto& first = scene.cameras[0];
    CHECK(first.name == "First");
    CHECK_VEC(first.position, glm::vec3(3, 0, 5));
    CHECK_VEC(first.forward, glm::vec3(-1, 0, 0));
    CHECK_VEC(first.up, glm::vec3(0, 1, 0));
    CHECK(first.yfov == doctest::Approx(0.7f));
    // Matrix T(0,10,0) R_x(-90) S(2,1,0.5): the scale does not leak into
    // the unit vectors.
    const auto& second = scene.cameras[1];
    CHECK(second.name == "Second");
    CHECK_VEC(second.position, glm::vec3(0, 10, 0));
    CHECK_VEC(second.forward, glm::vec3(0, -1, 0));
    CHECK_VEC(second.up, glm::vec3(0, 0, -1));
    CHECK(second.yfov == doctest::Approx(0.5f));
}

TEST_CASE("gltf: material factors, emissive strength, ior, default material") {
    const Scene scene = loadFeature("materials.gltf");
    REQUIRE(scene.materials.size() == 3);
    REQUIRE(scene.triangles.size() == 3);
    CHECK(scene.triangles[0].material == 0);
    CHECK(scene.triangles[1].material == 1);
    CHECK(scene.triangles[2].material == 2);

    const MaterialDesc& full = scene.materials[0];
    CHECK(full.name == "Full");
    CHECK(glm::distance(full.baseColor, glm::vec4(0.1f, 0.2f, 0.3f, 0.4f)) < 1e-6f);
    CHECK(full.metallic == doctest::Approx(0.25f));
    CHECK(full.roughness == doctest::Approx(0.75f));
    CHECK_VEC(full.emissiveFactor, glm::vec3(0.5f, 0.25f, 1.0f));
    CHECK(full.emissiveStrength == doctest::Approx(4.0f));
    CHECK_VEC(full.emission(), glm::vec3(2.0f, 1.0f, 4.0f));
    CHECK(full.ior == doctest::Approx(1.33f));
    CHECK(full.doubleSided);
    CHECK(full.alphaMode == MaterialDesc::AlphaMode::Mask);
    CHECK(full.alphaCutoff == doctest::Approx(0.3f));

    const MaterialDesc& blend = scene.materials[1];
    CHECK(blend.name == "Blend");
    CHECK(blend.alphaMode == MaterialDesc::AlphaMode::Blend);
    CHECK(blend.baseColor == glm::vec4(1.0f));
    CHECK(blend.metallic == 1.0f);
    CHECK(blend.roughness == 1.0f);

    // glTF defaults for the primitive without a material.
    const MaterialDesc& fallback = scene.materials[2];
    CHECK(fallback.name == "default");
    CHECK(fallback.baseColor == glm::vec4(1.0f));
    CHECK(fallback.metallic == 1.0f);
    CHECK(fallback.roughness == 1.0f);
    CHECK(fallback.emission() == glm::vec3(0.0f));
    CHECK(fallback.ior == 1.5f);
    CHECK_FALSE(fallback.doubleSided);
    CHECK(fallback.alphaMode == MaterialDesc::AlphaMode::Opaque);
    CHECK(fallback.alphaCutoff == 0.5f);

    CHECK(strata::isEmitter(scene, scene.triangles[0]));
    CHECK_FALSE(strata::isEmitter(scene, scene.triangles[1]));
}

TEST_CASE("gltf: an unsupported used extension warns once and still loads") {
    const std::string path = dataPath("features/unknown-extension.gltf");
    CerrCapture capture;
    const Scene scene = strata::loadGltf(path);
    const std::string text = capture.text();
    REQUIRE(!text.empty());
    CHECK(text.back() == '\n');
    const std::string line = text.substr(0, text.size() - 1);
    CHECK(isOneLine(line));
    CHECK(line.rfind(path + ": warning: ", 0) == 0);
    CHECK(line.find("EXT_strata_test_unknown, EXT_lights_image_based") != std::string::npos);
    CHECK(line.find("KHR_materials_emissive_strength") == std::string::npos);
    REQUIRE(scene.triangles.size() == 1);
    CHECK_VEC(scene.materials[0].emission(), glm::vec3(3.0f));
    CHECK(scene.extensionsUsed.size() == 3);
}

TEST_CASE("gltf: a zero-area emissive triangle is kept, counted, and warned about") {
    const std::string path = dataPath("broken/zero-area-emitter.gltf");
    CerrCapture capture;
    const Scene scene = strata::loadGltf(path);
    const std::string text = capture.text();
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);
    CHECK(text.rfind(path + ": warning: 1 emissive triangle", 0) == 0);
    REQUIRE(scene.triangles.size() == 5);  // floor 2, light 2, sliver 1
    CHECK(scene.droppedEmitters == 1);
    CHECK(strata::isEmitter(scene, scene.triangles[2]));
    CHECK(strata::isEmitter(scene, scene.triangles[3]));
    CHECK_FALSE(strata::isEmitter(scene, scene.triangles[4]));
    CHECK(strata::isEmissive(scene.materials[scene.triangles[4].material]));
}

// A file with no camera and nothing that emits loads: the default view is
// the renderer's (scene/view.h), the light a white environment of radiance 1.
TEST_CASE("gltf: a file without a camera or a light gets the default white environment and one warning") {
    const std::string path = dataPath("lights/bare-sphere.gltf");
    CerrCapture capture;
    const Scene scene = strata::loadGltf(path);
    CHECK(scene.cameras.empty());
    CHECK(scene.lights.empty());
    CHECK(scene.environment.enabled);
    CHECK(scene.environment.source == strata::kDefaultEnvironment);
    CHECK(scene.environment.scale == glm::vec3(1.0f));
    CHECK(scene.environment.rotation == 0.0f);
    CHECK(scene.environment.rgb.empty());
    CHECK(capture.text() == path + ": warning: no light: lighting the scene with a uniform white environment of "
                                   "radiance 1; --env or --env-color sets another\n");
}

TEST_CASE("gltf: without the default light an unlit file is the no-light error, and an external light needs none") {
    const std::string path = dataPath("lights/bare-sphere.gltf");
    LoadOptions strict;
    strict.defaultLight = false;
    CHECK_THROWS_WITH_AS(strata::loadGltf(path, strict),
                         (path + ": error: no light: no triangle has an emissive material (emissiveFactor * "
                                 "emissiveStrength > 0) and a non-zero area, no node has a KHR_lights_punctual "
                                 "light, and no --env is given").c_str(),
                         strata::Error);
    LoadOptions external;
    external.externalLight = true;
    CerrCapture capture;
    CHECK_FALSE(strata::loadGltf(path, external).environment.enabled);
    CHECK(capture.text().empty());
    CHECK(strata::loadGltf(path, kNoRequirements).triangles.size() == 1280);
}

TEST_CASE("gltf: every broken file fails with one line naming file and problem") {
    struct Case {
        const char* file;
        const char* phrase;
    };
    const Case cases[] = {
        {"truncated-json.gltf", "invalid glTF: "},
        {"truncated.glb", "truncated GLB"},
        {"not-binary.glb", "'glTF' magic"},
        {"missing-bin.gltf", "uri \"missing-bin.bin\""},
        {"accessor-out-of-range.gltf",
         "accessor 0 (mesh 0 (\"Floor\") primitive 0 POSITION) is out of range of bufferView 0"},
        {"index-out-of-range.gltf", "mesh 1 (\"Light\") primitive 0: index 7 "},
        {"nan-position.gltf",
         "accessor 4 (mesh 2 (\"Bad\") primitive 0 POSITION): vertex 1 has a NaN"},
        {"attribute-not-an-index.gltf", "invalid glTF: 'attributes' value is not an integer type."},
        {"unsupported-required-extension.gltf",
         "unsupported required extension(s): EXT_lights_image_based"},
        {"zero-area-only-emitter.gltf", "no light: "},
        {"lines-mode.gltf",
         "no triangles to render: skipped 1 primitive(s) that are not triangles: mesh 0 (\"Cube\") "
         "primitive 0 (LINES)"},
        {"orthographic-camera.gltf", "camera 0 (\"Ortho\") is orthographic"},
        {"no-scenes.gltf", "no scenes"},
        {"node-two-parents.gltf",
         "node 1 (\"Light\") is reached twice from scene 0 (a node may have one parent, and a root none)"},
        {"empty.gltf", "empty file"},
        {"buffer-uri-directory.gltf", "unreadable file: uri \".\" refers to "},
        {"buffer-uri-empty.gltf", "unreadable file: uri \"empty.gltf\" refers to "},
        {"not-json.gltf", "not a glTF file: neither a JSON object"},
        {"does-not-exist.gltf", "cannot open file: "},
    };
    for (const Case& c : cases) {
        const std::string path = dataPath(std::string("broken/") + c.file);
        CAPTURE(path);
        const std::string message = loadError(path);
        CAPTURE(message);
        REQUIRE_MESSAGE(!message.empty(), "loaded without an error");
        CHECK(isOneLine(message));
        CHECK(message.rfind(path + ": error: ", 0) == 0);
        CHECK(message.find(c.phrase) != std::string::npos);
    }
}

TEST_CASE("gltf: the zero-area-only emitter error counts the zero-area triangles") {
    const std::string path = dataPath("broken/zero-area-only-emitter.gltf");
    CHECK_THROWS_WITH_AS(strata::loadGltf(path),
                         (path + ": error: no light: no triangle has an emissive material "
                                 "(emissiveFactor * emissiveStrength > 0) and a non-zero area, no node has a "
                                 "KHR_lights_punctual light, and no --env is given; 2 emissive triangle(s) have zero area")
                             .c_str(),
                         strata::Error);
}

TEST_CASE("gltf: a directory is not a glTF file") {
    const std::string path = dataPath("broken");
    CHECK_THROWS_WITH_AS(strata::loadGltf(path),
                         (path + ": error: cannot read file: is a directory").c_str(),
                         strata::Error);
}

TEST_CASE("warn: one line on stderr") {
    CerrCapture capture;
    strata::warn("a.gltf", "first\nsecond");
    CHECK(capture.text() == "a.gltf: warning: first second\n");
}

TEST_CASE("scenes: shipped scenes load") {
    const std::string root = std::string(STRATA_SOURCE_DIR) + "/scenes/";
    SUBCASE("cornell-box") {
        CerrCapture capture;
        const Scene scene = strata::loadGltf(root + "cornell-box.gltf");
        CHECK(capture.text().empty());
        CHECK(scene.triangles.size() == 32);
        REQUIRE(scene.cameras.size() == 1);
        CHECK_VEC(scene.cameras[0].position, glm::vec3(0.0f, 1.0f, 3.8f));
        CHECK_VEC(scene.cameras[0].forward, glm::vec3(0.0f, 0.0f, -1.0f));
        CHECK(scene.cameras[0].yfov ==
              doctest::Approx(40.0 * std::numbers::pi / 180.0).epsilon(1e-4));
        std::size_t emitters = 0;
        for (const auto& t : scene.triangles) {
            if (!strata::isEmitter(scene, t)) continue;
            ++emitters;
            checkNormals(t, {0, -1, 0});  // the light faces down
            CHECK_VEC(scene.materials[t.material].emission(), glm::vec3(15.0f));
        }
        CHECK(emitters == 2);
        for (const auto& t : scene.triangles) checkFrontFaceMatchesNormals(t);
        // Walls, floor and ceiling face the inside of the room.
        const glm::vec3 centre(0.0f, 1.0f, 0.0f);
        for (const auto& t : scene.triangles) {
            const glm::vec3 c = (t.v[0] + t.v[1] + t.v[2]) / 3.0f;
            const bool wall = std::abs(c.x) > 0.99f || c.y < 0.01f || c.y > 1.99f || c.z < -0.99f;
            if (wall) CHECK(glm::dot(t.n[0], centre - c) > 0.0f);
        }
    }
    SUBCASE("furnace") {
        const Scene scene = strata::loadGltf(root + "furnace.gltf");
        REQUIRE(scene.triangles.size() == 12);
        REQUIRE(scene.cameras.size() == 1);
        CHECK_VEC(scene.cameras[0].position, glm::vec3(0.0f));
        for (const auto& t : scene.triangles) {
            CHECK(strata::isEmitter(scene, t));
            const glm::vec3 c = (t.v[0] + t.v[1] + t.v[2]) / 3.0f;
            CHECK(glm::dot(t.n[0], -c) > 0.0f);  // front faces point inward
            checkFrontFaceMatchesNormals(t);
        }
        const MaterialDesc& m = scene.materials[scene.triangles[0].material];
        CHECK_VEC(glm::vec3(m.baseColor), glm::vec3(0.5f));
        CHECK_VEC(m.emission(), glm::vec3(0.5f));
    }
}

TEST_SUITE_END();
