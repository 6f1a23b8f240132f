// Morph targets and skins at load (glTF 2.0 3.7.2.2, 3.7.3): each posed mesh
// against the same mesh authored already posed, vertex for vertex, and the
// broken files of tests/data/deform/broken for their errors. Data:
// tests/data/make_deform.py (morph, skin).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_util.h"
#include "gltf_util.h"
#include "scene/scene.h"

TEST_SUITE_BEGIN("unit");

namespace {

using namespace strata;
using namespace strata::test;

const LoadOptions kNoRequirements{false, false};

Scene loadDeform(const std::string& name) { return loadGltf(dataPath("deform/" + name), kNoRequirements); }

// Triangles [first, first + count) of `scene` against [twin, twin + count),
// moved by `offset`: vertices, unit normals and tangents (when kept) equal to
// float rounding.
void checkSamePose(const Scene& scene, std::size_t first, std::size_t twin, std::size_t count, glm::vec3 offset) {
    for (std::size_t i = 0; i < count; ++i) {
        CAPTURE(i);
        const Triangle &a = scene.triangles[first + i], &b = scene.triangles[twin + i];
        checkTriangle(a, b.v[0] - offset, b.v[1] - offset, b.v[2] - offset);
        checkNormals(a, b.n[0], b.n[1], b.n[2]);
        if (scene.tangents.empty()) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            CHECK_VEC(glm::vec3(scene.tangents[first + i][k]), glm::vec3(scene.tangents[twin + i][k]));
            CHECK(scene.tangents[first + i][k].w == scene.tangents[twin + i][k].w);
        }
    }
}

}  // namespace

TEST_CASE("morph targets: POSITION, NORMAL and TANGENT targets with the mesh's or the node's weights, sparse targets too") {
    // Nodes: the morphed quad with mesh.weights (0.5, 0.25), then at x + 3
    // with its own weights (1, -0.5); the quad authored posed by each at
    // x + 10 and x + 13. Two triangles each.
    const Scene scene = loadDeform("morph.gltf");
    REQUIRE(scene.triangles.size() == 8);
    REQUIRE(scene.tangents.size() == 8);
    checkSamePose(scene, 0, 4, 2, {10, 0, 0});
    checkSamePose(scene, 2, 6, 2, {10, 0, 0});
    // Target 1 (sparse, over zeros) moves vertex 2 by (1, 1, -1) x weight:
    // the own-weights node's vertex 2 is (1, 1, 0) + (0, -0.5, 1) - 0.5 (1, 1, -1) + (3, 0, 0).
    CHECK_VEC(scene.triangles[2].v[2], glm::vec3(3.5f, 0.0f, 1.5f));
}

TEST_CASE("skins: sum_i w_i (jointWorld_i inverseBind_i) v for positions, normals and tangents, the node's transform ignored") {
    // The bar on three joints (two JOINTS/WEIGHTS sets, float and normalized
    // u16 weights; its node under a parent, both with transforms that must
    // be ignored), then its twin authored posed at x + 10. Its last row's
    // weights sum to 0.98: renormalized, with one warning.
    CerrCapture capture;
    const Scene scene = loadDeform("skin.gltf");
    REQUIRE(scene.triangles.size() == 12);
    REQUIRE(scene.tangents.size() == 12);
    checkSamePose(scene, 0, 6, 6, {10, 0, 0});
    CHECK(capture.text().find("node 5 (\"Skinned\") with skin 0 (\"Legs\"), primitive 0: 2 vertices have joint "
                              "weights whose sum is off 1 by more than 2e-7 per weight; renormalized") !=
          std::string::npos);
    // The hip turns by 20 degrees about the rig's origin (0.5, 0, 0): the bar's
    // foot vertex (-0.25, 0) of joint 0 alone goes to 0.5 + R(20) (-0.75, 0).
    const double c = std::cos(20.0 * 3.14159265358979 / 180.0), s = std::sin(20.0 * 3.14159265358979 / 180.0);
    CHECK_VEC(scene.triangles[0].v[0], glm::vec3(float(0.5 - 0.75 * c), float(-0.75 * s), 0.0f));
}

TEST_CASE("morph targets and skins: every broken file fails with one line naming the problem") {
    const std::string bad = "mesh 0 (\"Bad\")";
    const std::string bar = "mesh 0 (\"Bar\") primitive 0";
    const std::string skinned = "node 5 (\"Skinned\") with skin 0 (\"Legs\"), primitive 0: ";
    const std::pair<const char*, std::string> cases[] = {
        {"morph-weights-count.gltf", bad + " weights has 3 number(s) but the mesh has 2 morph target(s)"},
        {"morph-target-count.gltf", bad + " primitive 0 target 0 POSITION has 2 elements but POSITION has 3"},
        {"morph-primitives-differ.gltf",
         bad + ": primitive 1 has 2 morph target(s) but primitive 0 has 1; the primitives of a mesh have the same number"},
        {"skin-joint-range.gltf", skinned + "vertex 0 has joint index 5 (JOINTS_0), out of range: the skin has 3 joints"},
        {"skin-weights-type.gltf",
         "(" + bar + " WEIGHTS_0) is SHORT VEC4; expected FLOAT/UNSIGNED_BYTE/UNSIGNED_SHORT VEC4, integers normalized"},
        {"skin-negative-weight.gltf", bar + " WEIGHTS_0: vertex 0 has weight -0.5; weights are finite and not negative"},
        {"skin-missing-weights.gltf", skinned + "has no JOINTS_0 and WEIGHTS_0"},
        {"skin-joints-alone.gltf", bar + ": has JOINTS_1 without WEIGHTS_1"},
        {"skin-ibm-singular.gltf", "skin 0 (\"Legs\"): inverseBindMatrices[1] is not invertible (determinant 0)"},
        {"skin-ibm-count.gltf", "skin 0 (\"Legs\"): inverseBindMatrices has 2 matrices for 3 joints"},
    };
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dataPath("deform/broken"))) {
        files += entry.path().extension() == ".gltf";
        checkRenderRefuses(entry.path().string());
    }
    CHECK(files == std::size(cases));  // every file in the folder has its case
    for (const auto& [file, expected] : cases) {
        const std::string path = dataPath(std::string("deform/broken/") + file);
        CAPTURE(path);
        const std::string message = loadError(path);
        CHECK(isOneLine(message));
        CHECK(message.rfind(path + ": error: ", 0) == 0);
        CHECK(message.find(expected) != std::string::npos);
    }
}

TEST_SUITE_END();
