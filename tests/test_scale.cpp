// Scenes larger than a storage descriptor reaches (lavapipe: 128 MiB): every
// per-triangle array and the emitters are read through texel views, each
// descriptor stays within the device's limits, and a scene beyond what the
// device can address at all is a one-line error. Lowered limits
// (RenderTuning::limits) take small scenes down the large-scene path.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "render/command.h"
#include "upload/device_scene.h"
#include "pack/gpu_scene.h"
#include "scene/scene.h"
#include "test_util.h"
#include "util/error.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

// Renders `scene` as the device allows and again with a storage range of 16
// bytes, so that every array is read through its texel view: the two images
// are the same bits.
void checkLargePathMatches(const Scene& scene) {
    const GpuScene g = buildAndPack(scene);
    RenderSettings s;
    s.reads = ReadMode::Texel;  // the BVH through texel views, the rest as storage
    s.width = 24;
    s.height = 16;
    s.spp = 2;
    s.maxDepth = 4;
    s.seed = 3;
    const RenderResult normal = uploadAndRender(g, scene.cameras.at(0), s);
    RenderTuning t;
    t.limits.storageRange = 16;  // every array has a texel view to be read through
    REQUIRE(g.shading.size() * sizeof(gpu::TriShading) > t.limits.storageRange);
    const RenderResult large = uploadAndRender(g, scene.cameras.at(0), s, t);
    CHECK(normal.reads == gpu::kReadsTexelBvh);
    CHECK(large.reads == gpu::kReadsTexelAll);
    CHECK(large.nonFinite == 0);
    CHECK(large.closestRays == normal.closestRays);
    CHECK(large.shadowRays == normal.shadowRays);
    CHECK(sameImage(normal.film, large.film));
    CHECK(large.sceneBytes == normal.sceneBytes);
    CHECK(vk::validationMessageCount() == 0);
}

}  // namespace

TEST_CASE("scale: past the storage range every array is read through texel views, with the same image" * doctest::test_suite("slow")) {
    SUBCASE("textures, normal maps, transmission, emissive triangles") {
        checkLargePathMatches(loadGltf(sourcePath("scenes/materials-board.gltf")));
    }
    SUBCASE("alpha test") { checkLargePathMatches(loadGltf(sourcePath("tests/data/textures/alpha-mask.gltf"))); }
    SUBCASE("environment map and a directional light") { checkLargePathMatches(envBoardWithSun()); }
}

TEST_CASE("scale: reads follow the device's limits, and a scene beyond them is a one-line error" * doctest::test_suite("unit")) {
    GpuScene g;
    g.source = "big.glb";
    g.nodes.resize(100);     // 3200 bytes (BVH2)
    g.tris.resize(1000);     // 48000 bytes
    g.shading.resize(1000);  // 48000 bytes
    g.materials.resize(1);
    SceneLimits l{1u << 20, 1u << 20, 1u << 30};
    CHECK(chooseReads(l, g, ReadMode::Auto, false, true) == gpu::kReadsTexelAll);  // lavapipe
    CHECK(chooseReads(l, g, ReadMode::Auto, false, false) == gpu::kReadsStorage);  // a GPU
    CHECK(chooseReads(l, g, ReadMode::Texel, false, true) == gpu::kReadsTexelBvh);
    g.shading.resize(2000);   // 96000 bytes: 6000 texels, past a view of 4000 but within the storage range
    l.texelElements = 4000;
    CHECK(chooseReads(l, g, ReadMode::Auto, false, true) == gpu::kReadsTexelBvh);  // the BVH alone
    g.shading.resize(1000);
    l.texelElements = 1u << 20;
    CHECK(chooseReads(l, g, ReadMode::Storage, false, true) == gpu::kReadsStorage);

    l.storageRange = 16384;  // the triangles and their shading only fit texel views
    CHECK(chooseReads(l, g, ReadMode::Auto, false, false) == gpu::kReadsTexelAll);
    CHECK(chooseReads(l, g, ReadMode::Texel, false, false) == gpu::kReadsTexelAll);
    CHECK_THROWS_WITH_AS(chooseReads(l, g, ReadMode::Storage, false, true),
                         "big.glb: error: --reads storage: the triangle vertices need 48000 bytes, more than "
                         "the device's maxStorageBufferRange (16384 bytes)",
                         Error);

    l.texelElements = 2000;  // 3000 texels of 16 bytes needed
    CHECK_THROWS_WITH_AS(chooseReads(l, g, ReadMode::Auto, false, true),
                         "big.glb: error: the triangle vertices need 48000 bytes, more than the device's "
                         "maxStorageBufferRange (16384 bytes) and maxTexelBufferElements (2000 texels of 16 bytes)",
                         Error);

    l = {1u << 20, 1u << 20, 32768};
    CHECK_THROWS_WITH_AS(chooseReads(l, g, ReadMode::Auto, false, true),
                         "big.glb: error: the triangle vertices need 48000 bytes in one buffer, more than the "
                         "device's maxMemoryAllocationSize (32768 bytes)",
                         Error);

    l = {16384, 1u << 20, 1u << 30};
    g.tris.resize(100);  // the per-triangle arrays fit the storage range again
    g.shading.resize(100);
    g.materials.resize(300);  // 300 x 176 bytes: past the storage range, read through a texel view
    CHECK(chooseReads(l, g, ReadMode::Auto, false, false) == gpu::kReadsTexelAll);
    const std::string materialBytes = std::to_string(300 * sizeof(gpu::Material));
    CHECK_THROWS_WITH_AS(chooseReads(l, g, ReadMode::Storage, false, false),
                         ("big.glb: error: --reads storage: the materials need " + materialBytes +
                          " bytes, more than the device's maxStorageBufferRange (16384 bytes)")
                             .c_str(),
                         Error);
    g.materials.resize(1);
    g.envTables.resize(5000);  // 20000 bytes: the same
    CHECK(chooseReads(l, g, ReadMode::Auto, false, false) == gpu::kReadsTexelAll);
    CHECK_THROWS_WITH_AS(chooseReads(l, g, ReadMode::Storage, false, false),
                         "big.glb: error: --reads storage: the environment sampling tables need 20000 bytes, "
                         "more than the device's maxStorageBufferRange (16384 bytes)",
                         Error);
}

TEST_CASE("scale: strata render of a scene the device cannot hold fails with one line and writes nothing") {
    TempDir dir;
    RenderCommand cmd;
    cmd.scene = sourcePath("scenes/cornell-box.gltf");
    cmd.outputs = {dir / "box.exr", dir / "box.png"};
    cmd.quiet = true;
    cmd.validation = vk::validationRequestedByEnvironment();
    cmd.settings.width = 8;
    cmd.settings.height = 8;
    cmd.settings.spp = 1;
    cmd.tuning.limits.allocation = 1024;  // the 32 triangles' vertices are 1536 bytes
    std::string message;
    try {
        runRender(cmd);
    } catch (const Error& e) {
        message = e.what();
    }
    CAPTURE(message);
    CHECK(message.rfind(cmd.scene + ": error: the ", 0) == 0);
    CHECK(message.find("more than the device's maxMemoryAllocationSize (1024 bytes)") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
    CHECK(dir.empty());
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("scale: a render whose scene and image need more than the device's memory is one line before any buffer") {
    TempDir dir;
    RenderCommand cmd;
    cmd.scene = sourcePath("scenes/cornell-box.gltf");
    cmd.outputs = {dir / "box.exr"};
    cmd.quiet = true;
    cmd.validation = vk::validationRequestedByEnvironment();
    cmd.settings.width = 8;
    cmd.settings.height = 8;
    cmd.settings.spp = 1;
    const auto refusal = [&](std::uint64_t memory) {
        cmd.tuning.limits.memory = memory;
        try {
            runRender(cmd);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // Below what its flattened triangles' arrays alone need (TriVerts,
    // TriShading, the emitters' Emitter), the loader refuses it before they
    // are made (finding 8 of the validator corpus: a million placements of
    // an emitter were refused only after flattening).
    const Scene box = loadGltf(cmd.scene);
    std::size_t emitters = 0;
    for (const Triangle& t : box.triangles) emitters += isEmissive(box.materials[t.material]) ? 1 : 0;
    const std::uint64_t least = box.triangles.size() * kDeviceBytesPerTriangle + emitters * kDeviceBytesPerEmitter;
    const std::string early = refusal(least - 1);
    CAPTURE(early);
    CHECK(early.rfind(cmd.scene + ": error: the scene's ", 0) == 0);
    CHECK(early.find(" placed nodes flatten into " + std::to_string(box.triangles.size()) + " triangles (" +
                     std::to_string(emitters) + " of them emitters, which are always flattened), whose arrays need " +
                     "at least " + std::to_string(least) + " bytes of device memory, more than the " +
                     std::to_string(least - 1) + " bytes of ") != std::string::npos);
    CHECK(early.ends_with(" (the limit set)"));
    CHECK(early.find('\n') == std::string::npos);
    CHECK(dir.empty());
    const std::string message = refusal(least);
    CAPTURE(message);
    const std::string head = cmd.scene + ": error: the render needs ";
    REQUIRE(message.rfind(head, 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
    // 8 x 8 pixels of sums at 32 bytes, twice on lavapipe (the readback copy
    // is in the same memory).
    CHECK(message.find(" bytes of device memory (the scene's arrays ") != std::string::npos);
    CHECK(message.find(", the image's sample sums 4096 bytes), more than the " + std::to_string(least) + " bytes of ") !=
          std::string::npos);
    CHECK(message.find("(the limit set)") != std::string::npos);
    CHECK(dir.empty());
    // Exactly what it needs renders; a byte less is refused.
    const std::uint64_t needed = std::stoull(message.substr(head.size()));
    CHECK(refusal(needed - 1).rfind(head + std::to_string(needed) + " bytes", 0) == 0);
    CHECK(refusal(needed).empty());
    CHECK(std::filesystem::exists(dir / "box.exr"));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("scale: strata render --stats reports the scene's memory, packed and on the device") {
    TempDir dir;
    const std::string scene = sourcePath("scenes/materials-board.gltf");
    const Run r = run("render " + scene + " -o " + (dir / "m.png") + " --width 16 --height 9 --spp 1 --quiet --stats" +
                      " --stats-json " + (dir / "s.json"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find("memory     scene ") != std::string::npos);
    std::ifstream f(dir / "s.json");
    const nlohmann::json m = nlohmann::json::parse(f)["memory"];
    const GpuScene g = buildAndPack(loadGltf(scene));
    // The four-wide BVH, the per-triangle arrays, emitters, materials and textures, as packed.
    const std::uint64_t packed =
        g.wide.size() * sizeof(gpu::BvhNode4) + g.tris.size() * sizeof(gpu::TriVerts) +
        g.shading.size() * sizeof(gpu::TriShading) + g.texcoords.size() * sizeof(gpu::TriTexcoords) +
        g.tangents.size() * sizeof(gpu::TriTangents) + g.emitters.size() * sizeof(gpu::Emitter) +
        g.materials.size() * sizeof(gpu::Material) + g.textureRefs.size() * sizeof(gpu::TextureRef) +
        g.texels.size() * sizeof(std::uint32_t);
    CHECK(m["scene_packed_bytes"].get<std::uint64_t>() == packed);
    CHECK(m["scene_device_bytes"].get<std::uint64_t>() >= packed);
    CHECK(m["scene_device_bytes"].get<double>() <= 1.5 * static_cast<double>(packed));
    CHECK(m["device_peak_bytes"].get<std::uint64_t>() >= m["scene_device_bytes"].get<std::uint64_t>());
    CHECK(m["host_peak_rss_bytes"].get<std::uint64_t>() > packed);
}

namespace {

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// packSceneAndRelease(copy of scene, its BVH, width) against packScene(scene, its BVH).
void checkConsumingPack(const Scene& scene, int bvhWidth) {
    CAPTURE(bvhWidth);
    const GpuScene kept = buildAndPack(scene);
    Scene consumed = scene;
    const GpuScene g = packSceneAndRelease(consumed, buildSceneBvh(consumed), bvhWidth, LightSampler::Auto,
                                           {0, true});  // mip chains, as buildAndPack's
    CHECK(consumed.triangles.empty());  // released
    CHECK(consumed.texcoords.empty());
    CHECK(consumed.tangents.empty());
    CHECK(g.triangleCount == kept.triangleCount);
    CHECK(sameBytes(g.tris, kept.tris));
    CHECK(sameBytes(g.shading, kept.shading));
    CHECK(sameBytes(g.texcoords, kept.texcoords));
    CHECK(sameBytes(g.tangents, kept.tangents));
    CHECK(sameBytes(g.emitters, kept.emitters));
    CHECK(sameBytes(g.wide, kept.wide));
    CHECK(sameBytes(g.materials, kept.materials));
    CHECK(sameBytes(g.textureRefs, kept.textureRefs));
    CHECK(sameBytes(g.texels, kept.texels));
    CHECK(g.wideDepth == kept.wideDepth);
    CHECK(g.features.bits == kept.features.bits);
    CHECK(g.sceneRadius == kept.sceneRadius);
    CHECK(g.totalPower == kept.totalPower);
    // The BVH2 is dropped only where the four-wide tree will be traversed.
    CHECK(g.bvhWidth == bvhWidth);
    if (bvhWidth == 4) CHECK(g.nodes.empty());
    else CHECK(sameBytes(g.nodes, kept.nodes));
}

}  // namespace

TEST_CASE("packSceneAndRelease packs what packScene packs, in several reorder chunks" * doctest::test_suite("unit")) {
    // 600,000 triangles: three chunks of the bucket pass (2^18), the last
    // partial; every 997th emissive, so emitters are numbered across chunks.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f), off(-0.05f, 0.05f);
    Scene soup;
    soup.path = "soup";
    soup.materials.push_back(MaterialDesc{});
    MaterialDesc light;
    light.emissiveFactor = glm::vec3(1.0f, 0.5f, 0.25f);
    soup.materials.push_back(light);
    for (std::size_t i = 0; i < 600000; ++i) {
        Triangle t;
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        for (int k = 0; k < 3; ++k) t.v[k] = c + glm::vec3(off(rng), off(rng), off(rng));
        const glm::vec3 n = glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
        t.n[0] = t.n[1] = t.n[2] = n;
        t.material = i % 997 == 0 ? 1u : 0u;
        soup.triangles.push_back(t);
    }
    checkConsumingPack(soup, 4);
    checkConsumingPack(soup, 2);
}

TEST_CASE("packSceneAndRelease keeps texture coordinates and tangents with their triangles" * doctest::test_suite("unit")) {
    const Scene scene = loadGltf(sourcePath("tests/data/textures/plane-tilted-map.gltf"));
    REQUIRE_FALSE(scene.texcoords.empty());
    REQUIRE_FALSE(scene.tangents.empty());
    checkConsumingPack(scene, 4);
    checkConsumingPack(scene, 2);
}

TEST_SUITE_END();
