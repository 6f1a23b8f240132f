// glTF loader geometry: TRIANGLE_STRIP and TRIANGLE_FAN against hand-written
// triangles, point and line primitives skipped with one warning, sparse
// accessors, KHR_mesh_quantization against the spec's int-to-float formulas,
// and one error line for each file of tests/data/geometry/broken. Data:
// tests/data/make_geometry.py (the numbers there are mirrored here).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_util.h"
#include "gltf_util.h"
#include "pack/textures.h"
#include "test_util.h"
#include "scene/scene.h"
#include "util/error.h"

TEST_SUITE_BEGIN("unit");

namespace {

using strata::LoadOptions;
using strata::Scene;
using strata::Triangle;
using namespace strata::test;

const LoadOptions kNoRequirements{false, false};

Scene loadGeometry(const std::string& name) {
    return strata::loadGltf(dataPath("geometry/" + name), kNoRequirements);
}

struct Expected {
    glm::vec3 v0, v1, v2;
};

// The triangles in order, each front face (counter-clockwise) +Z, with the
// geometric normal at every vertex (the files have no NORMAL).
void checkFlatTriangles(const Scene& scene, const std::vector<Expected>& expected) {
    REQUIRE(scene.triangles.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        CAPTURE(i);
        const Triangle& t = scene.triangles[i];
        checkTriangle(t, expected[i].v0, expected[i].v1, expected[i].v2);
        CHECK(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]).z > 0.0f);
        checkNormals(t, {0, 0, 1});
    }
}

std::vector<Expected> movedBy(std::vector<Expected> list, glm::vec3 by) {
    for (Expected& e : list) e = {e.v0 + by, e.v1 + by, e.v2 + by};
    return list;
}

std::vector<Expected> concat(std::vector<Expected> a, const std::vector<Expected>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// Exact equality: the decoded values are the spec's formulas evaluated in float.
#define CHECK_EXACT(actual, expected)                                                            \
    CHECK_MESSAGE(glm::vec3(actual) == glm::vec3(expected), str(glm::vec3(actual)), " != ", \
                  str(glm::vec3(expected)))

}  // namespace

TEST_CASE("gltf geometry: TRIANGLE_STRIP gives the spec's triangles, indexed and not") {
    // glTF 2.0 3.7.2.1: triangle i is (v_i, v_i+1, v_i+2) for even i and
    // (v_i, v_i+2, v_i+1) for odd i, so every triangle keeps the strip's
    // front face. Vertices (0,1) (0,0) (1,1) (1,0) (2,1) (2,0).
    const std::vector<Expected> strip = {
        {{0, 1, 0}, {0, 0, 0}, {1, 1, 0}},
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
        {{1, 1, 0}, {1, 0, 0}, {2, 1, 0}},
        {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}},
    };
    // The indexed copy (moved by (0, 3, 0)) gives the same triangles; its
    // last index repeats a vertex, and that degenerate triangle is dropped.
    checkFlatTriangles(loadGeometry("strip.gltf"), concat(strip, movedBy(strip, {0, 3, 0})));
}

TEST_CASE("gltf geometry: TRIANGLE_FAN gives the spec's triangles, indexed and not") {
    // Triangle i is (v_i+1, v_i+2, v_0); v_0 = (0,0), then (1,0) (1,1) (0,1) (-1,1).
    const std::vector<Expected> fan = {
        {{1, 0, 0}, {1, 1, 0}, {0, 0, 0}},
        {{1, 1, 0}, {0, 1, 0}, {0, 0, 0}},
        {{0, 1, 0}, {-1, 1, 0}, {0, 0, 0}},
    };
    checkFlatTriangles(loadGeometry("fan.gltf"), concat(fan, movedBy(fan, {0, 3, 0})));
}

TEST_CASE("gltf geometry: point and line primitives are skipped with one warning") {
    const std::string path = dataPath("geometry/lines-and-triangles.gltf");
    CerrCapture capture;
    const Scene scene = strata::loadGltf(path);
    CHECK(capture.text() ==
          path + ": warning: skipped 4 primitive(s) that are not triangles: mesh 1 (\"Wire\") "
                 "primitive 0 (LINES), mesh 1 (\"Wire\") primitive 2 (POINTS), mesh 2 (\"Loop\") "
                 "primitive 0 (LINE_LOOP) and 1 more\n");
    // "Tri", then "Wire" primitive 1 on its two nodes (the second moved by x + 3).
    checkFlatTriangles(scene, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                               {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                               {{3, 0, 1}, {4, 0, 1}, {3, 1, 1}}});
}

TEST_CASE("gltf geometry: a scene of lines only is one error line") {
    const std::string path = dataPath("broken/lines-mode.gltf");
    CerrCapture capture;
    CHECK_THROWS_WITH_AS(strata::loadGltf(path, kNoRequirements),
                         (path + ": error: no triangles to render: skipped 1 primitive(s) that are "
                                 "not triangles: mesh 0 (\"Cube\") primitive 0 (LINES)")
                             .c_str(),
                         strata::Error);
    CHECK(capture.text().empty());
}

TEST_CASE("gltf geometry: sparse positions, normals and indices, with and without a bufferView") {
    const Scene scene = loadGeometry("sparse.gltf");
    REQUIRE(scene.triangles.size() == 6);
    // "Base": the quad (0,0) (1,0) (1,1) (0,1) with vertices 1 and 3 replaced
    // by (2,0,0) and (0,3,0); the normal of vertex 2 replaced by (0,1,1).
    const float s = std::sqrt(0.5f);
    checkTriangle(scene.triangles[0], {0, 0, 0}, {2, 0, 0}, {1, 1, 0});
    checkNormals(scene.triangles[0], {0, 0, 1}, {0, 0, 1}, {0, s, s});
    checkTriangle(scene.triangles[1], {0, 0, 0}, {1, 1, 0}, {0, 3, 0});
    checkNormals(scene.triangles[1], {0, 0, 1}, {0, s, s}, {0, 0, 1});
    // "Zeros": no bufferView, so vertex 0 stays (0,0,0); node moved by x + 5.
    checkTriangle(scene.triangles[2], {5, 0, 0}, {6, 0, 0}, {5, 1, 0});
    // "Indices": 0 1 2 0 1 2 with indices 4 and 5 replaced by 2 and 3.
    checkTriangle(scene.triangles[3], {10, 0, 0}, {11, 0, 0}, {11, 1, 0});
    checkTriangle(scene.triangles[4], {10, 0, 0}, {11, 1, 0}, {10, 1, 0});
    // "IndexZeros": indices without bufferView (tinygltf 2.7 refuses them;
    // gltf_compressed.cpp hides them from it): 0 0 0 with 1 and 2 substituted.
    checkTriangle(scene.triangles[5], {15, 0, 0}, {16, 0, 0}, {16, 1, 0});
}

TEST_CASE("gltf geometry: an accessor without a bufferView may have max(2^20, buffer bytes) elements") {
    // zeros-limit.gltf: 2^20 zero positions (its buffers hold 38 bytes), two
    // of them replaced; one indexed triangle. One more element is
    // broken/sparse-zeros-count.gltf's error.
    const Scene scene = loadGeometry("zeros-limit.gltf");
    REQUIRE(scene.triangles.size() == 1);
    checkTriangle(scene.triangles[0], {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
}

TEST_CASE("gltf geometry: quantized POSITION by the spec's formulas, the node dequantizes") {
    const Scene scene = loadGeometry("quantized-positions.gltf");
    REQUIRE(scene.triangles.size() == 9);
    struct Case {
        const char* what;
        glm::vec3 v0, v1, v2;
    };
    // KHR_mesh_quantization: normalized BYTE max(c / 127, -1), UNSIGNED_BYTE
    // c / 255, SHORT max(c / 32767, -1), UNSIGNED_SHORT c / 65535; not
    // normalized: the integer.
    const Case cases[] = {
        {"BYTE", {-128, 0, 0}, {127, 0, -127}, {0, 64, 1}},
        {"BYTE normalized", {-1, 0, 0}, {1, 0, -1}, {0, 64.0f / 127.0f, 1.0f / 127.0f}},
        {"UNSIGNED_BYTE", {0, 0, 0}, {255, 0, 0}, {0, 128, 1}},
        {"UNSIGNED_BYTE normalized", {0, 0, 0}, {1, 0, 0}, {0, 128.0f / 255.0f, 1.0f / 255.0f}},
        {"SHORT", {-32768, 0, 0}, {32767, 0, -32767}, {0, 16384, 1}},
        {"SHORT normalized", {-1, 0, 0}, {1, 0, -1}, {0, 16384.0f / 32767.0f, 1.0f / 32767.0f}},
        {"UNSIGNED_SHORT", {0, 0, 0}, {65535, 0, 0}, {0, 32768, 1}},
        {"UNSIGNED_SHORT normalized", {0, 0, 0}, {1, 0, 0},
         {0, 32768.0f / 65535.0f, 1.0f / 65535.0f}},
        // The UNSIGNED_SHORT mesh again on a node scaled by 0.5, moved by (1, 2, 3).
        {"dequantized", {1, 2, 3}, {32768.5f, 2, 3}, {1, 16386, 3.5f}},
    };
    for (std::size_t i = 0; i < std::size(cases); ++i) {
        CAPTURE(cases[i].what);
        const Triangle& t = scene.triangles[i];
        CHECK_EXACT(t.v[0], cases[i].v0);
        CHECK_EXACT(t.v[1], cases[i].v1);
        CHECK_EXACT(t.v[2], cases[i].v2);
    }
}

TEST_CASE("gltf geometry: quantized TEXCOORD_0 by the spec's formulas") {
    const Scene scene = loadGeometry("quantized-texcoords.gltf");
    REQUIRE(scene.triangles.size() == 8);
    REQUIRE(scene.texcoords.size() == 8);
    struct Case {
        const char* what;
        glm::vec2 uv[3];
    };
    const Case cases[] = {
        {"BYTE", {{-128, 127}, {0, 64}, {-1, 1}}},
        {"BYTE normalized", {{-1, 1}, {0, 64.0f / 127.0f}, {-1.0f / 127.0f, 1.0f / 127.0f}}},
        {"UNSIGNED_BYTE", {{0, 255}, {128, 1}, {255, 0}}},
        {"UNSIGNED_BYTE normalized", {{0, 1}, {128.0f / 255.0f, 1.0f / 255.0f}, {1, 0}}},
        {"SHORT", {{-32768, 32767}, {16384, 0}, {-1, 1}}},
        {"SHORT normalized", {{-1, 1}, {16384.0f / 32767.0f, 0}, {-1.0f / 32767.0f, 1.0f / 32767.0f}}},
        {"UNSIGNED_SHORT", {{0, 65535}, {32768, 1}, {65535, 0}}},
        {"UNSIGNED_SHORT normalized", {{0, 1}, {32768.0f / 65535.0f, 1.0f / 65535.0f}, {1, 0}}},
    };
    for (std::size_t i = 0; i < std::size(cases); ++i) {
        CAPTURE(cases[i].what);
        for (int k = 0; k < 3; ++k) {
            const glm::vec4 uv = scene.texcoords[i][static_cast<std::size_t>(k)];
            CHECK_EXACT(glm::vec3(uv.x, uv.y, 0), glm::vec3(cases[i].uv[k], 0));
        }
    }
}

TEST_CASE("gltf geometry: quantized NORMAL and TANGENT, normalized BYTE and SHORT") {
    const Scene scene = loadGeometry("quantized-normals.gltf");
    REQUIRE(scene.triangles.size() == 2);
    REQUIRE(scene.tangents.size() == 2);
    // xyz (-128, 0, 127) and (-32768, 0, 32767) decode to (-1, 0, 1): the
    // spec's max(c / 127, -1) clamps; c / 127 alone would tilt the normal.
    const float s = std::sqrt(0.5f);
    for (std::size_t i = 0; i < 2; ++i) {
        CAPTURE(i);
        checkNormals(scene.triangles[i], {-s, 0, s}, {0, 0, 1}, {s, 0, s});
        const auto& tangents = scene.tangents[i];
        CHECK_VEC(glm::vec3(tangents[0]), glm::vec3(-s, 0, s));
        CHECK_VEC(glm::vec3(tangents[1]), glm::vec3(0, 0, 1));
        CHECK_VEC(glm::vec3(tangents[2]), glm::vec3(s, 0, s));
        CHECK(tangents[0].w == 1.0f);
        CHECK(tangents[1].w == -1.0f);
        CHECK(tangents[2].w == 1.0f);
    }
}

TEST_CASE("gltf geometry: TEXCOORD_n for any n, the two sets a material reads in the uv slots") {
    const Scene scene = loadGeometry("texcoord-sets.gltf");
    REQUIRE(scene.triangles.size() == 3);
    REQUIRE(scene.texcoords.size() == 3);
    // Materials: 0 "Glow", 1 "Sets23" (baseColor reads 3, emissive 2), 2
    // "Set3" (both 3), 3 "Sets01" (baseColor 1, emissive 0).
    using Sets = std::array<int, 2>;
    const Sets sets[3] = {{2, 3}, {3, 3}, {0, 1}};
    for (std::size_t t = 0; t < 3; ++t) {
        CAPTURE(t);
        const strata::MaterialDesc& m = scene.materials[t + 1];
        CHECK(m.uvSets == sets[t]);
        // Set n of vertex k is (n + k / 4, 10 n + k / 8) (make_geometry.py).
        for (int k = 0; k < 3; ++k) {
            const glm::vec4 uv = scene.texcoords[t][static_cast<std::size_t>(k)];
            const auto a = static_cast<float>(sets[t][0]), b = static_cast<float>(sets[t][1]);
            const glm::vec4 expected(a + k / 4.0f, 10 * a + k / 8.0f, b + k / 4.0f, 10 * b + k / 8.0f);
            CHECK_MESSAGE(uv == expected, k);
        }
    }
    // Packed, each slot reads uv.xy or uv.zw (kTexCoord1) by its set's place.
    const std::vector<bool> used = {false, true, true, true, false};
    std::vector<strata::gpu::Material> materials(scene.materials.size());
    const strata::PackedTextures packed = strata::packTextures(scene, used, materials);
    auto second = [&](std::uint32_t ref) { return (packed.refs[ref].flags & strata::gpu::kTexCoord1) != 0; };
    CHECK(second(materials[1].baseColorTex));
    CHECK_FALSE(second(materials[1].emissiveTex));
    CHECK_FALSE(second(materials[2].baseColorTex));
    CHECK_FALSE(second(materials[2].emissiveTex));
    CHECK(second(materials[3].baseColorTex));
    CHECK_FALSE(second(materials[3].emissiveTex));
}

TEST_CASE("gltf geometry: every broken file fails with one line naming file and problem") {
    const std::string position = "accessor 0 (mesh 0 (\"Bad\") primitive 0 POSITION)";
    const std::string sparse = position + ": sparse";
    const std::string bad = "mesh 0 (\"Bad\") primitive 0: ";
    const std::string undeclared =
        " (KHR_mesh_quantization allows it, but the file does not declare that extension)";
    // The file and its message after "PATH: error: ".
    const std::pair<const char*, std::string> cases[] = {
        {"sparse-index-out-of-range.gltf",
         sparse + " index 3 (sparse.indices[1]) is out of range: the accessor has 3 elements"},
        {"sparse-not-increasing.gltf",
         sparse + " index 1 (sparse.indices[1]) is not greater than the previous one, 1; sparse "
                  "indices must be strictly increasing"},
        {"sparse-count.gltf", sparse + ".count 4 is not in [1, 3] (the accessor's count)"},
        {"sparse-indices-out-of-view.gltf",
         sparse + ".indices is out of range of bufferView 0: byteOffset 1 + byteStride 1 * (count "
                  "2 - 1) + element size 1 = 3 > byteLength 2"},
        {"sparse-values-out-of-view.gltf",
         sparse + ".values is out of range of bufferView 1: byteOffset 0 + byteStride 12 * (count "
                  "2 - 1) + element size 12 = 24 > byteLength 12"},
        {"sparse-index-type.gltf",
         sparse + ".indices componentType 5126 (FLOAT) is not "
                  "UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT"},
        {"sparse-missing-view.gltf",
         sparse + ".values refers to bufferView 99, which does not exist (3 bufferViews)"},
        {"sparse-negative-offset.gltf", sparse + ".indices byteOffset -4 is negative"},
        {"no-bufferview-count.gltf",
         position + " has no bufferView and count 4294967296, more than the file can justify: at "
                    "most max(1048576, the 0 bytes of its buffers) = 1048576 elements"},
        {"sparse-zeros-count.gltf",
         position + " has no bufferView and count 1048577, more than the file can justify: at "
                    "most max(1048576, the 32 bytes of its buffers) = 1048576 elements"},
        {"quantized-undeclared.gltf", position + " is SHORT VEC3; expected FLOAT VEC3" + undeclared},
        {"quantized-position-vec2.gltf",
         position + " is SHORT VEC2; expected FLOAT/BYTE/UNSIGNED_BYTE/SHORT/UNSIGNED_SHORT VEC3"},
        {"quantized-normal-ubyte.gltf",
         "accessor 1 (mesh 0 (\"Bad\") primitive 0 NORMAL) is UNSIGNED_BYTE VEC3; expected "
         "FLOAT/BYTE/SHORT VEC3, integers normalized"},
        {"quantized-normal-unnormalized.gltf",
         "accessor 1 (mesh 0 (\"Bad\") primitive 0 NORMAL) is BYTE but not normalized"},
        {"quantized-texcoord-undeclared.gltf",
         "accessor 1 (mesh 0 (\"Bad\") primitive 0 TEXCOORD_0) is UNSIGNED_BYTE but not normalized" +
             undeclared},
        {"strip-too-short.gltf", bad + "index count 2 of a TRIANGLE_STRIP primitive is less than 3"},
        {"fan-index-out-of-range.gltf",
         bad + "index 9 (indices[3], accessor 1) is out of range: POSITION has 3 vertices"},
        {"unknown-mode.gltf", bad + "mode 7 is not a glTF primitive mode (0 to 6)"},
        {"color-unnormalized.gltf",
         "accessor 1 (mesh 0 (\"Bad\") primitive 0 COLOR_0) is UNSIGNED_BYTE but not normalized"},
        {"color-vec2.gltf", "accessor 1 (mesh 0 (\"Bad\") primitive 0 COLOR_0) is neither VEC3 nor VEC4"},
        {"color-count.gltf", bad + "COLOR_0 has 2 elements but POSITION has 3"},
        {"variants-bad-material.gltf",
         "mesh 0 (\"A\") primitive 0 KHR_materials_variants mapping 0: material 9 does not exist (4 materials)"},
        {"variants-bad-index.gltf",
         "mesh 0 (\"A\") primitive 0 KHR_materials_variants mapping 0: variant 5 does not exist (3 variants)"},
        {"basisu-required.gltf",
         "required extension KHR_texture_basisu cannot be read: strata was built without a Basis Universal decoder "
         "(Debian has none)"},
        {"basisu-no-fallback.gltf",
         "material 1 (\"Textured\") emissiveTexture: texture 0: its image is KHR_texture_basisu, which strata cannot "
         "decode (Debian has no Basis Universal decoder), and it has no fallback source"},
        {"texcoord-three-sets.gltf",
         "material 1 (\"Textured\"): its textures read 3 texture coordinate sets (TEXCOORD_0, TEXCOORD_2, "
         "TEXCOORD_3); strata interpolates at most two per material"},
        {"texcoord-negative.gltf",
         "material 1 (\"Textured\") emissiveTexture: texCoord -1 is not a TEXCOORD set (>= 0)"},
        {"texcoord-missing-set.gltf",
         bad + "material 1 emissiveTexture reads TEXCOORD_2, which the primitive does not have"},
    };
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dataPath("geometry/broken"))) {
        files += entry.path().extension() == ".gltf";
    }
    CHECK(files == std::size(cases));  // every file in the folder has its case
    for (const auto& [file, expected] : cases) {
        const std::string path = dataPath(std::string("geometry/broken/") + file);
        CAPTURE(path);
        const std::string message = loadError(path);
        REQUIRE_MESSAGE(!message.empty(), "loaded without an error");
        CHECK(isOneLine(message));
        CHECK(message == path + ": error: " + expected);
    }
}

TEST_CASE("gltf geometry: strata render on each broken file exits 2, one line, no output") {
    std::size_t checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dataPath("geometry/broken"))) {
        checkRenderRefuses(entry.path().string());
        ++checked;
    }
    CHECK(checked >= 28);
}

TEST_CASE("gltf geometry: a texture read through TEXCOORD_2 renders as its TEXCOORD_0 twin, bit for bit" *
          doctest::test_suite("render")) {
    strata::RenderSettings s;
    s.width = 16;
    s.height = 16;
    s.spp = 2;
    const strata::Scene twin = loadGeometry("texcoord-0.gltf");
    const strata::RenderResult reference = renderScene(twin, s);
    CHECK(imageMean(reference.film).mean > 0.0);
    CHECK(sameImage(renderScene(loadGeometry("texcoord-2.gltf"), s).film, reference.film));
    CHECK(strata::vk::validationMessageCount() == 0);
}

TEST_CASE("gltf geometry: lines next to triangles render, with the one warning" *
          doctest::test_suite("render")) {
    const std::string file = dataPath("geometry/lines-and-triangles.gltf");
    TempDir out;
    const Run r = run("render " + file + " -o " + out / "a.exr" +
                      " --spp 1 --width 8 --height 8 --quiet");
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.rfind(file + ": warning: skipped 4 primitive(s) that are not triangles: ", 0) == 0);
    CHECK(std::filesystem::exists(out.path / "a.exr"));
}

TEST_SUITE_END();
