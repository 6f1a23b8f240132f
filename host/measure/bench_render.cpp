#include "measure/bench_render.h"

#include <algorithm>
#include <cmath>

#include "image/metrics.h"
#include "render/renderer.h"
#include "render/sampler_kind.h"
#include "stages/stages.h"

namespace strata {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

RenderSettings settingsFor(const BenchCommand& cmd, int width, int height, std::uint32_t spp) {
    RenderSettings s = cmd.settings;
    s.width = width;
    s.height = height;
    s.spp = spp;
    return s;
}

// Each render warms its pipeline up apart and creates it anew (its creation
// is timed: start-up).
RenderTuning benchTuning() {
    RenderTuning t;
    t.warmUp = true;
    t.reusePipeline = false;
    return t;
}

// Uploads the scene and renders it, as `strata render` does.
RenderResult timedRender(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                         const RenderSettings& s, const RenderTuning& t, PipelineTimes& pipelines) {
    checkSamplerSettings(samplerByKind(s.sampler), s.spp, s.width, s.height);
    SceneRequest request = sceneRequest(s, t);
    request.consume = Consume::Scene;  // uploaded again by the next render
    const DeviceScene dev = uploadPrepared(ctx, request, scene);
    RenderResult r = render(ctx, dev, camera, s, t);
    pipelines.push_back(r.pipelineMs);
    return r;
}

double perSecond(double count, double seconds) { return seconds > 0.0 ? count / seconds : 0.0; }

// The figures of one render that the dispatch section reports.
nlohmann::ordered_json dispatchFigures(const RenderResult& r) {
    const double dispatches = static_cast<double>(r.dispatches);
    const double submissions = std::max(1u, r.submissions);
    return {{"dispatches", r.dispatches},
            {"submissions", r.submissions},
            {"dispatches_per_submission", dispatches / submissions},
            {"device_s", r.deviceSeconds},
            {"wall_s", r.seconds},
            {"device_ms_per_dispatch", 1e3 * r.deviceSeconds / std::max(1.0, dispatches)},
            {"host_ms_per_submit", 1e3 * r.hostSubmitSeconds / submissions},
            {"host_overhead_ms_per_submit", 1e3 * (r.hostSubmitSeconds - r.deviceSeconds) / submissions},
            {"dispatches_per_s", perSecond(dispatches, r.seconds)},
            {"msamples_per_s", perSecond(static_cast<double>(r.film.pixels()) * r.spp * 1e-6, r.deviceSeconds)},
            {"warm_up_device_ms", 1e3 * r.warmUpDeviceSeconds}};
}

}  // namespace

nlohmann::ordered_json benchPathTracing(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                                        const BenchCommand& cmd, const RgbImage* reference,
                                        PipelineTimes& pipelines) {
    const RenderSettings s = settingsFor(cmd, cmd.settings.width, cmd.settings.height, cmd.settings.spp);
    const RenderResult r = timedRender(ctx, scene, camera, s, benchTuning(), pipelines);
    const double samples = static_cast<double>(r.film.pixels()) * r.spp;
    const double rays = static_cast<double>(r.closestRays + r.shadowRays);
    nlohmann::ordered_json j;
    j["image"] = {s.width, s.height};
    j["spp"] = r.spp;
    j["seed"] = s.seed;
    j["max_depth"] = s.maxDepth;
    j["sampler"] = samplerByKind(s.sampler).name;
    j["samples"] = static_cast<std::uint64_t>(samples);
    j["submissions"] = r.submissions;
    j["device_s"] = r.deviceSeconds;
    j["wall_s"] = r.seconds;
    j["msamples_per_s"] = perSecond(samples * 1e-6, r.deviceSeconds);
    j["closest_rays"] = r.closestRays;
    j["shadow_rays"] = r.shadowRays;
    j["rays"] = r.closestRays + r.shadowRays;
    j["mrays_per_s"] = perSecond(rays * 1e-6, r.deviceSeconds);
    // Every closest-hit ray is one segment of a path, the last one included
    // (it escapes, or ends at the depth limit or in roulette).
    j["mean_path_length"] = samples > 0 ? static_cast<double>(r.closestRays) / samples : 0.0;
    j["shadow_rays_per_sample"] = samples > 0 ? static_cast<double>(r.shadowRays) / samples : 0.0;
    j["non_finite"] = r.nonFinite;
    j["warm_up_device_ms"] = 1e3 * r.warmUpDeviceSeconds;
    j["warm_up_host_ms"] = 1e3 * r.warmUpHostSeconds;
    j["warm_up_pixels"] = r.warmUpPixels;
    j["upload_ms"] = r.uploadMs;
    if (reference) {
        const std::vector<float> image = r.film.mean();
        const ErrorMetrics m = compareImages(image.data(), reference->rgb.data(), image.size());
        j["reference"] = cmd.reference;
        j["relmse"] = m.relMse;
        j["rmse"] = m.rmse;
        // 1 / (relMSE x device seconds): speed and error in one figure (docs/benchmarks.md).
        j["efficiency"] = m.relMse > 0.0 && r.deviceSeconds > 0.0 ? nlohmann::ordered_json(1.0 / (m.relMse * r.deviceSeconds))
                                                                  : nlohmann::ordered_json(nullptr);
    } else {
        j["reference"] = nullptr;
        j["relmse"] = nullptr;
    }

    // The cost of counting rays: the same render with SPEC_COUNT_RAYS on and
    // off, alternated so that drifting machine load falls on both alike.
    const int side = cmd.quick ? 32 : 256;
    const std::uint32_t spp = cmd.quick ? 1 : 2;
    const int pairs = cmd.quick ? 1 : 3;
    std::vector<double> on, off;
    for (int k = 0; k < pairs; ++k)
        for (bool count : {true, false}) {
            RenderTuning c = benchTuning();
            c.countRays = count;
            (count ? on : off).push_back(
                timedRender(ctx, scene, camera, settingsFor(cmd, side, side, spp), c, pipelines).deviceSeconds);
        }
    const double mOn = median(on), mOff = median(off);
    j["ray_counting"] = {{"image", {side, side}},
                         {"spp", spp},
                         {"pairs", pairs},
                         {"device_s_counting", mOn},
                         {"device_s_not_counting", mOff},
                         {"overhead_percent", mOff > 0.0 ? 100.0 * (mOn / mOff - 1.0) : 0.0}};
    return j;
}

nlohmann::ordered_json benchDispatch(const vk::Context& ctx, const GpuScene& scene, const Camera& camera,
                                     const BenchCommand& cmd, PipelineTimes& pipelines) {
    // Samples per size: enough for many dispatches at the small sizes, one
    // sample (the least there is) at the large ones.
    const double budget = cmd.quick ? 8192.0 : 262144.0;
    const std::vector<int> sizes = cmd.quick ? std::vector<int>{64, 128}
                                             : std::vector<int>{64, 128, 256, 512, 1024, 2048};
    nlohmann::ordered_json j;
    const RenderTuning defaults;
    j["sample_budget_per_size"] = budget;
    j["tile"] = defaults.tileSize;
    j["submission_target_s"] = defaults.submitSeconds;
    j["samples_per_dispatch"] = 1;
    // One sample a dispatch (the megakernel otherwise runs a submission's
    // samples in one): what is timed is a dispatch's cost.
    RenderTuning oneEach = benchTuning();
    oneEach.samplesPerDispatch = 1;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (int size : sizes) {
        const double pixels = static_cast<double>(size) * size;
        const auto spp = static_cast<std::uint32_t>(std::max(1.0, std::floor(budget / pixels)));
        const RenderResult r =
            timedRender(ctx, scene, camera, settingsFor(cmd, size, size, spp), oneEach, pipelines);
        nlohmann::ordered_json row = {{"size", size}, {"spp", r.spp},
                                      {"dispatches_per_sample", r.spp ? r.dispatches / r.spp : 0}};
        row.update(dispatchFigures(r));
        rows.push_back(row);
    }
    j["sizes"] = rows;

    // Several one-sample dispatches recorded per command buffer, at 64^2.
    const int size = 64;
    const std::vector<std::uint32_t> perSubmit = cmd.quick ? std::vector<std::uint32_t>{1, 4, 16}
                                                           : std::vector<std::uint32_t>{1, 8, 64};
    const std::uint32_t spp = cmd.quick ? 16 : 128;
    nlohmann::ordered_json runs = nlohmann::ordered_json::array();
    double first = 0.0, last = 0.0;
    for (std::uint32_t n : perSubmit) {
        RenderTuning t = oneEach;
        t.fixedBatch = n;
        const RenderResult r = timedRender(ctx, scene, camera, settingsFor(cmd, size, size, spp), t, pipelines);
        nlohmann::ordered_json run = {{"recorded_per_submission", n}};
        run.update(dispatchFigures(r));
        run["host_ms_per_dispatch"] = 1e3 * r.hostSubmitSeconds / std::max<std::uint64_t>(1, r.dispatches);
        runs.push_back(run);
        (n == perSubmit.front() ? first : last) = perSecond(static_cast<double>(r.dispatches), r.seconds);
    }
    j["batching"] = {{"size", size},
                     {"spp", spp},
                     {"runs", runs},
                     {"speedup_most_vs_one", first > 0.0 ? last / first : 0.0}};
    return j;
}

}  // namespace strata
