#include "measure/converge.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "denoise/command.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "measure/plot.h"
#include "render/sampler_kind.h"
#include "stages/stages.h"
#include "stats/stats.h"
#include "util/error.h"
#include "util/files.h"
#include "vk/context.h"

namespace strata {
namespace {

std::string csv(const std::vector<ConvergeReport>& runs) {
    std::string out = "sampler,spp,device_seconds,relmse_mean,relmse_std,relmse_trimmed_mean,rmse_mean,efficiency\n";
    char line[256];
    for (const auto& r : runs)
        for (const auto& l : r.levels) {
            std::snprintf(line, sizeof line, "%s,%u,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", r.sampler.c_str(), l.spp,
                          l.seconds, l.relMse, l.relMseStd, l.relMseTrimmed, l.rmse, l.efficiency);
            out += line;
        }
    return out;
}

void plot(const std::string& path, const std::vector<ConvergeReport>& runs, const std::string& sceneName) {
    static const std::array<float, 3> kColors[] = {{0.85f, 0.55f, 0.0f}, {0.8f, 0.2f, 0.1f}, {0.1f, 0.45f, 0.7f},
                                                  {0.8f, 0.4f, 0.7f},  {0.0f, 0.6f, 0.45f}, {0.35f, 0.7f, 0.9f}};
    Panel bySpp{sceneName + ": relMSE vs spp", "samples per pixel", "relMSE", true, true, {}};
    Panel byTime{"relMSE vs device seconds", "device seconds", "relMSE", true, true, {}};
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const ConvergeReport& r = runs[i];
        char label[96];
        std::snprintf(label, sizeof label, "%s (slope %.2f)", r.sampler.c_str(), r.slopeSpp);
        Series a{label, {}, {}, kColors[i % 6]};
        Series b = a;
        std::snprintf(label, sizeof label, "%s (slope %.2f)", r.sampler.c_str(), r.slopeTime);
        b.label = label;
        for (const auto& l : r.levels) {
            a.x.push_back(l.spp), a.y.push_back(l.relMse);
            b.x.push_back(l.seconds), b.y.push_back(l.relMse);
        }
        bySpp.series.push_back(a);
        byTime.series.push_back(b);
    }
    const ConvergeReport& r0 = runs.front();
    const auto& first = r0.levels.front();
    const auto& last = r0.levels.back();
    bySpp.series.push_back({"slope -1", {double(first.spp), double(last.spp)},
                            {first.relMse, first.relMse * first.spp / last.spp}, {0.5f, 0.5f, 0.5f}, true, false});
    byTime.series.push_back({"slope -1", {first.seconds, last.seconds},
                             {first.relMse, first.relMse * first.seconds / last.seconds}, {0.5f, 0.5f, 0.5f}, true, false});
    writeChart(path, {bySpp, byTime});
}

}  // namespace

nlohmann::json ConvergeReport::toJson() const {
    nlohmann::json j;
    j["sampler"] = sampler;
    j["seeds"] = seeds;
    j["relmse_eps"] = eps;
    j["slope_relmse_vs_spp"] = slopeSpp;
    j["slope_relmse_vs_seconds"] = slopeTime;
    j["bias_floor_b2"] = biasFloor;
    j["variance_constant_c"] = varianceConstant;
    j["reference_noise_floor"] = referenceFloor;
    for (const auto& l : levels)
        j["levels"].push_back({{"spp", l.spp},
                               {"device_seconds", l.seconds},
                               {"relmse_mean", l.relMse},
                               {"relmse_std", l.relMseStd},
                               {"relmse_trimmed_mean", l.relMseTrimmed},
                               {"rmse_mean", l.rmse},
                               {"efficiency", l.efficiency}});
    return j;
}

namespace {

// The report of one series of measurements: per level, the seeds' metrics and seconds.
ConvergeReport summarize(const ConvergeCommand& cmd, const std::vector<std::vector<ErrorMetrics>>& metrics,
                         const std::vector<std::vector<double>>& seconds, const RgbImage& ref) {
    ConvergeReport report;
    report.seeds = cmd.seeds;
    std::vector<double> spp, rel, secs;
    for (std::size_t i = 0; i < metrics.size(); ++i) {
        ConvergeLevel l;
        l.spp = cmd.spp[i];
        const double n = static_cast<double>(metrics[i].size());
        for (std::size_t k = 0; k < metrics[i].size(); ++k) {
            l.relMse += metrics[i][k].relMse / n;
            l.relMseTrimmed += metrics[i][k].relMseTrimmed / n;
            l.rmse += metrics[i][k].rmse / n;
            l.seconds += seconds[i][k] / n;
        }
        for (const auto& m : metrics[i]) l.relMseStd += (m.relMse - l.relMse) * (m.relMse - l.relMse);
        l.relMseStd = n > 1 ? std::sqrt(l.relMseStd / (n - 1)) : 0.0;
        l.efficiency = l.relMse > 0 && l.seconds > 0 ? 1.0 / (l.relMse * l.seconds) : 0.0;
        report.eps = metrics[i].front().eps;
        report.levels.push_back(l);
        spp.push_back(l.spp);
        rel.push_back(l.relMse);
        secs.push_back(l.seconds);
    }
    if (metrics.size() >= 2) {
        report.slopeSpp = stats::fitLogLogSlope(spp, rel);
        report.slopeTime = stats::fitLogLogSlope(secs, rel);
        const stats::BiasFit fit = stats::fitBiasFloor(spp, rel);
        report.biasFloor = fit.b2;
        report.varianceConstant = fit.c;
    }
    if (!ref.variance.empty()) {
        double sum = 0.0;
        for (std::size_t i = 0; i < ref.rgb.size(); ++i)
            sum += ref.variance[i] / (static_cast<double>(ref.rgb[i]) * ref.rgb[i] + report.eps);
        report.referenceFloor = sum / static_cast<double>(ref.rgb.size());
    }
    return report;
}

}  // namespace

std::vector<ConvergeReport> measureConvergence(const ConvergeCommand& cmd) {
    if (cmd.spp.empty()) fail(cmd.scene, "converge needs at least one spp value");
    const RgbImage ref = readReference(cmd.reference);
    RenderSettings s = cmd.settings;
    s.width = ref.width;
    s.height = ref.height;
    s.spp = cmd.spp.back();
    s.progress = false;
    s.aov = cmd.denoise;
    SceneRequest request = sceneRequest(s);
    request.file = cmd.scene;
    request.env = cmd.env;
    request.load.variant = cmd.variant;
    if (!cmd.restrictPaths.empty()) request.load.restrictPaths = restrictRoot(cmd.restrictPaths);
    request.load.instancing = cmd.instancing;
    request.textureMaxSize = cmd.textureMaxSize;
    request.camera->view = cmd.view;
    request.consume = Consume::None;
    const HostScene host = prepareScene(request);
    const Camera& camera = host.camera;
    vk::Context ctx({cmd.device, cmd.validation});
    const DeviceScene dev = uploadPrepared(ctx, request, host.gpu);
    const std::size_t levels = cmd.spp.size();
    // [0]: as rendered, [1]: denoised (cmd.denoise).
    std::vector<std::vector<ErrorMetrics>> metrics[2] = {std::vector<std::vector<ErrorMetrics>>(levels),
                                                         std::vector<std::vector<ErrorMetrics>>(levels)};
    std::vector<std::vector<double>> seconds[2] = {std::vector<std::vector<double>>(levels),
                                                   std::vector<std::vector<double>>(levels)};
    // Samplers whose prefixes are valid samplings (independent, Sobol) are
    // measured at checkpoints of one render per seed; the grid samplers
    // stratify for a given total spp, so each level is a render of its own.
    const bool prefixes = samplerByKind(s.sampler).prefixesAreSamplings;
    for (std::uint32_t k = 0; k < cmd.seeds; ++k) {
        s.seed = cmd.settings.seed + k;
        std::size_t level = 0;
        auto measure = [&](const RenderResult& r) {
            const std::vector<float> mean = r.film.mean();
            metrics[0][level].push_back(compareImages(mean.data(), ref.rgb.data(), mean.size()));
            seconds[0][level].push_back(r.deviceSeconds);
            if (cmd.denoise) {
                const DenoiseResult d = denoise(ctx, denoiseInput(aovImages(r.film)), cmd.method);
                metrics[1][level].push_back(compareImages(d.rgb.data(), ref.rgb.data(), d.rgb.size()));
                seconds[1][level].push_back(r.deviceSeconds + d.deviceSeconds);
            }
            ++level;
        };
        // The first render dispatches once before its timed loop (measured
        // apart, cleared: the same image): lavapipe compiles a pipeline's
        // code on its first dispatch, which a cold shader cache made part of
        // the first seed's device seconds.
        RenderTuning tuning;
        tuning.warmUp = k == 0;
        if (prefixes) {
            render(ctx, dev, camera, s, tuning, Checkpoints{cmd.spp, measure});
        } else {
            for (std::uint32_t spp : cmd.spp) {
                RenderSettings one = s;
                one.spp = spp;
                measure(render(ctx, dev, camera, one, tuning));
                tuning.warmUp = false;
            }
        }
        if (!cmd.quiet) std::fprintf(stderr, "strata: converge: seed %u of %u done\n", k + 1, cmd.seeds);
    }

    std::vector<ConvergeReport> reports{summarize(cmd, metrics[0], seconds[0], ref)};
    reports[0].sampler = samplerByKind(s.sampler).name;
    if (cmd.denoise) {
        reports.push_back(summarize(cmd, metrics[1], seconds[1], ref));
        reports[1].sampler = reports[0].sampler + "+" + denoiseMethodName(cmd.method);
    }
    return reports;
}

int runConverge(const ConvergeCommand& cmd) {
    checkOutputPath(cmd.report);
    if (!cmd.plot.empty()) checkOutputPath(cmd.plot);
    std::vector<std::uint32_t> kinds;
    if (cmd.allSamplers) {
        for (const auto& info : samplers()) {
            bool suits = true;
            for (std::uint32_t spp : cmd.spp) {
                try {
                    checkSamplerSettings(info, spp, 1, 1);
                } catch (const Error&) {
                    suits = false;
                }
            }
            if (suits) kinds.push_back(info.kind);
            else if (!cmd.quiet)
                std::fprintf(stderr, "strata: converge: %s skipped (it does not suit every --spp value)\n", info.name);
        }
    } else {
        kinds.push_back(cmd.settings.sampler);
    }
    std::vector<ConvergeReport> runs;
    for (std::uint32_t kind : kinds) {
        ConvergeCommand one = cmd;
        one.settings.sampler = kind;
        for (ConvergeReport& r : measureConvergence(one)) runs.push_back(std::move(r));
    }
    if (!cmd.plot.empty()) plot(cmd.plot, runs, std::filesystem::path(cmd.scene).stem().string());
    nlohmann::json j;
    for (const auto& r : runs) j["runs"].push_back(r.toJson());
    writeTextAtomically(cmd.report, lowerExtension(cmd.report) == ".csv" ? csv(runs) : j.dump(2) + "\n");
    std::printf("%s", csv(runs).c_str());
    for (const auto& r : runs)
        std::printf("%s: slope relMSE vs spp %.3f, vs device seconds %.3f; bias floor b^2 %.3g (c %.3g); "
                    "reference noise floor %.3g; relMSE eps %g\n",
                    r.sampler.c_str(), r.slopeSpp, r.slopeTime, r.biasFloor, r.varianceConstant,
                    r.referenceFloor, r.eps);
    return 0;
}

}  // namespace strata
