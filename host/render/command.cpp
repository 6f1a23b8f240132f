#include "render/command.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>

#include "denoise/command.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "render/sampler_kind.h"
#include "render/report.h"
#include "stages/stages.h"
#include "util/error.h"
#include "util/files.h"
#include "util/interrupt.h"
#include "vk/check.h"
#include "vk/context.h"

namespace strata {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A scene on the device (through the stages of stages/stages.h), and what a
// frame of --frames needs to pose it again: the request, the host Scene
// (its triangles released, its placements kept), the BVH's bottom levels.
struct Loaded {
    SceneRequest request;
    HostScene host;
    DeviceScene dev;
    std::string sceneHash;  // sceneContentHash, with states
    double deviceMs = 0.0;
};

bool usesStates(const RenderCommand& cmd) { return !cmd.states.empty() || !cmd.resume.empty(); }

void checkResumable(const RenderCommand& cmd, const RenderState& st, const StateInfo& here);


// Below this the loader's lower bound of the flattened triangles' device
// memory is not worth a Vulkan instance to read the device's (any device
// has more; the upload checks the whole render).
constexpr std::uint64_t kDeviceProbeBytes = std::uint64_t(256) << 20;

// The device's memory for the loader's early check (LoadOptions::
// deviceMemory): the open device's, else read without opening it where the
// scene needs more than kDeviceProbeBytes; a lowered limit (tests) wins.
// Nothing known when no device is found (opening it says why).
void setDeviceBudget(const RenderCommand& cmd, const vk::Context* ctx, SceneRequest& r) {
    const std::uint64_t lowered = r.limits.memory;
    const int index = cmd.device;
    r.load.deviceMemory = [ctx, lowered, index](std::uint64_t needed) {
        vk::DeviceMemory m;
        std::string name = "the device";
        if (ctx) {
            m = vk::deviceMemory(ctx->memory, ctx->info.vkType);
            name = ctx->info.name;
        } else if (needed > kDeviceProbeBytes || (lowered > 0 && needed > lowered)) {
            if (const auto probe = vk::probeDeviceMemory(index)) m = probe->memory, name = probe->name;
        }
        if (lowered > 0 && (m.bytes == 0 || lowered < m.bytes)) m = {lowered, "the limit set"};
        return m.bytes == 0 ? DeviceBudget{} : DeviceBudget{m.bytes, name + " (" + m.what + ")"};
    };
}

// The settings a state of this render records (stateSettings).
nlohmann::ordered_json settingsOf(const RenderCommand& cmd, const Loaded& l) {
    return stateSettings(cmd.settings, l.host.camera, (l.host.gpu.features.bits & gpu::kFeatureLightTree) != 0u);
}

// Load, build, pack and upload `cmd.scene`; `shared` is the device, created
// on first use (after the scene loaded; the loader may read its memory
// before: setDeviceBudget). A --resume state (`resumed`) is checked against
// the scene and settings before the device is opened.
Loaded load(const RenderCommand& cmd, std::unique_ptr<vk::Context>& shared, const RenderState* resumed = nullptr) {
    Loaded l;
    l.request = sceneRequest(cmd);
    setDeviceBudget(cmd, shared.get(), l.request);
    l.host = prepareScene(l.request);
    if (usesStates(cmd)) l.sceneHash = sceneContentHash(l.host.gpu, l.host.camera);
    if (resumed) {
        StateInfo here;
        here.sceneHash = l.sceneHash;
        here.settings = settingsOf(cmd, l);
        here.batch = cmd.tuning.maxBatch;
        checkResumable(cmd, *resumed, here);
    }
    const auto t1 = std::chrono::steady_clock::now();
    if (!shared) {
        shared = std::make_unique<vk::Context>(vk::ContextOptions{cmd.device, cmd.validation});
        if (!cmd.quiet)
            std::fprintf(stderr, "strata: device %u: %s (%s, %s)\n", shared->info.index, shared->info.name.c_str(),
                         shared->info.type.c_str(), shared->info.driver.c_str());
    }
    l.deviceMs = msSince(t1);
    l.dev = uploadPrepared(*shared, l.request, l.host.gpu);
    return l;
}

// Poses a loaded scene for another frame's shutter: its moving placements
// (a new top level and instances array on the device) and cameras.
void pose(const vk::Context& ctx, const RenderCommand& cmd, Loaded& l) {
    Scene& scene = l.host.scene;
    scene.poser->pose(scene, cmd.settings.shutterOpen, cmd.settings.shutterClose);
    l.host.camera = requestedCamera(l.request, scene);
    if (!scene.instanced()) return;
    SceneBvh top;
    top.bottoms = l.host.bottoms;
    buildTopLevel(scene, top);
    l.host.gpu.instances = packInstanceArray(scene, top);
    l.dev.instances = uploadArray(ctx, l.host.gpu.instances, sceneLimits(ctx, l.request.limits));
}

// The header of the states this render writes.
StateInfo stateInfo(const RenderCommand& cmd, const vk::Context& ctx, const Loaded& l) {
    StateInfo in;
    in.scene = cmd.scene;
    in.sceneHash = l.sceneHash;
    in.settings = settingsOf(cmd, l);
    in.implementation = stateImplementation(ctx.info.name, ctx.info.driver, cmd.settings);
    in.spp = cmd.settings.spp;
    in.shard = cmd.shard;
    in.shards = cmd.shards;
    in.batch = cmd.tuning.maxBatch;
    return in;
}

// Refuses a state that this render cannot continue: another scene, other
// settings, other samples.
void checkResumable(const RenderCommand& cmd, const RenderState& st, const StateInfo& here) {
    const std::string mismatch = stateMismatch(st.info, cmd.resume, here, "this render");
    if (!mismatch.empty()) fail(cmd.resume, "cannot resume: " + mismatch);
    const SampleRange range = renderRange(cmd);
    const std::string shardText =
        cmd.shards ? "shard " + std::to_string(cmd.shard) + "/" + std::to_string(cmd.shards) : "the whole render";
    if (st.info.shards != cmd.shards || st.info.shard != cmd.shard || st.acc.begin != range.begin)
        fail(cmd.resume, "cannot resume: it holds samples " + std::to_string(st.acc.begin) + "-" +
                             std::to_string(st.acc.end) + (st.info.shards ? " of shard " + std::to_string(st.info.shard) +
                                                                                "/" + std::to_string(st.info.shards)
                                                                          : "") +
                             "; this render is " + shardText + ", samples " + std::to_string(range.begin) + "-" +
                             std::to_string(range.end));
    if (st.acc.end > range.end)
        fail(cmd.resume, "cannot resume: it already holds " + std::to_string(st.acc.end - st.acc.begin) +
                             " spp, more than this render's " + std::to_string(range.end - range.begin) +
                             " (--spp " + std::to_string(cmd.settings.spp) + ")");
}

// A state from another device or traversal is continued with a note: the
// result is then statistically equivalent to an uninterrupted render, not
// the same bits.
void noteImplementation(const RenderCommand& cmd, const RenderState& st, const StateInfo& here) {
    if (!sameImplementation(st.info, here) && !cmd.quiet)
        std::fprintf(stderr,
                     "strata: note: %s was rendered on %s, this render runs on %s: the result is statistically "
                     "equivalent to an uninterrupted render, not the same bits\n",
                     cmd.resume.c_str(), implementationText(st.info.implementation).c_str(),
                     implementationText(here.implementation).c_str());
}

// What a render that failed on the device leaves to go on from: the states
// of its latest checkpoint, or the state it resumed, as it was.
std::string deviceFailureNote(const RenderCommand& cmd, std::uint32_t checkpointed) {
    if (checkpointed > 0)
        return "; the latest checkpoint (" + std::to_string(checkpointed) + " spp) is kept in " + cmd.states[0] +
               ": go on with --resume " + cmd.states[0];
    if (!cmd.resume.empty()) return "; " + cmd.resume + " is as it was: go on with --resume " + cmd.resume;
    if (!cmd.states.empty()) return "; no checkpoint was written (--checkpoint-every SECONDS writes them)";
    return "";
}

// Renders the loaded scene and writes the outputs; returns the signal that
// interrupted the render (the outputs then hold the samples reached), or 0.
// `resumed`: the state of --resume, read.
int renderAndWrite(const RenderCommand& cmd, const vk::Context& ctx, Loaded& l, const RenderState* resumed = nullptr) {
    SampleRun run;
    const SampleRange range = renderRange(cmd);
    run.begin = range.begin;
    run.end = range.end;
    StateInfo info;
    if (usesStates(cmd)) info = stateInfo(cmd, ctx, l);
    if (resumed) {
        noteImplementation(cmd, *resumed, info);
        run.resume = &resumed->acc;
    }
    run.keep = !cmd.states.empty();
    const auto writeStates = [&](const Accumulation& acc) {
        const RenderState st{info, acc};
        for (const std::string& path : cmd.states) writeState(path, st);
    };
    std::uint32_t checkpointed = 0;  // samples in the states the latest checkpoint wrote
    if (cmd.checkpointEvery > 0.0) {
        run.checkpointSeconds = cmd.checkpointEvery;
        run.onCheckpoint = [&](const Accumulation& acc) {
            writeStates(acc);
            checkpointed = acc.end - acc.begin;
            if (!cmd.quiet)  // on its own line, also under a terminal's progress line
                std::fprintf(stderr, "\rstrata: checkpoint: %u spp written\n", acc.end - acc.begin);
        };
    }
    RenderResult result;
    try {
        result = render(ctx, l.dev, l.host.camera, cmd.settings, cmd.tuning, {}, run);
    } catch (const vk::DeviceError& e) {  // lost, out of memory: exit 3, what there is to go on from named
        throw vk::DeviceError(e.what() + deviceFailureNote(cmd, checkpointed));
    }
    StatsInput in{&ctx, &l.host.scene, &l.host.gpu, &cmd.settings, &result, l.host.loadMs, l.host.packMs, l.deviceMs};
    nlohmann::json stats = statsJson(in);
    if (ctx.validation && vk::validationMessageCount() > 0)
        throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                              " Vulkan validation message(s) during the render");

    // The statistics and the states first, taken back if an image cannot be
    // written: all outputs or none.
    std::vector<std::string> written;
    const auto takeBack = [&] {
        for (const std::string& path : written) std::remove(path.c_str());
    };
    try {
        if (!cmd.statsJson.empty()) {
            writeTextAtomically(cmd.statsJson, stats.dump(2) + "\n");
            written.push_back(cmd.statsJson);
        }
        if (!cmd.states.empty()) {
            writeStates(result.state);
            written.insert(written.end(), cmd.states.begin(), cmd.states.end());
        }
    } catch (...) {
        takeBack();
        throw;
    }
    // The EXR header says how many samples the image holds (fewer than asked
    // when interrupted or stopped by --time).
    const std::vector<std::pair<std::string, int>> header{{"strata:spp", int(result.spp)},
                                                          {"strata:sppRequested", int(range.end - range.begin)}};
    try {
        if (cmd.denoise) {
            AovImages aov = aovImages(result.film);
            aov.attributes = header;
            const DenoiseMethod method = cmd.denoiseFast ? DenoiseMethod::Fast : DenoiseMethod::Nfor;
            const DenoiseResult d = denoise(ctx, denoiseInput(aov), method);
            if (ctx.validation && vk::validationMessageCount() > 0)
                throw vk::DeviceError(std::to_string(vk::validationMessageCount()) +
                                      " Vulkan validation message(s) while denoising");
            writeDenoised(cmd.outputs, aov, d.rgb);
            if (!cmd.quiet)
                std::fprintf(stderr, "strata: denoised (%s) in %.3f s (device %.3f s)\n", denoiseMethodName(method),
                             d.seconds, d.deviceSeconds);
        } else {
            writeFilmImages(cmd.outputs, result.film, cmd.variance, header);
        }
    } catch (...) {
        takeBack();
        throw;
    }
    if (cmd.stats) std::fputs(statsText(stats).c_str(), stdout);
    if (result.nonFinite > 0)
        warn(cmd.scene, std::to_string(result.nonFinite) + " of " +
                            std::to_string(std::uint64_t(result.spp) * cmd.settings.width * cmd.settings.height) +
                            " samples were NaN or Inf and were left out of the image");
    if (!cmd.quiet) {
        for (const auto& out : cmd.states) std::fprintf(stderr, "strata: wrote %s\n", out.c_str());
        for (const auto& out : cmd.outputs) std::fprintf(stderr, "strata: wrote %s\n", out.c_str());
    }
    if (result.interrupted)
        std::fprintf(stderr, "strata: interrupted by %s: the outputs hold %u of %u spp\n",
                     signalName(result.interrupted).c_str(), result.spp, range.end - range.begin);
    return result.interrupted;
}

// --dry-run: what the command would do, in one line.
int dryRun(const RenderCommand& cmd) {
    const SampleRange range = renderRange(cmd);
    std::string outputs;
    for (const auto* list : {&cmd.states, &cmd.outputs})
        for (const std::string& o : *list) outputs += (outputs.empty() ? "" : ", ") + o;
    std::printf("strata: dry run: would render %s at %dx%d, samples %u-%u of %u%s%s, to %s\n", cmd.scene.c_str(),
                cmd.settings.width, cmd.settings.height, range.begin, range.end, cmd.settings.spp,
                cmd.shards ? (" (shard " + std::to_string(cmd.shard) + "/" + std::to_string(cmd.shards) + ")").c_str()
                           : "",
                cmd.resume.empty() ? "" : (", resuming " + cmd.resume).c_str(), outputs.c_str());
    return 0;
}

}  // namespace

// What the command asks of the stages: its file, environment, loader
// options, view, BVH, reads and limits; with --frames the placements kept.
SceneRequest sceneRequest(const RenderCommand& cmd) {
    SceneRequest r = sceneRequest(cmd.settings, cmd.tuning);
    r.file = cmd.scene;
    r.env = cmd.env;
    r.load.variant = cmd.variant;
    if (!cmd.restrictPaths.empty()) r.load.restrictPaths = restrictRoot(cmd.restrictPaths);
    r.load.instancing = cmd.instancing;
    r.textureMaxSize = cmd.textureMaxSize;
    r.load.motion.frames = cmd.frames.enabled;
    r.camera->view = cmd.view;
    r.consume = Consume::All;
    r.keepPlacements = cmd.frames.enabled;
    return r;
}

SampleRange renderRange(const RenderCommand& cmd) {
    if (cmd.shards) return shardRange(cmd.settings.spp, cmd.shard, cmd.shards, cmd.tuning.maxBatch);
    return {0, cmd.settings.spp};
}

void writeFilmImages(const std::vector<std::string>& outputs, const Film& film, bool variance,
                     const std::vector<std::pair<std::string, int>>& attributes) {
    if (film.aov) {
        AovImages aov = aovImages(film);
        aov.attributes = attributes;
        writeImages(outputs, film.width, film.height, aov.color, aovChannels(aov));
    } else if (variance) {
        ExtraChannels var;
        var.add("variance", "RGB", film.varianceOfMean());
        var.attributes = attributes;
        writeImages(outputs, film.width, film.height, film.mean(), var);
    } else {
        ExtraChannels none;
        none.attributes = attributes;
        writeImages(outputs, film.width, film.height, film.mean(), none);
    }
}

std::string frameFileName(const std::string& pattern, int frame) {
    const std::size_t first = pattern.find('#');
    if (first == std::string::npos) return pattern;
    std::size_t last = first;
    while (last < pattern.size() && pattern[last] == '#') ++last;
    std::string number = std::to_string(frame);
    if (number.size() < last - first) number.insert(0, last - first - number.size(), '0');
    return pattern.substr(0, first) + number + pattern.substr(last);
}

int runRender(const RenderCommand& cmd) {
    // The flags alone were checked while parsing (cli/checks.h); what needs
    // the file system before any work: image support, writable outputs.
    for (const auto& out : cmd.outputs) requireImageSupport(out);
    for (const auto& out : cmd.outputs) checkOutputPath(out);
    for (const auto& out : cmd.states) checkOutputPath(out);
    if (!cmd.statsJson.empty()) checkOutputPath(cmd.statsJson);
    if (cmd.dryRun) return dryRun(cmd);
    std::optional<RenderState> resumed;
    if (!cmd.resume.empty()) resumed = readState(cmd.resume);  // a bad state file before any work

    // SIGINT, SIGTERM: the render in progress stops after its submission and
    // writes what it reached; the status is then 128 + the signal.
    installInterruptHandlers();
    std::unique_ptr<vk::Context> ctx;
    if (!cmd.frames.enabled) {
        Loaded l = load(cmd, ctx, resumed ? &*resumed : nullptr);
        const int signal = renderAndWrite(cmd, *ctx, l, resumed ? &*resumed : nullptr);
        return signal ? 128 + signal : 0;
    }
    // Each frame its own shutter. The scene is loaded once (every mesh the
    // animation moves instanced); each later frame poses its placements and
    // cameras again: a new top level and instances array. A scene without a
    // poser (Scene::poser) is loaded anew each frame. The device and its
    // compiled pipelines stay.
    const FrameRange& fr = cmd.frames;
    std::optional<Loaded> l;
    for (int f = fr.first; f <= fr.last; f += fr.step) {
        RenderCommand frame = cmd;
        frame.settings.shutter = true;
        frame.settings.shutterOpen = fr.open(f);
        frame.settings.shutterClose = fr.close(f);
        for (std::string& out : frame.outputs) out = frameFileName(out, f);
        if (!frame.statsJson.empty()) frame.statsJson = frameFileName(frame.statsJson, f);
        const auto t0 = std::chrono::steady_clock::now();
        if (l && l->host.scene.poser)
            pose(*ctx, frame, *l);
        else  // the first frame, or a scene the poser cannot pose (Scene::poser)
            l.emplace(load(frame, ctx));
        const double setUpMs = msSince(t0);
        if (f != fr.first && l->host.scene.poser) {  // this frame's start-up: the posing alone (--stats: pack)
            l->host.loadMs = l->deviceMs = l->dev.uploadMs = 0.0;
            l->host.packMs = setUpMs;
        }
        const int signal = renderAndWrite(frame, *ctx, *l);
        if (!cmd.quiet)
            std::fprintf(stderr, "strata: frame %d: set-up %.1f ms, in all %.2f s\n", f, setUpMs, msSince(t0) / 1000.0);
        if (signal) return 128 + signal;  // this frame written with the samples reached; no later frame
    }
    return 0;
}

}  // namespace strata
