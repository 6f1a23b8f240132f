// The stage runner (host/stages): one SceneRequest, load -> camera -> BVH ->
// pack on the host, each choice acted on by one stage. CPU only: no upload.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>

#include "stages/stages.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("unit");

namespace {

// The upload takes no BVH width: the packed scene's is the only one.
template <class T>
concept HasBvhWidth = requires(T t) { t.bvhWidth; };
static_assert(!HasBvhWidth<UploadOptions>);
static_assert(HasBvhWidth<GpuScene>);

SceneRequest fileRequest(const std::string& rel, int bvhWidth, Consume consume) {
    SceneRequest r;
    r.file = sourcePath(rel);
    r.camera = CameraChoice{{}, 32, 24};
    r.bvhWidth = bvhWidth;
    r.consume = consume;
    return r;
}

// A chain of triangles shrinking by 1.15x, one per leaf: a tree deeper than
// the four-wide traversal's register stack holds (kBvhMaxRegs).
Scene deepChain() { return triangleChain(400, 1.15f); }

}  // namespace

TEST_CASE("stages: packing chooses the BVH width once, and drops the BVH2 only where the four-wide tree is traversed") {
    {
        const HostScene h = prepareScene(fileRequest("scenes/cornell-box.gltf", 4, Consume::All));
        CHECK(h.gpu.bvhWidth == 4);
        CHECK(h.gpu.nodes.empty());
        CHECK_FALSE(h.gpu.wide.empty());
        CHECK(h.scene.triangles.empty());  // consumed by packing
        CHECK(h.gpu.triangleCount > 0);
        CHECK(h.loadMs > 0.0);
        CHECK(h.packMs > 0.0);
    }
    {
        const HostScene h = prepareScene(fileRequest("scenes/cornell-box.gltf", 2, Consume::All));
        CHECK(h.gpu.bvhWidth == 2);
        CHECK_FALSE(h.gpu.nodes.empty());
    }
    for (Consume keep : {Consume::None}) {
        const HostScene h = prepareScene(fileRequest("scenes/cornell-box.gltf", 4, keep));
        CHECK(h.gpu.bvhWidth == 4);
        CHECK_FALSE(h.gpu.nodes.empty());  // both trees kept: the CPU reference traversal reads the BVH2
        CHECK(h.scene.triangles.size() == h.gpu.triangleCount);
    }
    // A tree too deep for the register stack is traversed as the BVH2,
    // whatever width was asked for; packing keeps it.
    SceneRequest deep;
    deep.build.bins = 2;
    deep.build.maxLeafSize = 1;
    deep.consume = Consume::All;
    const HostScene h = prepareScene(deep, deepChain());
    REQUIRE(h.gpu.wideDepth > kBvhMaxRegs);
    CHECK(h.gpu.bvhWidth == 2);
    CHECK_FALSE(h.gpu.nodes.empty());
    CHECK(h.loadMs == 0.0);  // given a scene: no load stage
}

TEST_CASE("stages: --frames keeps the placements and the bottom levels that packing would release") {
    SceneRequest r = fileRequest("tests/data/instancing/instances.gltf", 4, Consume::All);
    r.load.instancing = Instancing::On;
    const HostScene released = prepareScene(r);
    REQUIRE(released.gpu.placementCount > 1);
    CHECK(released.scene.instances.empty());
    CHECK(released.bottoms.empty());
    r.keepPlacements = true;
    const HostScene kept = prepareScene(r);
    CHECK_FALSE(kept.scene.instances.empty());
    CHECK(kept.bottoms.size() >= 2);  // the world's, then each shared mesh's
    CHECK(kept.scene.triangles.empty());
}

TEST_CASE("stages: a file's bytes load as the file does, the camera is chooseCamera's for the request's view") {
    SceneRequest r = fileRequest("scenes/cornell-box.gltf", 4, Consume::None);
    std::ifstream f(r.file, std::ios::binary);
    r.bytes = std::vector<unsigned char>(std::istreambuf_iterator<char>(f), {});
    const HostScene fromBytes = prepareScene(r);
    r.bytes.reset();
    const HostScene fromFile = prepareScene(r);
    CHECK(fromBytes.scene.triangles.size() == fromFile.scene.triangles.size());
    CHECK(fromBytes.gpu.tris.size() == fromFile.gpu.tris.size());
    const Camera expected = chooseCamera(fromFile.scene, ViewOptions{}, 32, 24);
    CHECK(fromFile.camera.position == expected.position);
    CHECK(fromFile.camera.forward == expected.forward);
    CHECK(fromFile.camera.yfov == expected.yfov);
    r.camera->view.fovDegrees = 30.0f;
    CHECK(requestedCamera(r, fromFile.scene).yfov == doctest::Approx(30.0 * std::numbers::pi / 180.0));
    // The request of a render's settings: the upload's options from one place.
    RenderSettings s;
    s.reads = ReadMode::Storage;
    s.bvhStack = BvhStack::Memory;
    s.width = 8;
    s.height = 4;
    const UploadOptions o = uploadOptions(sceneRequest(s));
    CHECK(o.reads == ReadMode::Storage);
    CHECK(o.stack == BvhStack::Memory);
    CHECK(o.imageBytes == sampleSumBytes(s));
}

TEST_SUITE_END();
