// Files glTF 2.0 calls valid that strata once refused (issue 45: running
// strata on Khronos' glTF-Validator test corpus), written by
// tests/data/make_validator.py: each loads, read as the spec says (a part
// skipped with one warning, a default used, a fallback taken); and
// KHR_node_visibility.
#include <doctest/doctest.h>

#include <string>

#include "gltf_util.h"
#include "scene/scene.h"

TEST_SUITE_BEGIN("unit");

namespace {

using namespace strata;
using namespace strata::test;

// Loads validator/NAME; `warning` is the one warning line expected after
// "PATH: warning: " (empty: none).
Scene loadChecked(const std::string& name, const std::string& warning, LoadOptions options = {}) {
    const std::string path = dataPath("validator/" + name);
    CAPTURE(path);
    CerrCapture capture;
    Scene scene = loadGltf(path, options);
    CHECK(capture.text() == (warning.empty() ? std::string() : path + ": warning: " + warning + "\n"));
    return scene;
}

// The file's triangle, (0,0,0) (1,0,0) (0,1,0), moved by `by`.
void checkTriangle(const Scene& scene, glm::vec3 by) {
    REQUIRE(scene.triangles.size() >= 1);
    CHECK_VEC(scene.triangles[0].v[0], by);
    CHECK_VEC(scene.triangles[0].v[1], by + glm::vec3(1, 0, 0));
    CHECK_VEC(scene.triangles[0].v[2], by + glm::vec3(0, 1, 0));
}

}  // namespace

TEST_CASE("validator corpus: a skin without inverseBindMatrices binds by identity") {
    checkTriangle(loadChecked("skin-without-inverse-bind.gltf", ""), glm::vec3(0));
}

TEST_CASE("validator corpus: an indices accessor without bufferView is zeros, in a file without compression") {
    const Scene scene = loadChecked("indices-without-view.gltf", "");
    checkTriangle(scene, glm::vec3(0));
}

TEST_CASE("validator corpus: a node matrix that is not affine is applied as affine with one warning") {
    checkTriangle(loadChecked("matrix-not-affine.gltf", "1 node matrix(es) with a last row other than (0, 0, 0, 1), "
                                                        "applied as affine (the row ignored; first: node 0 (\"Triangle\"))"),
                  glm::vec3(0));
}

TEST_CASE("validator corpus: primitives without POSITION or with a triangle count not a multiple of 3 are skipped") {
    const Scene scene = loadChecked("primitives-to-skip.gltf",
                                    "skipped 2 primitive(s) that glTF 2.0 says not to render: mesh 0 (\"Triangle\") "
                                    "primitive 1 (no POSITION), mesh 0 (\"Triangle\") primitive 2 (4 vertices without "
                                    "indices, not a multiple of 3)");
    CHECK(scene.triangles.size() == 1);
}

TEST_CASE("validator corpus: a texture without a source reads as absent") {
    const Scene scene = loadChecked("texture-without-source.gltf",
                                    "1 texture(s) without a source image: the materials read them as absent");
    REQUIRE(!scene.materials.empty());
    CHECK_FALSE(scene.materials[0].emissiveTexture.used());
}

TEST_CASE("validator corpus: an image no texture uses may be undecodable") {
    loadChecked("unused-undecodable-image.gltf",
                "1 image(s) not decoded, left unused (first: image 0: cannot decode 3 bytes: not a PNG or JPEG (the "
                "image formats of glTF 2.0), nor a WebP or AVIF image)");
}

TEST_CASE("validator corpus: KHR_animation_pointer moves a node through its pointer, other targets are ignored") {
    const std::string ignored = "KHR_animation_pointer: 1 channel(s) animating other than a node's transform or "
                                "weights ignored (first: /materials/0/emissiveFactor)";
    checkTriangle(loadChecked("animation-pointer.gltf", ignored), glm::vec3(0));
    LoadOptions at1;
    at1.motion.enabled = true;
    at1.motion.open = at1.motion.close = 1.0;  // the pose at t = 1: translated by (2, 0, 0)
    checkTriangle(loadChecked("animation-pointer.gltf", ignored, at1), glm::vec3(2, 0, 0));
}

TEST_CASE("KHR_node_visibility: a hidden node hides its subtree's meshes, not its camera") {
    const Scene scene = loadChecked("node-visibility.gltf", "");
    CHECK(scene.triangles.size() == 1);
    checkTriangle(scene, glm::vec3(0));
    REQUIRE(scene.cameras.size() == 1);  // under the hidden node
}

#if STRATA_WEBP
TEST_CASE("validator corpus: an image in a data: URI of a type tinygltf does not list (WebP) is decoded") {
    const Scene scene = loadChecked("webp-data-uri.gltf", "");
    REQUIRE(scene.images.size() == 1);
    CHECK(scene.images[0].width == 1);
    CHECK(scene.images[0].height == 1);
    CHECK(scene.materials[0].emissiveTexture.used());
}
#endif

TEST_CASE("validator corpus: a .gltf buffer without a uri is one line naming it, not tinygltf's words") {
    // The corpus' root/named_objects.gltf and unused_objects.gltf, valid to
    // the validator (it loads no data), have a scene whose data is nowhere.
    const std::string path = dataPath("validator/buffer-without-uri.gltf");
    CHECK(loadError(path) == path + ": error: buffer 0 has no uri: only a .glb's binary chunk can be a buffer "
                                    "without one, so its data is nowhere");
}

TEST_SUITE_END();
