#include "measure/bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "measure/bench_render.h"
#include "measure/tracer.h"
#include "pack/gpu_scene.h"
#include "render/report.h"
#include "scene/scene.h"
#include "stages/stages.h"
#include "util/error.h"
#include "util/files.h"
#include "vk/check.h"
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

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Framing {
    Camera camera;
    std::string description;
    glm::vec3 lo{1e30f}, hi{-1e30f};
};

// The scene's camera or the --look-from view, else (none in the file) the
// peer's auto-framing, not frameScene's: the rays must be the peer's.
Framing frame(const Scene& scene, const BenchCommand& cmd) {
    Framing f;
    for (const auto& t : scene.triangles)
        for (const auto& v : t.v) f.lo = glm::min(f.lo, v), f.hi = glm::max(f.hi, v);
    const float diag = glm::length(f.hi - f.lo);
    if (!scene.cameras.empty() || cmd.view.lookGiven()) {
        f.camera = chooseCamera(scene, cmd.view, int(cmd.settings.width), int(cmd.settings.height));
        f.description = cmd.view.lookGiven() ? "--look-from" : "camera " + std::to_string(cmd.view.camera);
    } else {
        const glm::vec3 c = (f.lo + f.hi) * 0.5f;
        Camera& cam = f.camera;
        cam.position = c + glm::normalize(glm::vec3(0.6f, 0.45f, 1.0f)) * (diag * 1.1f);
        cam.forward = glm::normalize(c - cam.position);
        cam.up = glm::cross(glm::normalize(glm::cross(cam.forward, glm::vec3(0, 1, 0))), cam.forward);
        cam.yfov = cmd.view.fovDegrees.value_or(45.0f) * std::numbers::pi_v<float> / 180.0f;
        f.description = "none in file: auto-framed as the peer does";
    }
    return f;
}

// The tracer's upload of the scene.
struct Upload {
    std::uint64_t packedBytes = 0, deviceBytes = 0;
    double ms = 0.0;
};

// The peer's three ray sets, traced with the shader BVH (median of cmd.reps
// passes each).
nlohmann::ordered_json traversalSection(const vk::Context& ctx, const SceneRequest& request, const GpuScene& gpu,
                                        const Framing& fr, const BenchCommand& cmd, Upload& upload) {
    SceneRequest traced = request;
    traced.imageBytes = 0;  // rays only: no image's sums beside the scene
    DeviceTracer tracer(ctx, uploadPrepared(ctx, traced, gpu));
    const glm::vec3 lo = fr.lo, hi = fr.hi;
    const Camera& cam = fr.camera;
    const float eps = 1e-4f * glm::length(hi - lo);
    const glm::vec3 light((lo.x + hi.x) * 0.5f, hi.y, (lo.z + hi.z) * 0.5f);
    // Primary rays through pixel centres, row 0 at the top.
    const int W = cmd.settings.width, H = cmd.settings.height;
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
    std::vector<std::uint32_t> primaryInstances;
    const auto primaryHits = tracer.trace(primary, gpu::kTraceClosest, cmd.reps, &primarySeconds, &primaryInstances);

    std::vector<gpu::TraceRay> diffuse, occlusion;
    std::size_t primaryHitCount = 0;
    for (std::size_t i = 0; i < primary.size(); ++i) {
        const gpu::TraceHit& h = primaryHits[i];
        if (h.triangle == gpu::kNoHit) continue;
        ++primaryHitCount;
        const gpu::TriVerts& t = gpu.tris[h.triangle];
        glm::vec3 n = glm::normalize(glm::cross(glm::vec3(t.v1 - t.v0), glm::vec3(t.v2 - t.v0)));
        if (primaryInstances[i] != gpu::kNoInstance) {
            // An instance's triangle: its normal by the inverse transpose,
            // worldToObject's rows (the record's first texels) as columns.
            const std::size_t r = primaryInstances[i];
            glm::mat3 normalMatrix;
            for (int k = 0; k < 3; ++k) normalMatrix[k] = glm::vec3(glm::uintBitsToFloat(gpu.instances[r + k]));
            n = glm::normalize(normalMatrix * n);
        }
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
    j["image"] = {W, H};
    j["reps"] = cmd.reps;
    j["reads"] = readsName(tracer.deviceScene().reads);
    j["bvh_width"] = tracer.bvhWidth();
    j["bvh_stack"] = bvhStackName(tracer.deviceScene());
    j["work_queue"] = tracer.workQueue();
    j["secondary_origin_offset"] = eps;
    j["occlusion_point"] = {light.x, light.y, light.z};
    j["rays"] = {
        {"primary", {{"rays", primary.size()}, {"hits", primaryHitCount}, {"device_s", primarySeconds},
                     {"mrays_per_s", mrays(primary.size(), primarySeconds)}}},
        {"diffuse", {{"rays", diffuse.size()}, {"hits", diffuseHitCount}, {"device_s", diffuseSeconds},
                     {"mrays_per_s", mrays(diffuse.size(), diffuseSeconds)}}},
        {"occlusion", {{"rays", occlusion.size()}, {"occluded", occludedCount}, {"device_s", occlusionSeconds},
                       {"mrays_per_s", mrays(occlusion.size(), occlusionSeconds)}}}};
    const DeviceScene& d = tracer.deviceScene();
    upload = {d.packedBytes, d.deviceBytes, d.uploadMs};
    return j;
}


std::string format(const char* fmt, auto... args) {
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    return buf;
}

double num(const nlohmann::ordered_json& v) { return v.is_number() ? v.get<double>() : 0.0; }

// The report for people: the JSON's figures, section by section.
std::string benchText(const nlohmann::ordered_json& j) {
    std::string o;
    std::string features;
    for (const auto& f : j["features"]) features += (features.empty() ? "" : ", ") + f.get<std::string>();
    o += format("strata bench: %s (%zu triangles), %s (%s)\n", j["scene"].get<std::string>().c_str(),
                j["triangles"].get<std::size_t>(), j["device"].get<std::string>().c_str(),
                j["driver"].get<std::string>().c_str());
    o += "features: " + (features.empty() ? std::string("none") : features) + "; camera: " +
         j["camera"].get<std::string>() +
         (j.contains("environment") ? "; environment " + j["environment"].get<std::string>() : std::string()) +
         "\n";
    const auto& su = j["startup"];
    o += "start-up: " + startupText(su);
    if (!su.contains("pipeline_ms"))
        o += "\n";
    else
        o += format(",\n"
                "          pipeline %.1f ms (median %.1f of %d), first dispatch %.2f ms device / %.2f ms host "
                "(%d px of the image);\n"
                "          at 64^2 a fresh pipeline's first dispatch %.2f ms, later ones %.2f ms\n",
                num(su["pipeline_ms"]), num(su["pipeline_ms_median"]),
                su["pipelines_created"].get<int>(), num(su["first_dispatch_device_ms"]),
                num(su["first_dispatch_host_ms"]), su["first_dispatch_pixels"].get<int>(),
                num(su["first_dispatch_device_ms_64"]), num(su["steady_dispatch_device_ms_64"]));
    const auto& b = j["bvh"];
    o += format("BVH: %.1f ms (%.1f ms/Mtri), %d nodes, %d leaves, depth %d, SAH cost %.2f, %.2f MiB\n",
                num(b["build_ms"]), num(b["build_ms_per_mtri"]), b["nodes"].get<int>(), b["leaves"].get<int>(),
                b["max_depth"].get<int>(), num(b["sah_cost"]), num(b["bytes"]) / 1048576.0);
    o += format("     four-wide: collapsed in %.1f ms, %d nodes, depth %d, SAH cost %.2f, %.2f MiB\n",
                num(b["wide_collapse_ms"]), b["wide_nodes"].get<int>(), b["wide_depth"].get<int>(),
                num(b["wide_sah_cost"]), num(b["wide_bytes"]) / 1048576.0);
    o += "memory: " + memoryText(j["memory"]) + "\n";
    const auto& t = j["traversal"];
    o += format("traversal (%dx%d, BVH%d, stack in %s, %s reads, %s, median of %d):\n",
                t["image"][0].get<int>(), t["image"][1].get<int>(), t["bvh_width"].get<int>(),
                t["bvh_stack"].get<std::string>().c_str(), t["reads"].get<std::string>().c_str(),
                t["work_queue"].get<bool>() ? "work queue" : "one ray per invocation", t["reps"].get<int>());
    for (const char* set : {"primary", "diffuse", "occlusion"}) {
        const auto& r = t["rays"][set];
        const bool occl = r.contains("occluded");
        const double n = std::max(1.0, num(r["rays"]));
        o += format("  %-10s %9zu rays  %6.1f%% %-9s %8.3f Mrays/s\n", set, r["rays"].get<std::size_t>(),
                    100.0 * num(occl ? r["occluded"] : r["hits"]) / n, occl ? "occluded" : "hit",
                    num(r["mrays_per_s"]));
    }
    if (!j.contains("path_tracing")) return o;
    const auto& p = j["path_tracing"];
    o += format("path tracing (%dx%d, %d spp, max depth %d, %s, seed %d):\n", p["image"][0].get<int>(),
                p["image"][1].get<int>(), p["spp"].get<int>(), p["max_depth"].get<int>(),
                p["sampler"].get<std::string>().c_str(), p["seed"].get<int>());
    o += format("  %.3f Msamples/s, %.3f Mrays/s (%.3g closest + %.3g shadow rays), %.2f s device\n",
                num(p["msamples_per_s"]), num(p["mrays_per_s"]), num(p["closest_rays"]), num(p["shadow_rays"]),
                num(p["device_s"]));
    o += format("  mean path length %.3f segments, %.3f shadow rays per sample\n", num(p["mean_path_length"]),
                num(p["shadow_rays_per_sample"]));
    if (p["relmse"].is_number())
        o += format("  relMSE %.4g against %s (efficiency 1/(relMSE s) %.4g)\n", num(p["relmse"]),
                    p["reference"].get<std::string>().c_str(), num(p["efficiency"]));
    else
        o += "  relMSE: no --reference given\n";
    const auto& rc = p["ray_counting"];
    o += format("  ray counters cost %+.1f%% (%dx%d, %d spp, median of %d alternated pairs)\n",
                num(rc["overhead_percent"]), rc["image"][0].get<int>(), rc["image"][1].get<int>(),
                rc["spp"].get<int>(), rc["pairs"].get<int>());
    const auto& d = j["dispatch"];
    o += format("dispatch throughput (one sample per dispatch, tiles of %d^2, at most %.0f samples per size):\n",
                d["tile"].get<int>(), num(d["sample_budget_per_size"]));
    o += "  size   spp  dispatches  per submit  device ms/dispatch  host ms/submit  dispatches/s  Msamples/s\n";
    for (const auto& r : d["sizes"])
        o += format("  %4d %5d %11d %11.1f %19.3f %15.3f %13.1f %11.3f\n", r["size"].get<int>(), r["spp"].get<int>(),
                    r["dispatches"].get<int>(), num(r["dispatches_per_submission"]), num(r["device_ms_per_dispatch"]),
                    num(r["host_ms_per_submit"]), num(r["dispatches_per_s"]), num(r["msamples_per_s"]));
    const auto& bt = d["batching"];
    o += format("  dispatches recorded per submission at %d^2, %d spp:\n", bt["size"].get<int>(), bt["spp"].get<int>());
    for (const auto& r : bt["runs"])
        o += format("    %3d per submit: %4d submissions, host %.3f ms/dispatch, device %.3f ms/dispatch, "
                    "%.1f dispatches/s; host beyond device %.3f ms/submit\n",
                    r["recorded_per_submission"].get<int>(), r["submissions"].get<int>(),
                    num(r["host_ms_per_dispatch"]), num(r["device_ms_per_dispatch"]), num(r["dispatches_per_s"]),
                    num(r["host_overhead_ms_per_submit"]));
    o += format("    most vs one per submit: %.3fx dispatches/s\n", num(bt["speedup_most_vs_one"]));
    return o;
}

nlohmann::ordered_json bvhJson(const GpuScene& gpu, double packMs) {
    return {{"build_ms", gpu.bvh.buildMs},
            {"build_ms_per_mtri", gpu.bvh.buildMs / (double(gpu.triangleCount) * 1e-6)},
            {"pack_ms", packMs},
            {"nodes", gpu.bvh.nodes},
            {"leaves", gpu.bvh.leaves},
            {"max_depth", gpu.bvh.maxDepth},
            {"sah_cost", gpu.bvh.sahCost},
            {"bytes", gpu.bvh.bytes},
            {"wide_nodes", gpu.wide.size()},
            {"wide_depth", gpu.wideDepth},
            {"wide_sah_cost", gpu.wideSahCost},
            {"wide_collapse_ms", gpu.wideBuildMs},
            {"wide_bytes", gpu.wide.size() * sizeof(gpu::BvhNode4)}};
}

}  // namespace

int runBench(const BenchCommand& cmd) {
    if (!cmd.json.empty()) checkOutputPath(cmd.json);
    // The reference first: a mismatch is an error before any work.
    RgbImage reference;
    if (!cmd.reference.empty()) {
        reference = readReference(cmd.reference);
        if (reference.width != cmd.settings.width || reference.height != cmd.settings.height)
            fail(cmd.reference, "reference is " + std::to_string(reference.width) + "x" +
                                    std::to_string(reference.height) + ", bench renders " +
                                    std::to_string(cmd.settings.width) + "x" + std::to_string(cmd.settings.height) +
                                    " (set --width and --height to match)");
    }
    SceneRequest request = sceneRequest(cmd.settings);
    request.file = cmd.scene;
    request.env = cmd.env;
    request.load.requireEmitter = false;  // traversal needs no light
    request.load.variant = cmd.variant;
    if (!cmd.restrictPaths.empty()) request.load.restrictPaths = restrictRoot(cmd.restrictPaths);
    request.load.instancing = cmd.instancing;
    request.textureMaxSize = cmd.textureMaxSize;
    request.camera.reset();  // framed below, as the peer frames (the loaded triangles' bounds)
    request.consume = Consume::Scene;  // the packed scene is uploaded by each section
    auto t0 = std::chrono::steady_clock::now();
    Scene scene = loadScene(request);
    const std::string environment = scene.environment.enabled ? scene.environment.source : "";
    const double loadMs = msSince(t0);
    if (scene.triangles.empty()) fail(cmd.scene, "no triangles to trace");
    const Framing fr = frame(scene, cmd);

    HostScene host = prepareScene(request, std::move(scene));
    const double packMs = host.packMs;  // the BVH build and the packing
    const GpuScene& gpu = host.gpu;
    const auto t1 = std::chrono::steady_clock::now();
    vk::Context ctx({cmd.device, cmd.validation});
    const double deviceMs = msSince(t1);

    Upload upload;
    nlohmann::ordered_json traversal = traversalSection(ctx, request, gpu, fr, cmd, upload);
    auto checkValidation = [&] {
        if (ctx.validation && vk::validationMessageCount() > 0)
            throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                                  " Vulkan validation message(s) during the bench");
    };
    nlohmann::ordered_json j;
    j["scene"] = cmd.scene;
    j["device"] = ctx.info.name;
    j["device_type"] = ctx.info.type;
    j["driver"] = ctx.info.driver;
    j["triangles"] = gpu.triangleCount;
    j["camera"] = fr.description;
    j["features"] = gpu.features.names();
    if (!environment.empty()) j["environment"] = environment;
    auto finish = [&] {
        j["bvh"] = bvhJson(gpu, packMs);
        j["traversal"] = traversal;
        j["memory"] = memoryJson(upload.packedBytes, upload.deviceBytes);
        if (!cmd.json.empty()) writeTextAtomically(cmd.json, j.dump(2) + "\n");
        std::fputs(benchText(j).c_str(), stdout);
        return 0;
    };
    if (cmd.only == "traversal") {
        checkValidation();
        j["only"] = cmd.only;
        j["startup"] = {{"load_ms", loadMs}, {"pack_ms", packMs}, {"bvh_build_ms", gpu.bvh.buildMs},
                        {"device_init_ms", deviceMs}, {"upload_ms", upload.ms}};
        return finish();
    }
    PipelineTimes pipelines;
    nlohmann::ordered_json path =
        benchPathTracing(ctx, gpu, fr.camera, cmd, cmd.reference.empty() ? nullptr : &reference, pipelines);
    nlohmann::ordered_json dispatch = benchDispatch(ctx, gpu, fr.camera, cmd, pipelines);
    checkValidation();

    std::vector<double> sorted = pipelines;
    std::sort(sorted.begin(), sorted.end());
    const auto& steady = dispatch["sizes"][0];
    j["quick"] = cmd.quick;
    j["startup"] = {{"load_ms", loadMs},
                    {"pack_ms", packMs},   // BVH build included
                    {"bvh_build_ms", gpu.bvh.buildMs},
                    {"device_init_ms", deviceMs},
                    {"upload_ms", path["upload_ms"]},
                    {"pipeline_ms", pipelines.front()},
                    {"pipeline_ms_median", sorted[sorted.size() / 2]},
                    {"pipelines_created", pipelines.size()},
                    // A fresh pipeline's first dispatch against the same dispatch later: 64^2, one sample.
                    {"first_dispatch_device_ms_64", steady["warm_up_device_ms"]},
                    {"steady_dispatch_device_ms_64", steady["device_ms_per_dispatch"]},
                    // The process's first path-tracing dispatch (a tile of the bench image).
                    {"first_dispatch_device_ms", path["warm_up_device_ms"]},
                    {"first_dispatch_host_ms", path["warm_up_host_ms"]},
                    {"first_dispatch_pixels", path["warm_up_pixels"]}};
    j["path_tracing"] = path;
    j["dispatch"] = dispatch;
    return finish();
}

}  // namespace strata
