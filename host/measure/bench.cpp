#include "measure/bench.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "render/gpu_scene.h"
#include "render/tracer.h"
#include "scene/scene.h"
#include "util/error.h"
#include "util/files.h"
#include "vk/context.h"

namespace strata {
namespace {

// The peer's per-pixel random numbers: a PCG step with the RXS-M-XS output.
std::uint32_t pcgNext(std::uint32_t& s) {
    s = s * 747796405u + 2891336453u;
    const std::uint32_t w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}
float unitFloat(std::uint32_t& s) { return static_cast<float>(pcgNext(s) >> 8) * (1.0f / 16777216.0f); }

glm::vec3 cosineAbout(glm::vec3 n, std::uint32_t& seed) {
    const glm::vec3 a = std::fabs(n.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 tx = glm::normalize(glm::cross(a, n)), ty = glm::cross(n, tx);
    const float r1 = unitFloat(seed), r2 = unitFloat(seed);
    const float phi = 2.0f * std::numbers::pi_v<float> * r1, rr = std::sqrt(r2);
    return glm::normalize(tx * (rr * std::cos(phi)) + ty * (rr * std::sin(phi)) +
                          n * std::sqrt(std::max(0.0f, 1.0f - r2)));
}

gpu::TraceRay makeRay(glm::vec3 o, glm::vec3 d, float tmax) {
    gpu::TraceRay r{};
    r.origin = o;
    r.dir = d;
    r.tmin = 0.0f;
    r.tmax = tmax;
    return r;
}

}  // namespace

int runBench(const BenchCommand& cmd) {
    if (!cmd.json.empty() && lowerExtension(cmd.json) != ".json") fail(cmd.json, "bench report must be .json");
    LoadOptions options;
    options.requireCamera = false;   // auto-framed like the peer
    options.requireEmitter = false;  // traversal needs no light
    Scene scene = loadGltf(cmd.scene, options);
    if (scene.triangles.empty()) fail(cmd.scene, "no triangles to trace");

    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& t : scene.triangles)
        for (const auto& v : t.v) lo = glm::min(lo, v), hi = glm::max(hi, v);
    const float diag = glm::length(hi - lo);
    const float eps = 1e-4f * diag;
    Camera cam;
    std::string camDesc;
    if (!scene.cameras.empty()) {
        if (cmd.camera < 0 || static_cast<std::size_t>(cmd.camera) >= scene.cameras.size())
            fail(cmd.scene, "--camera " + std::to_string(cmd.camera) + " does not exist");
        cam = scene.cameras[cmd.camera];
        camDesc = "camera " + std::to_string(cmd.camera);
    } else {
        const glm::vec3 c = (lo + hi) * 0.5f;
        cam.position = c + glm::normalize(glm::vec3(0.6f, 0.45f, 1.0f)) * (diag * 1.1f);
        cam.forward = glm::normalize(c - cam.position);
        cam.up = glm::cross(glm::normalize(glm::cross(cam.forward, glm::vec3(0, 1, 0))), cam.forward);
        cam.yfov = 45.0f * std::numbers::pi_v<float> / 180.0f;
        camDesc = "none in file: auto-framed as the peer does";
    }
    const glm::vec3 light((lo.x + hi.x) * 0.5f, hi.y, (lo.z + hi.z) * 0.5f);

    const auto t0 = std::chrono::steady_clock::now();
    GpuScene gpu = packScene(scene);
    const double packMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    vk::Context ctx({cmd.device, cmd.validation});
    DeviceTracer tracer(ctx, gpu, Traversal::Auto);

    // Primary rays through pixel centres, row 0 at the top.
    const int W = cmd.width, H = cmd.height;
    const float tanHalf = std::tan(cam.yfov * 0.5f);
    const glm::vec3 right = glm::normalize(glm::cross(cam.forward, cam.up));
    const glm::vec3 up = glm::cross(right, cam.forward);
    std::vector<gpu::TraceRay> primary;
    primary.reserve(static_cast<std::size_t>(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float sx = (2.0f * (x + 0.5f) / W - 1.0f) * tanHalf * W / H;
            const float sy = (1.0f - 2.0f * (y + 0.5f) / H) * tanHalf;
            primary.push_back(makeRay(cam.position, glm::normalize(cam.forward + sx * right + sy * up), 1e30f));
        }
    double primarySeconds = 0.0;
    const auto primaryHits = tracer.trace(primary, gpu::kTraceClosest, cmd.reps, &primarySeconds);

    std::vector<gpu::TraceRay> diffuse, occlusion;
    std::size_t primaryHitCount = 0;
    for (std::size_t i = 0; i < primary.size(); ++i) {
        const gpu::TraceHit& h = primaryHits[i];
        if (h.triangle == gpu::kNoHit) continue;
        ++primaryHitCount;
        const gpu::TriVerts& t = gpu.tris[h.triangle];
        glm::vec3 n = glm::normalize(glm::cross(glm::vec3(t.v1 - t.v0), glm::vec3(t.v2 - t.v0)));
        if (glm::dot(n, primary[i].dir) > 0.0f) n = -n;
        const glm::vec3 o = primary[i].origin + primary[i].dir * h.t + n * eps;
        std::uint32_t seed = 0x9E3779B9u ^ static_cast<std::uint32_t>(i);
        diffuse.push_back(makeRay(o, cosineAbout(n, seed), 1e30f));
        const glm::vec3 toL = light - o;
        const float dist = glm::length(toL);
        if (glm::dot(toL, n) > 0.0f && dist > 2.0f * eps) occlusion.push_back(makeRay(o, toL / dist, dist - eps));
    }
    double diffuseSeconds = 0.0, occlusionSeconds = 0.0;
    const auto diffuseHits = tracer.trace(diffuse, gpu::kTraceClosest, cmd.reps, &diffuseSeconds);
    const auto occluded = tracer.trace(occlusion, gpu::kTraceAny, cmd.reps, &occlusionSeconds);
    std::size_t diffuseHitCount = 0, occludedCount = 0;
    for (const auto& h : diffuseHits) diffuseHitCount += h.triangle != gpu::kNoHit;
    for (const auto& h : occluded) occludedCount += h.t > 0.0f;

    auto mrays = [](std::size_t n, double s) { return s > 0.0 ? static_cast<double>(n) / s * 1e-6 : 0.0; };
    nlohmann::ordered_json j;
    j["scene"] = cmd.scene;
    j["device"] = ctx.info.name;
    j["device_type"] = ctx.info.type;
    j["triangles"] = scene.triangles.size();
    j["camera"] = camDesc;
    j["image"] = {W, H};
    j["reps"] = cmd.reps;
    j["traversal"] = tracer.texel() ? "texel" : "storage";
    j["secondary_origin_offset"] = eps;
    j["occlusion_point"] = {light.x, light.y, light.z};
    j["bvh"] = {{"build_ms", gpu.bvh.buildMs},
                {"build_ms_per_mtri", gpu.bvh.buildMs / (scene.triangles.size() * 1e-6)},
                {"pack_ms", packMs},
                {"nodes", gpu.bvh.nodes},
                {"leaves", gpu.bvh.leaves},
                {"max_depth", gpu.bvh.maxDepth},
                {"sah_cost", gpu.bvh.sahCost},
                {"bytes", gpu.bvh.bytes}};
    j["rays"] = {
        {"primary", {{"rays", primary.size()}, {"hits", primaryHitCount}, {"device_s", primarySeconds},
                     {"mrays_per_s", mrays(primary.size(), primarySeconds)}}},
        {"diffuse", {{"rays", diffuse.size()}, {"hits", diffuseHitCount}, {"device_s", diffuseSeconds},
                     {"mrays_per_s", mrays(diffuse.size(), diffuseSeconds)}}},
        {"occlusion", {{"rays", occlusion.size()}, {"occluded", occludedCount}, {"device_s", occlusionSeconds},
                       {"mrays_per_s", mrays(occlusion.size(), occlusionSeconds)}}}};
    if (!cmd.json.empty()) writeTextAtomically(cmd.json, j.dump(2) + "\n");

    std::printf("strata bench: %s (%zu triangles), %dx%d, %s, %s traversal, median of %d\n", cmd.scene.c_str(),
                scene.triangles.size(), W, H, ctx.info.name.c_str(), tracer.texel() ? "texel" : "storage", cmd.reps);
    std::printf("  BVH build %.1f ms (%.1f ms/Mtri), %u nodes, %u leaves, depth %u, SAH cost %.2f\n", gpu.bvh.buildMs,
                gpu.bvh.buildMs / (scene.triangles.size() * 1e-6), gpu.bvh.nodes, gpu.bvh.leaves, gpu.bvh.maxDepth,
                gpu.bvh.sahCost);
    std::printf("  primary    %9zu rays  %6.1f%% hit       %8.3f Mrays/s\n", primary.size(),
                100.0 * primaryHitCount / std::max<std::size_t>(1, primary.size()), mrays(primary.size(), primarySeconds));
    std::printf("  diffuse    %9zu rays  %6.1f%% hit       %8.3f Mrays/s\n", diffuse.size(),
                100.0 * diffuseHitCount / std::max<std::size_t>(1, diffuse.size()), mrays(diffuse.size(), diffuseSeconds));
    std::printf("  occlusion  %9zu rays  %6.1f%% occluded  %8.3f Mrays/s\n", occlusion.size(),
                100.0 * occludedCount / std::max<std::size_t>(1, occlusion.size()),
                mrays(occlusion.size(), occlusionSeconds));
    return 0;
}

}  // namespace strata
