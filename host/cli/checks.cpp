#include "cli/checks.h"

#include <initializer_list>
#include <string>

#include "image/image_io.h"
#include "render/sampler_kind.h"
#include "render/state.h"
#include "util/error.h"
#include "util/files.h"

namespace strata::cli {
namespace {

// --frames excludes --shutter and sets the shutter per frame; --fps and
// --shutter-angle need it; every output it writes names the frame.
void checkFrameFlags(const Parsed& parsed, const RenderCommand& cmd) {
    if (!cmd.frames.enabled) {
        for (const char* f : {"--fps", "--shutter-angle"})
            if (parsed.has(f)) badFlag(std::string(f) + " needs --frames");
        return;
    }
    if (parsed.has("--shutter")) badFlag("--frames sets each frame's shutter (--fps, --shutter-angle); leave out --shutter");
    for (const std::string& out : cmd.outputs)
        if (out.find('#') == std::string::npos)
            badFlag("with --frames each output names its frame by a run of '#', e.g. out_####.exr; got '" + out + "'");
    if (!cmd.statsJson.empty() && cmd.statsJson.find('#') == std::string::npos)
        badFlag("with --frames --stats-json names its frame by a run of '#', e.g. stats_####.json");
}

// .state outputs, --checkpoint-every, --resume and --shard: one render, not
// a sequence of frames; a checkpoint needs a state to write; a shard needs
// a whole batch of samples.
void checkStateFlags(const RenderCommand& cmd) {
    if (cmd.checkpointEvery > 0.0 && cmd.states.empty())
        badFlag("--checkpoint-every rewrites the .state outputs: add -o FILE.state");
    if (cmd.frames.enabled && (!cmd.states.empty() || !cmd.resume.empty() || cmd.shards))
        badFlag("--frames renders frame by frame: .state outputs, --resume and --shard are for one image");
    if (!cmd.resume.empty() && lowerExtension(cmd.resume) != ".state")
        badFlag("--resume takes a .state file, got '" + cmd.resume + "'");
    if (cmd.shards) shardRange(cmd.settings.spp, cmd.shard, cmd.shards, cmd.tuning.maxBatch);
}

// A report or table written as text: one of the `allowed` extensions.
void checkTextOutput(const std::string& path, std::initializer_list<const char*> allowed, const std::string& what) {
    if (path.empty()) return;
    const std::string ext = lowerExtension(path);
    for (const char* a : allowed)
        if (ext == a) return;
    fail(path, what);
}

}  // namespace

void checkViewFlags(const ViewOptions& view) {
    if (view.lookFrom.has_value() != view.lookAt.has_value())
        badFlag(view.lookFrom ? "--look-from needs --look-at" : "--look-at needs --look-from");
    if (view.up && !view.lookFrom) badFlag("--up needs --look-from and --look-at");
}

void checkLensFlags(const RenderSettings& s) {
    if (s.apertureBlades == 1 || s.apertureBlades == 2)
        badFlag("--aperture-blades must be 0 (round) or 3 or more, got " + std::to_string(s.apertureBlades));
    if (!s.animation.empty() && !s.shutter) badFlag("--animation needs --shutter (or --frames)");
    if (s.cameraEffects() && s.integrator == IntegratorKind::Wavefront)
        badFlag("--lens-radius and a --shutter interval need the megakernel integrator; the wavefront integrator "
                "has no lens and no time");
}

void checkEnvFlags(const Parsed& parsed, const EnvironmentOptions& env) {
    if (!env.file.empty() && env.hasColor) badFlag("--env and --env-color exclude each other");
    for (const std::string& a : parsed.given)
        if ((a == "--env-intensity" || a == "--env-rotate") && !env.given())
            badFlag(a + " needs --env or --env-color");
}

void checkSamplingFlags(const RenderSettings& s, std::uint32_t cap) {
    if (s.lightCandidates > 0 && s.lightSampler == LightSampler::Power)
        badFlag("--light-candidates resamples the light tree's choices: not with --light-sampler power");
    if (s.minSpp > 0 && !s.adaptive()) badFlag("--min-spp needs --noise-threshold");
    if (!s.adaptive()) return;
    if (s.minSpp > cap)
        badFlag("--min-spp " + std::to_string(s.minSpp) + " is above the cap --spp " + std::to_string(cap));
}

void checkRenderFlags(const Parsed& parsed, const RenderCommand& cmd) {
    checkEnvFlags(parsed, cmd.env);
    checkViewFlags(cmd.view);
    checkFrameFlags(parsed, cmd);
    checkLensFlags(cmd.settings);
    checkSamplingFlags(cmd.settings, cmd.settings.spp);
    if (cmd.settings.adaptive() && cmd.shards > 1)
        badFlag("--shard and --noise-threshold exclude each other: a shard's blocks would stop on its own samples, "
                "and the merge would not be the render's; render adaptively in one job (--checkpoint-every "
                "survives a preemption)");
    checkStateFlags(cmd);
    if (cmd.settings.aov && cmd.settings.integrator == IntegratorKind::Wavefront)
        badFlag(std::string(cmd.denoise ? "--denoise" : "--aov") +
                " needs the megakernel integrator (--integrator megakernel); the wavefront integrator keeps no "
                "AOVs");
    for (const std::string& out : cmd.outputs) outputFormat(out);
    checkSamplerSettings(samplerByKind(cmd.settings.sampler), cmd.settings.spp, cmd.settings.width,
                         cmd.settings.height);
}

void checkConvergeFlags(const ConvergeCommand& cmd) {
    checkTextOutput(cmd.report, {".csv", ".json"}, "converge report must be .csv or .json");
    if (!cmd.plot.empty()) outputFormat(cmd.plot);
    // Each spp against the sampler (the image's size comes from the
    // reference; its part of the check is the render's). --sampler all
    // measures the samplers that suit them all.
    if (!cmd.allSamplers)
        for (std::uint32_t spp : cmd.spp) checkSamplerSettings(samplerByKind(cmd.settings.sampler), spp, 1, 1);
    // With a threshold, each listed spp is a cap.
    checkSamplingFlags(cmd.settings, cmd.spp.empty() ? 0u : cmd.spp.back());
}

void checkEdgesFlags(const EdgesCommand& cmd) {
    checkTextOutput(cmd.table, {".csv"}, "edges table must be .csv");
    if (!cmd.plot.empty()) outputFormat(cmd.plot);
    checkEdgeSettings(cmd.settings);
}

void checkBenchFlags(const BenchCommand& cmd) {
    checkTextOutput(cmd.json, {".json"}, "bench report must be .json");
    checkSamplingFlags(cmd.settings, cmd.settings.spp);
}

void checkCompareFlags(const CompareArgs& args) {
    checkTextOutput(args.json, {".json"}, "compare report must be .json");
}

void checkDenoiseFlags(const DenoiseCommand& cmd) {
    for (const std::string& out : cmd.outputs) outputFormat(out);
}

void checkMergeFlags(const MergeCommand& cmd) {
    for (const std::string& out : cmd.outputs) outputFormat(out);
}

}  // namespace strata::cli
