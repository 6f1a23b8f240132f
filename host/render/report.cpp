#include "render/report.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "render/sampler_kind.h"
#include "spirv/cache.h"
#include "upload/device_scene.h"
#include "util/interrupt.h"
#include "util/memory.h"
#include "vk/buffer.h"

namespace strata {

nlohmann::json statsJson(const StatsInput& in) {
    nlohmann::json j;
    const auto& dev = in.ctx->info;
    j["device"] = {{"index", dev.index}, {"name", dev.name}, {"type", dev.type},
                   {"driver", dev.driver}, {"api_version", dev.apiVersion}};
    std::size_t emissiveTriangles = 0;
    for (const auto& e : in.gpu->emitters) emissiveTriangles += e.kind == gpu::kLightTriangle;
    j["scene"] = {{"file", in.scene->path},
                  {"triangles", in.gpu->triangleCount},
                  {"materials", in.scene->materials.size()},
                  {"emissive_triangles", emissiveTriangles},
                  {"dropped_zero_area_emitters", in.scene->droppedEmitters},
                  {"punctual_lights", in.scene->lights.size()},
                  {"environment", in.scene->environment.enabled ? in.scene->environment.source : ""},
                  {"cameras", in.scene->cameras.size()},
                  {"features", in.gpu->features.names()},
                  {"variants", in.scene->variants},
                  {"variant", in.scene->variant}};
    if (in.gpu->placementCount > 0) {
        const BvhStats& t = in.gpu->top;
        j["instancing"] = {{"placements", in.gpu->placementCount},   {"shared_meshes", in.gpu->sharedMeshCount},
                           {"stored_triangles", in.gpu->triangleCount}, {"placed_triangles", in.gpu->placedTriangles},
                           {"top_nodes", t.nodes},                    {"top_max_depth", t.maxDepth},
                           {"top_build_ms", t.buildMs}};
    }
    if (!in.gpu->lightTree.empty())
        j["light_tree"] = {{"nodes", in.gpu->lightTree.size()},
                           {"max_depth", in.gpu->lightTreeDepth},
                           {"build_ms", in.gpu->lightTreeMs},
                           {"tree_probability", in.gpu->lightTreeProb},
                           {"clusters", in.gpu->lightClusters},
                           {"candidates", in.settings ? in.settings->lightCandidateCount() : 1u}};
    if (!in.gpu->images.empty()) {
        nlohmann::json list = nlohmann::json::array();
        std::uint64_t bytes = 0;
        for (const PackedImage& p : in.gpu->images) {
            bytes += p.bytes;
            list.push_back({{"name", p.name},           {"width", p.width},   {"height", p.height},
                            {"file_width", p.fileWidth}, {"file_height", p.fileHeight}, {"bytes", p.bytes}});
        }
        j["textures"] = {{"images", in.gpu->images.size()}, {"bytes", bytes}, {"list", list}, {"mip_ms", in.gpu->mipMs}};
    }
    const BvhStats& b = in.gpu->bvh;
    j["bvh"] = {{"nodes", b.nodes},   {"leaves", b.leaves},     {"max_depth", b.maxDepth},
                {"sah_cost", b.sahCost}, {"build_ms", b.buildMs}, {"bytes", b.bytes}};
    const RenderSettings& s = *in.settings;
    const RenderResult& r = *in.result;
    j["startup"] = {{"load_ms", in.loadMs},        {"bvh_build_ms", b.buildMs}, {"pack_ms", in.packMs},
                    {"device_init_ms", in.deviceMs}, {"upload_ms", r.uploadMs}, {"pipeline_ms", r.pipelineMs}};
    // The process's shader modules so far (spirv/cache.h): compiled, or read from the cache.
    const spirv::ShaderCacheStats sc = spirv::shaderCacheStats();
    j["startup"]["shaders_compiled"] = sc.compiled;
    j["startup"]["shaders_cached"] = sc.loaded;
    j["startup"]["shader_compile_ms"] = sc.compileMs;
    j["startup"]["shader_load_ms"] = sc.loadMs;
    j["render"] = {{"width", s.width},
                   {"height", s.height},
                   {"spp_requested", s.spp},
                   {"spp", r.spp},
                   {"interrupted", r.interrupted ? nlohmann::json(signalName(r.interrupted)) : nlohmann::json()},
                   {"seed", s.seed},
                   {"max_depth", s.maxDepth},
                   {"seconds", r.seconds},
                   {"device_seconds", r.deviceSeconds},
                   {"msamples_per_second", r.msamplesPerSecond()},
                   {"mean_spp_rendered", r.film.pixels() ? double(r.samplesTaken) / double(r.film.pixels()) : 0.0},
                   {"submissions", r.submissions},
                   {"dispatches", r.dispatches},
                   {"closest_rays", r.closestRays},
                   {"shadow_rays", r.shadowRays},
                   {"non_finite_samples", r.nonFinite},
                   {"reads", readsName(r.reads)},
                   {"bvh_width", r.bvhWidth},
                   {"bvh_stack", r.bvhStack},
                   {"sampler", samplerByKind(s.sampler).name},
                   {"filter", filterName(s.filter.kind)},
                   {"filter_radius", s.filter.radius}};
    if (s.adaptive()) j["render"]["noise_threshold"] = s.noiseThreshold;
    j["memory"] = memoryJson(r.sceneBytes, r.sceneDeviceBytes);
    j["validation"] = {{"enabled", in.ctx->validation},
                       {"messages", vk::validationMessageCount()}};
    return j;
}

std::string statsText(const nlohmann::json& j) {
    std::ostringstream o;
    const auto& d = j["device"];
    o << "device     " << d["index"].get<int>() << ": " << d["name"].get<std::string>() << " ("
      << d["type"].get<std::string>() << ", " << d["driver"].get<std::string>() << ", Vulkan "
      << d["api_version"].get<std::string>() << ")\n";
    const auto& s = j["scene"];
    std::string features;
    for (const auto& f : s["features"]) features += (features.empty() ? "" : ", ") + f.get<std::string>();
    o << "scene      " << s["file"].get<std::string>() << ": " << s["triangles"] << " triangles, "
      << s["materials"] << " materials, " << s["emissive_triangles"] << " emissive triangles, "
      << s["punctual_lights"] << " punctual lights"
      << (s["environment"].get<std::string>().empty() ? "" : ", environment " + s["environment"].get<std::string>())
      << "\n";
    o << "features   " << (features.empty() ? "none" : features) << "\n";
    if (!s["variants"].empty()) {
        std::string variants;
        for (const auto& v : s["variants"]) variants += (variants.empty() ? "" : ", ") + v.get<std::string>();
        const std::string chosen = s["variant"].get<std::string>();
        o << "variants   " << variants << " (" << (chosen.empty() ? "none chosen" : "rendering " + chosen) << ")\n";
    }
    char line[256];
    if (j.contains("instancing")) {
        const auto& i = j["instancing"];
        std::snprintf(line, sizeof line,
                      "instances  %llu placements of %llu shared meshes and the world's triangles: %llu triangles "
                      "stored, %llu placed; top level %u nodes, max depth %u, build %.1f ms\n",
                      i["placements"].get<unsigned long long>(), i["shared_meshes"].get<unsigned long long>(),
                      i["stored_triangles"].get<unsigned long long>(), i["placed_triangles"].get<unsigned long long>(),
                      i["top_nodes"].get<unsigned>(), i["top_max_depth"].get<unsigned>(), i["top_build_ms"].get<double>());
        o << line;
    }
    if (j.contains("light_tree")) {
        const auto& t = j["light_tree"];
        std::snprintf(line, sizeof line,
                      "lights     light tree of %llu nodes (%llu clusters), max depth %u, build %.1f ms; chosen "
                      "through it with probability %.4g, %u candidates a light sample\n",
                      t["nodes"].get<unsigned long long>(), t["clusters"].get<unsigned long long>(),
                      t["max_depth"].get<unsigned>(), t["build_ms"].get<double>(), t["tree_probability"].get<double>(),
                      t.value("candidates", 1u));
        o << line;
    }
    if (j.contains("textures")) o << "textures   " << texturesText(j["textures"]) << "\n";
    const auto& b = j["bvh"];
    std::snprintf(line, sizeof line,
                  "bvh        %u nodes, %u leaves, max depth %u, SAH cost %.2f, build %.1f ms, %.2f MiB\n",
                  b["nodes"].get<unsigned>(), b["leaves"].get<unsigned>(), b["max_depth"].get<unsigned>(),
                  b["sah_cost"].get<double>(), b["build_ms"].get<double>(),
                  b["bytes"].get<double>() / (1024.0 * 1024.0));
    o << line;
    const auto& su = j["startup"];
    std::snprintf(line, sizeof line, ", shaders %u compiled (%.1f ms) %u cached (%.1f ms), pipeline %.1f ms\n",
                  su["shaders_compiled"].get<unsigned>(), su["shader_compile_ms"].get<double>(),
                  su["shaders_cached"].get<unsigned>(), su["shader_load_ms"].get<double>(),
                  su["pipeline_ms"].get<double>());
    o << "start-up   " << startupText(su) << line;
    const auto& r = j["render"];
    std::snprintf(line, sizeof line,
                  "render     %dx%d, %u spp (of %u), max depth %u, %.3f s (device %.3f s), %.3f Msamples/s, %s reads, BVH%d (stack in %s), %s sampler\n",
                  r["width"].get<int>(), r["height"].get<int>(), r["spp"].get<unsigned>(),
                  r["spp_requested"].get<unsigned>(), r["max_depth"].get<unsigned>(),
                  r["seconds"].get<double>(), r["device_seconds"].get<double>(), r["msamples_per_second"].get<double>(),
                  r["reads"].get<std::string>().c_str(), r["bvh_width"].get<int>(),
                  r["bvh_stack"].get<std::string>().c_str(),
                  r["sampler"].get<std::string>().c_str());
    o << line;
    if (r.contains("noise_threshold")) {
        std::snprintf(line, sizeof line, "adaptive   noise threshold %g: %.1f spp a pixel on average this render\n",
                      r["noise_threshold"].get<double>(), r["mean_spp_rendered"].get<double>());
        o << line;
    }
    if (r.contains("interrupted") && !r["interrupted"].is_null())
        o << "stopped    by " << r["interrupted"].get<std::string>() << " before the samples asked for\n";
    o << "samples    " << r["non_finite_samples"] << " non-finite dropped\n";
    o << "memory     " << memoryText(j["memory"]) << "\n";
    return o.str();
}

nlohmann::json memoryJson(std::uint64_t scenePackedBytes, std::uint64_t sceneDeviceBytes) {
    return {{"scene_packed_bytes", scenePackedBytes},
            {"scene_device_bytes", sceneDeviceBytes},
            {"device_peak_bytes", vk::peakDeviceMemoryBytes()},
            {"host_peak_rss_bytes", peakRssBytes()}};
}

std::string startupText(const nlohmann::json& su) {
    char line[256];
    std::snprintf(line, sizeof line, "load %.1f ms, BVH build %.1f ms (pack %.1f ms in all), device %.1f ms, upload %.1f ms",
                  su["load_ms"].get<double>(), su["bvh_build_ms"].get<double>(), su["pack_ms"].get<double>(),
                  su["device_init_ms"].get<double>(), su["upload_ms"].get<double>());
    return line;
}

std::string texturesText(const nlohmann::json& t) {
    std::vector<nlohmann::json> list(t["list"].begin(), t["list"].end());
    std::stable_sort(list.begin(), list.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
        return a["bytes"].get<std::uint64_t>() > b["bytes"].get<std::uint64_t>();
    });
    std::size_t downsampled = 0;
    for (const auto& i : list)
        downsampled += i["width"] != i["file_width"] || i["height"] != i["file_height"];
    std::ostringstream o;
    o << list.size() << " image(s), " << sizeText(t["bytes"].get<std::uint64_t>()) << " on the device";
    if (downsampled > 0) o << ", " << downsampled << " downsampled";
    constexpr std::size_t kNamed = 4;
    for (std::size_t k = 0; k < std::min(list.size(), kNamed); ++k) {
        const auto& i = list[k];
        o << (k == 0 ? ": " : ", ") << i["name"].get<std::string>()
          << " " << i["width"] << "x" << i["height"] << " (" << sizeText(i["bytes"].get<std::uint64_t>());
        if (i["width"] != i["file_width"] || i["height"] != i["file_height"])
            o << ", " << i["file_width"] << "x" << i["file_height"] << " in the file";
        o << ")";
    }
    if (list.size() > kNamed) o << " and " << list.size() - kNamed << " more";
    if (t.contains("mip_ms") && t["mip_ms"].get<double>() > 0.0) {
        char ms[64];
        std::snprintf(ms, sizeof ms, "; with mip chains (%.1f ms)", t["mip_ms"].get<double>());
        o << ms;
    }
    return o.str();
}

std::string memoryText(const nlohmann::json& m) {
    const double mib = 1.0 / (1024.0 * 1024.0);
    const double packed = m["scene_packed_bytes"].get<double>(), device = m["scene_device_bytes"].get<double>();
    char line[256];
    std::snprintf(line, sizeof line,
                  "scene %.1f MiB packed, %.1f MiB on the device (%.2fx); device peak %.1f MiB; host peak RSS %.1f MiB",
                  packed * mib, device * mib, packed > 0.0 ? device / packed : 0.0,
                  m["device_peak_bytes"].get<double>() * mib, m["host_peak_rss_bytes"].get<double>() * mib);
    return line;
}

}  // namespace strata
