// Instances stored once (--instancing, Scene::sharedMeshes, kFeatureInstancing):
// the loader places the same triangles, in world space, as flattening does;
// the two-level traversal renders what the flattened scene renders, with every
// BVH variant and both integrators; EXT_mesh_gpu_instancing's bad data is one
// error line; --stats reports the placements. Data: tests/data/instancing (scripts/make_instances.py):
// a sphere placed by nine nodes (node 4 mirrored, node 7 scaled unevenly)
// and by a node with nine EXT_mesh_gpu_instancing instances under a turned
// parent, a finer sphere placed twice, and a floor and a lamp placed once;
// normal-mapped.gltf: a normal-mapped quad placed three times.
#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "gltf_util.h"
#include "image/metrics.h"
#include "scene/scene.h"
#include "test_util.h"

namespace {

using namespace strata;
using namespace strata::test;

const std::string kFile = dataPath("instancing/instances.gltf");
constexpr std::size_t kSphere = 80, kFineSphere = 320, kWorld = 3;  // the floor (2) and a one-triangle lamp

Scene loadWith(Instancing mode) {
    LoadOptions options;
    options.instancing = mode;
    return loadGltf(kFile, options);
}

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("instancing: a mesh placed twice or more is stored once per winding, and auto flattens a small scene") {
    const Scene on = loadWith(Instancing::On);
    CHECK(on.worldTriangles() == kWorld);
    REQUIRE(on.sharedMeshes.size() == 3);  // the sphere, its mirrored copy, the fine sphere
    CHECK(on.sharedMeshes[0].count == kSphere);
    CHECK(on.sharedMeshes[1].count == kSphere);
    CHECK(on.sharedMeshes[1].name.find("(mirrored)") != std::string::npos);
    CHECK(on.sharedMeshes[2].count == kFineSphere);
    CHECK(on.triangles.size() == kWorld + 2 * kSphere + kFineSphere);
    CHECK(on.instances.size() == 9 + 9 + 2);
    for (const Instancing mode : {Instancing::Off, Instancing::Auto}) {
        const Scene flat = loadWith(mode);
        CHECK(flat.instances.empty());
        CHECK(flat.sharedMeshes.empty());
        CHECK(flat.triangles.size() == kWorld + 18 * kSphere + 2 * kFineSphere);
    }
}

TEST_CASE("instancing: each placement puts the same vertices, normals and winding in world space as flattening") {
    const Scene on = loadWith(Instancing::On), flat = loadWith(Instancing::Off);
    // Flattening walks the nodes in the order the instances were recorded.
    std::size_t next = kWorld;
    for (std::size_t k = 0; k < on.instances.size(); ++k) {
        const MeshInstance& inst = on.instances[k];
        const SharedMesh& mesh = on.sharedMeshes[inst.mesh];
        const glm::dmat4 toWorld(inst.toWorld);
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(toWorld)));
        CHECK(glm::determinant(glm::dmat3(toWorld)) * (mesh.name.find("mirrored") != std::string::npos ? -1.0 : 1.0) > 0.0);
        double worst = 0.0, worstNormal = 0.0;
        for (std::size_t i = 0; i < mesh.count; ++i) {
            const Triangle& object = on.triangles[mesh.first + i];
            const Triangle& world = flat.triangles.at(next + i);
            CHECK(object.material == world.material);
            for (int v = 0; v < 3; ++v) {
                const glm::dvec3 p(toWorld * glm::dvec4(glm::dvec3(object.v[v]), 1.0));
                worst = std::max(worst, glm::length(p - glm::dvec3(world.v[v])));
                const glm::dvec3 n = glm::normalize(normalMatrix * glm::dvec3(object.n[v]));
                worstNormal = std::max(worstNormal, glm::length(n - glm::dvec3(world.n[v])));
            }
        }
        CAPTURE(k);
        CHECK(worst < 1e-5);        // the scene spans about 10 units: float rounding of the two paths
        CHECK(worstNormal < 1e-5);
        next += mesh.count;
    }
    CHECK(next == flat.triangles.size());
}

TEST_CASE("instancing: EXT_mesh_gpu_instancing's bad data is one error line naming the node, exit 2, no output") {
    const std::string dir = dataPath("instancing/broken/");
    const std::pair<const char*, const char*> cases[] = {
        {"count-mismatch.gltf",
         "node 3 (\"Row\"): EXT_mesh_gpu_instancing SCALE has 3 instances where another attribute has 4 (all must "
         "have the same count)"},
        {"nan-translation.gltf",
         "node 3 (\"Row\"): EXT_mesh_gpu_instancing instance 3: not finite, or a rotation that is not a quaternion"},
        {"no-attributes.gltf", "node 3 (\"Row\"): EXT_mesh_gpu_instancing has none of TRANSLATION, ROTATION and SCALE"},
        {"no-mesh.gltf", "node 3 (\"Row\"): EXT_mesh_gpu_instancing on a node without a mesh"},
    };
    for (const auto& [file, message] : cases) {
        CAPTURE(file);
        const std::string path = dir + file;
        const std::string error = loadError(path);
        CHECK(isOneLine(error));
        CHECK(error.find(message) != std::string::npos);
        expectError("render " + path, path + ": error: " + message);
    }
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("render");

TEST_CASE("instancing: the two-level traversal renders what the flattened scene renders, with every BVH variant" * doctest::test_suite("slow")) {
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.spp = 8;
    const Scene on = loadWith(Instancing::On), flat = loadWith(Instancing::Off);
    const GpuScene gpuOn = buildAndPack(on), gpuFlat = buildAndPack(flat);
    CHECK((gpuOn.features.bits & gpu::kFeatureInstancing) != 0u);
    CHECK((gpuFlat.features.bits & gpu::kFeatureInstancing) == 0u);
    const RenderResult flatResult = uploadAndRender(gpuFlat, flat.cameras.at(0), s);
    const RenderResult onResult = uploadAndRender(gpuOn, on.cameras.at(0), s);
    CHECK(onResult.nonFinite == 0);
    // The same samples and the same light choices (the lamp is one triangle,
    // so the emitter list has one order however the triangles are ordered):
    // paths part only where the transforms' float rounding turns a decision,
    // so the images agree far below the noise of 8 spp (relMSE about 1e-1;
    // measured between them: 6e-11).
    const std::vector<float> a = onResult.film.mean(), b = flatResult.film.mean();
    const ErrorMetrics m = compareImages(a.data(), b.data(), a.size());
    CHECK(m.relMse < 1e-6);
    const ImageMean ma = imageMean(onResult.film), mb = imageMean(flatResult.film);
    CHECK(std::abs(ma.mean - mb.mean) < 1e-3 * mb.mean);
    // The BVH2 and the four-wide tree with its stack in memory find the same
    // hits: the same bits.
    RenderSettings bvh2 = s;
    bvh2.bvhWidth = 2;
    RenderSettings memory = s;
    memory.bvhStack = BvhStack::Memory;
    CHECK(sameImage(uploadAndRender(buildAndPack(on, {}, 2), on.cameras.at(0), bvh2).film, onResult.film));
    CHECK(sameImage(uploadAndRender(gpuOn, on.cameras.at(0), memory).film, onResult.film));
}

TEST_CASE("instancing: bench traces the same ray sets instanced and flattened (an instance's normal for the secondary rays)") {
    TempDir out;
    nlohmann::json j[2];
    const char* modes[2] = {"on", "off"};
    for (int k = 0; k < 2; ++k) {
        const Run r = run("bench " + kFile + " --instancing " + modes[k] + " --quick --only traversal --width 64 --height 48" +
                          " --json " + out / (std::string(modes[k]) + ".json"));
        CAPTURE(r.output);
        REQUIRE(r.status == 0);
        std::ifstream in(out / (std::string(modes[k]) + ".json"));
        j[k] = nlohmann::json::parse(in)["traversal"]["rays"];
    }
    for (const char* set : {"primary", "diffuse", "occlusion"}) {
        CAPTURE(set);
        CHECK(j[0][set]["rays"] == j[1][set]["rays"]);
    }
    CHECK(j[0]["diffuse"]["hits"] == j[1]["diffuse"]["hits"]);
    CHECK(j[0]["occlusion"]["occluded"] == j[1]["occlusion"]["occluded"]);
}

TEST_CASE("instancing: --stats reports the placements") {
    TempDir out;
    const Run r = run("render " + kFile + " --instancing on --stats --stats-json " + out / "s.json" + " -o " +
                      out / "a.exr" + " --spp 1 --width 8 --height 8 --quiet");
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(r.output.find("instances  21 placements of 3 shared meshes") != std::string::npos);
    std::ifstream in(out / "s.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    CHECK(j["instancing"]["placements"] == 21);  // 20 instances and the world's triangles
    CHECK(j["instancing"]["stored_triangles"] == kWorld + 2 * kSphere + kFineSphere);
    CHECK(j["instancing"]["placed_triangles"] == kWorld + 18 * kSphere + 2 * kFineSphere);
    const Run flat = run("render " + kFile + " --stats -o " + out / "b.exr" + " --spp 1 --width 8 --height 8 --quiet");
    CHECK(flat.output.find("instances  ") == std::string::npos);
}

TEST_CASE("instancing: a normal-mapped mesh placed turned, mirrored and scaled shades as its flattened twin" * doctest::test_suite("slow")) {
    // Lit by the default white environment (no lamp), so the light samples
    // do not depend on how the triangles are ordered: the two images differ
    // only by the transforms' float rounding (measured 6e-16). Without
    // texture LOD: its random level choices are seeded by the hit, whose
    // last bits differ between the twins.
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.spp = 8;
    LoadOptions on, off;
    on.instancing = Instancing::On;
    off.instancing = Instancing::Off;
    const std::string file = dataPath("instancing/normal-mapped.gltf");
    CerrCapture quiet;  // the default-light warning
    const Scene a = loadGltf(file, on), b = loadGltf(file, off);
    CHECK(a.instances.size() == 3);
    const GpuScene ga = buildAndPack(a, {}, 4, false), gb = buildAndPack(b, {}, 4, false);
    CHECK((ga.features.bits & (gpu::kFeatureNormalMap | gpu::kFeatureInstancing)) ==
          (gpu::kFeatureNormalMap | gpu::kFeatureInstancing));
    const std::vector<float> x = uploadAndRender(ga, a.cameras.at(0), s).film.mean(),
                             y = uploadAndRender(gb, b.cameras.at(0), s).film.mean();
    CHECK(compareImages(x.data(), y.data(), x.size()).relMse < 1e-6);
}

TEST_CASE("instancing: the wavefront integrator renders an instanced scene as the megakernel does, bit for bit" * doctest::test_suite("slow")) {
    RenderSettings s;
    s.width = 48;
    s.height = 36;
    s.spp = 4;
    const Scene on = loadWith(Instancing::On);
    const GpuScene gpu = buildAndPack(on);
    const RenderResult mega = uploadAndRender(gpu, on.cameras.at(0), s);
    s.integrator = IntegratorKind::Wavefront;
    CHECK(sameImage(uploadAndRender(gpu, on.cameras.at(0), s).film, mega.film));
}

TEST_SUITE_END();
