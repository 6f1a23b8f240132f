#include "cli/commands.h"

#include <cstdio>
#include <filesystem>

#include "../../shaders/shared/types.h"
#include "cli/checks.h"
#include "cli/flag_groups.h"
#include "cli/flags.h"
#include "denoise/command.h"
#include "image/image_io.h"
#include "measure/compare.h"
#include "settings/filter.h"
#include "render/merge.h"
#include "render/sampler_kind.h"
#include "util/files.h"
#include "vk/context.h"

namespace strata::cli {
namespace {

// The commands' help texts: name, usage, one-line summary, the notes after the flags.
const CommandText kRenderText{"render", "SCENE.gltf|.glb [options]", "Render a glTF scene to EXR and/or PNG.",
    "Files appear whole or not at all: after an error, none is written.\n"};

const CommandText kReferenceText{"reference", "SCENE.gltf|.glb --spp N -o REF.exr [options]",
    "Render a reference: EXR with each pixel's variance of the mean.",
    "--spp and an .exr output are required. The EXR gets channels variance.R/G/B\n"
    "(the variance of each pixel's mean), which compare, converge and the tests use.\n"};

const CommandText kCompareText{"compare", "IMAGE.exr REFERENCE.exr [options]",
    "Print the error of an image against a reference.",
    "Prints RMSE, relMSE = mean (x - r)^2 / (r^2 + 0.01), relMSE with the largest\n"
    "0.1% of terms dropped, MAPE, SMAPE, the largest absolute error and the count of\n"
    "non-finite values. The images must have the same size and R, G, B channels.\n"};

const CommandText kMergeText{"merge", "A.state B.state ... -o OUT.exr|.png|.state [options]",
    "Sum the states of a render's shards into one image or state.",
    "The states must be of one scene with the same settings, and their sample\n"
    "ranges must not overlap. An image needs every sample of the render (--spp of\n"
    "the shards); a .state output alone may hold a contiguous part, to be merged\n"
    "again. The sums are exact: shards from one device merge to the bits a single\n"
    "render makes (docs/distributed.md). States with AOVs give the AOV layers.\n"};

const CommandText kConvergeText{"converge", "SCENE.gltf|.glb --reference REF.exr -o REPORT.csv|.json [options]",
    "Measure the error against a reference by spp and by device time.",
    "Each seed is one render; the image at every listed spp is taken along the way.\n"
    "Per spp: device seconds, relMSE (mean and standard deviation over the seeds) and\n"
    "efficiency 1 / (relMSE x seconds); then the log-log slopes of relMSE against spp\n"
    "and seconds, the floor b^2 of relMSE(N) = b^2 + c / N and the reference's own\n"
    "noise floor.\n"};

const CommandText kEdgesText{"edges", "[options]", "Measure how well each sampler estimates an edge's coverage.",
    "Samples are drawn by the GLSL samplers on the device. Per sampler and edge angle:\n"
    "the distinct estimates (shades) as the edge slides across the pixel, the RMSE\n"
    "against the exact coverage, and the RMSE independent samples would have.\n"};

const CommandText kBenchText{"bench", "SCENE.gltf|.glb [options]",
    "Measure traversal, path tracing, dispatch and start-up speed.",
    "Sections: traversal (primary, diffuse and occlusion rays, the ray sets of\n"
    "shared/peers/embree-rays), path tracing (Msamples/s, rays/s, relMSE against\n"
    "--reference), dispatch throughput, start-up. Device time from Vulkan\n"
    "timestamps, warm-up excluded.\n"};

const CommandText kDenoiseText{"denoise", "IN.exr -o OUT.exr [-o OUT.png] [options]",
    "Denoise an EXR rendered with --aov.",
    "IN.exr needs R, G, B and the layers of 'render --aov': variance, halfA, halfB,\n"
    "albedo, normal, depth and emitter (noisy.R/G/B, when present, is the image\n"
    "denoised). OUT.exr gets the denoised R, G, B, the input in noisy.R/G/B and the\n"
    "layers. The same input gives the same bits as 'render --denoise'.\n"};

const CommandText kDevicesText{"devices", "", "List the Vulkan devices.",
    "One line per device: index, name, type, driver and Vulkan version; --device takes the index.\n"};


std::vector<Flag<RenderCommand>> renderFlags() {
    using C = RenderCommand;
    const auto settings = [](auto& c) -> auto& { return c.settings; };
    return concat<C>({
        {
            outputFlag<C>("write the image to FILE: .exr (linear float) or .png (sRGB, 8 bits), or the whole "
                          "accumulation to FILE.state, to resume or merge (docs/distributed.md); may be given more "
                          "than once")
                .withDefault("SCENE.exr and SCENE.png in the current directory"),
            positive<C>("--checkpoint-every", "SECONDS",
                        "rewrite the .state outputs every SECONDS during the render, so that a crash loses at most "
                        "that much",
                        1e9, "seconds", STRATA_FIELD(checkpointEvery))
                .withDefault("never"),
            text<C>("--resume", "FILE.state",
                    "continue the render FILE.state holds to --spp N in all; the same scene and settings, the same "
                    "bits as an uninterrupted render",
                    STRATA_FIELD(resume)),
            flag<C>("--shard", "I/K",
                    "render shard I (from 0) of K: a contiguous run of whole batches of the --spp sample indices; "
                    "'strata merge' sums the shards' states",
                    [](C& c, const std::string& given, const std::string& v) {
                        const std::size_t slash = v.find('/');
                        if (slash == std::string::npos) badFlag(given + " takes I/K, e.g. 0/4, got '" + v + "'");
                        c.shard = static_cast<std::uint32_t>(parseUnsigned(given, v.substr(0, slash), 0, 1u << 24));
                        c.shards = static_cast<std::uint32_t>(parseUnsigned(given, v.substr(slash + 1), 1, 1u << 24));
                        if (c.shard >= c.shards)
                            badFlag(given + " " + v + ": I must be below K (shards count from 0)");
                    }),
            toggle<C>("--dry-run", "check the flags and outputs, print what would be rendered, and stop",
                      [](C& c) { c.dryRun = true; }),
            integer<C>("--spp", "N", "samples per pixel", 1, 1u << 30, STRATA_FIELD(settings.spp)),
            integer<C>("--width", "W", "image width in pixels", 1, 16384, STRATA_FIELD(settings.width)),
            integer<C>("--height", "H", "image height in pixels", 1, 16384, STRATA_FIELD(settings.height)),
            positive<C>("--time", "SECONDS",
                        "stop after the submission in progress once SECONDS have passed, recording the spp "
                        "reached",
                        1e9, "seconds", STRATA_FIELD(settings.timeLimit))
                .withDefault("no limit"),
            choice<C, std::uint32_t>("--mis",
                                     "how light sampling and BSDF sampling combine: Veach's power heuristic, or "
                                     "one technique alone",
                                     {{"power", gpu::kMisPower}, {"bsdf", gpu::kMisBsdf}, {"light", gpu::kMisLight}},
                                     STRATA_FIELD(settings.mis)),
            toggle<C>("--quiet", "print no device line, progress or names of the files written",
                      [](C& c) { c.quiet = true, c.settings.progress = false; }),
            toggle<C>("--stats", "print the device, scene, BVH, start-up, render and memory figures",
                      [](C& c) { c.stats = true; }),
            text<C>("--stats-json", "FILE", "write the --stats figures to FILE as JSON", STRATA_FIELD(statsJson)),
            toggle<C>("--aov",
                      "EXR outputs get the AOV layers: variance, halfA, halfB, albedo, normal (camera space), "
                      "depth, emitter (docs/denoising.md)",
                      [](C& c) { c.settings.aov = true; }),
            flag<C>("--frames", "FIRST:LAST[:STEP]",
                    "render the animation frame by frame: frame f poses the scene at f / fps; each -o holds a run of "
                    "'#' for the frame number (out_####.exr)",
                    [](C& c, const std::string& given, const std::string& v) {
                        const std::size_t a = v.find(':'), b = a == std::string::npos ? a : v.find(':', a + 1);
                        if (a == std::string::npos) badFlag(given + " takes FIRST:LAST[:STEP], got '" + v + "'");
                        c.frames.enabled = true;
                        c.frames.first = int(parseUnsigned(given, v.substr(0, a), 0, 1u << 24));
                        c.frames.last = int(parseUnsigned(given, v.substr(a + 1, b == std::string::npos ? b : b - a - 1),
                                                          0, 1u << 24));
                        if (b != std::string::npos)
                            c.frames.step = int(parseUnsigned(given, v.substr(b + 1), 1, 1u << 24));
                        if (c.frames.last < c.frames.first)
                            badFlag(given + ": LAST must not precede FIRST, got '" + v + "'");
                    }),
            positive<C>("--fps", "F", "frames per second of --frames", 1e6, "frames per second",
                        STRATA_FIELD(frames.fps))
                .withDefault("24"),
            flag<C>("--shutter-angle", "DEGREES",
                    "each frame's shutter stays open for DEGREES / 360 of the frame's time, in [0, 360]; 0: no "
                    "motion blur",
                    [](C& c, const std::string& given, const std::string& v) {
                        const double a = parseFinite(given, v);
                        if (a < 0.0 || a > 360.0) badFlag(given + " must be in [0, 360], got '" + v + "'");
                        c.frames.shutterAngle = a;
                    })
                .withDefault("0"),
            toggle<C>("--denoise",
                      "denoise the image (with the AOVs): R, G, B denoised, noisy.R/G/B the image as rendered; "
                      "'--denoise fast' for the edge-aware a-trous filter instead of the regression",
                      [](C& c) { c.denoise = true, c.settings.aov = true; }),
        },
        renderGroups<C>(settings),
    });
}

RenderCommand renderInit() {
    RenderCommand c;
    c.settings.progress = true;  // on a terminal; --quiet turns it off
    return c;
}

const CommandSpec<RenderCommand>& renderSpec(const std::string& name) {
    return name == "render" ? kept<kRenderText>(renderFlags, renderInit)
                            : kept<kReferenceText>(renderFlags, renderInit);
}

// --denoise takes an optional method, '--denoise fast' (or nfor): `args`
// without it, and whether it was fast.
std::vector<std::string> withoutDenoiseMethod(const std::vector<std::string>& given, bool& fast) {
    std::vector<std::string> args;
    for (std::size_t i = 0; i < given.size(); ++i) {
        args.push_back(given[i]);
        if (given[i] == "--denoise" && i + 1 < given.size() && (given[i + 1] == "fast" || given[i + 1] == "nfor"))
            fast = given[++i] == "fast";
    }
    return args;
}

// --frames sets the shutter per frame (render/command.cpp); the first
// frame's here, so that the checks see a render with a shutter.
void setFirstFrameShutter(RenderCommand& cmd) {
    if (!cmd.frames.enabled) return;
    cmd.settings.shutter = true;  // posed by the animation (renderer: frame by frame)
    cmd.settings.shutterOpen = cmd.frames.open(cmd.frames.first);
    cmd.settings.shutterClose = cmd.frames.close(cmd.frames.first);
}

// Parses a render-like command's flags and positional scene.
RenderCommand parseRenderLike(const std::string& name, const std::vector<std::string>& given, Parsed& parsed) {
    const CommandSpec<RenderCommand>& spec = renderSpec(name);
    RenderCommand cmd = spec.init;
    bool fast = false;
    parsed = parseFlags(spec, withoutDenoiseMethod(given, fast), cmd);
    cmd.denoiseFast = fast;
    if (parsed.positional.size() > 1)
        badFlag("unexpected argument '" + parsed.positional[1] + "' (one scene per " + name + ")");
    if (parsed.positional.empty()) badFlag(name + " needs a scene file (see 'strata " + name + " --help')");
    cmd.scene = parsed.positional[0];
    setFirstFrameShutter(cmd);
    checkRenderFlags(parsed, cmd);
    if (cmd.outputs.empty() && cmd.states.empty()) {
        const std::string stem = std::filesystem::path(cmd.scene).stem().string() + (cmd.frames.enabled ? "_####" : "");
        cmd.outputs = {stem + ".exr", stem + ".png"};
    }
    return cmd;
}

std::vector<std::uint32_t> parseSppList(const std::string& value) {
    std::vector<std::uint32_t> out;
    std::size_t start = 0;
    while (start <= value.size()) {
        const std::size_t comma = value.find(',', start);
        const std::string item = value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const auto v = static_cast<std::uint32_t>(parseUnsigned("--spp", item, 1, 1u << 30));
        if (!out.empty() && v <= out.back()) badFlag("--spp values must be ascending, got '" + value + "'");
        out.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

std::vector<Flag<CompareArgs>> compareFlags() {
    return {text<CompareArgs>("--json", "FILE", "also write the metrics to FILE as JSON", STRATA_FIELD(json))};
}

const CommandSpec<CompareArgs>& compareSpec() { return kept<kCompareText>(compareFlags); }

std::vector<Flag<MergeCommand>> mergeFlags() {
    using C = MergeCommand;
    return {
        outputFlag<C>("write FILE: .exr, .png or .state; may be given more than once"),
        toggle<C>("--variance", "EXR outputs get variance.R/G/B, the variance of each pixel's mean",
                  [](C& c) { c.variance = true; }),
        toggle<C>("--quiet", "print no timing or names of the files written", [](C& c) { c.quiet = true; }),
        toggle<C>("--dry-run", "check the flags and outputs, print what would be merged, and stop",
                  [](C& c) { c.dryRun = true; }),
    };
}

const CommandSpec<MergeCommand>& mergeSpec() { return kept<kMergeText>(mergeFlags); }

ConvergeCommand convergeInit() {
    ConvergeCommand c;
    for (std::uint32_t n = 1; n <= 256; n *= 2) c.spp.push_back(n);
    return c;
}

std::vector<Flag<ConvergeCommand>> convergeFlags() {
    using C = ConvergeCommand;
    return concat<C>({
        {
            text<C>("--reference", "REF.exr",
                    "the reference (from 'strata reference'); its size is the render size",
                    STRATA_FIELD(reference)),
            text<C>("--output", "REPORT", "write the report to REPORT: .csv or .json", STRATA_FIELD(report))
                .withAlias("-o"),
            flag<C>(
                "--spp", "N,N,...", "the spp at which the error is measured, ascending, each in [1, 1073741824]",
                [](C& c, const std::string&, const std::string& v) { c.spp = parseSppList(v); },
                [](const C& c) {
                    std::vector<std::string> items;
                    for (std::uint32_t n : c.spp) items.push_back(std::to_string(n));
                    return joined(items, ",");
                }),
            integer<C>("--seeds", "K", "renders, each with its own seed (--seed, --seed + 1, ...)", 1, 1000,
                       STRATA_FIELD(seeds)),
            text<C>("--plot", "PLOT.png", "draw relMSE against spp and against device seconds",
                    STRATA_FIELD(plot)),
            flag<C>(
                "--sampler", joined(samplerNames(), "|") + "|all",
                std::string(kSamplerHelp) + "; all: every sampler that suits the spp list",
                [](C& c, const std::string&, const std::string& v) {
                    if (v == "all") c.allSamplers = true;
                    else c.settings.sampler = samplerByName(v).kind;
                },
                [](const C& c) {
                    return std::string(c.allSamplers ? "all" : samplerByKind(c.settings.sampler).name);
                }),
            toggle<C>("--quiet", "print no device line or progress", [](C& c) { c.quiet = true; }),
            toggle<C>("--denoise",
                      "also denoise each image and measure it (sampler name +nfor, or +fast with "
                      "'--denoise fast'); its seconds include the denoiser's",
                      [](C& c) { c.denoise = true; }),
        },
        pathFlags<C>([](auto& c) -> auto& { return c.settings; }),
        envFlags<C>(),
        sceneFlags<C>(),
        deviceFlags<C>(),
    });
}

const CommandSpec<ConvergeCommand>& convergeSpec() { return kept<kConvergeText>(convergeFlags, convergeInit); }

std::vector<Flag<EdgesCommand>> edgesFlags() {
    using C = EdgesCommand;
    return concat<C>({
        {
            text<C>("--output", "TABLE.csv", "write the table to TABLE.csv", STRATA_FIELD(table)).withAlias("-o"),
            text<C>("--plot", "PLOT.png|.exr", "draw estimate against exact coverage", STRATA_FIELD(plot)),
            integer<C>("--spp", "N", "samples per pixel", 1, 1u << 16, STRATA_FIELD(settings.spp)),
            seedFlag<C>([](auto& c) -> auto& { return c.settings; }),
            flag<C>(
                "--sampler", joined(samplerNames(), "|") + "|all",
                "the samplers measured; all: every one that suits --spp",
                [](C& c, const std::string&, const std::string& v) {
                    c.settings.samplers.clear();
                    if (v != "all") c.settings.samplers.push_back(samplerByName(v).kind);
                },
                [](const C& c) {
                    std::vector<std::string> names;
                    for (std::uint32_t k : c.settings.samplers) names.push_back(samplerByKind(k).name);
                    return names.empty() ? std::string("all") : joined(names, ",");
                }),
        },
        deviceFlags<C>(),
    });
}

const CommandSpec<EdgesCommand>& edgesSpec() { return kept<kEdgesText>(edgesFlags); }

std::vector<Flag<BenchCommand>> benchFlags() {
    using C = BenchCommand;
    const auto settings = [](auto& c) -> auto& { return c.settings; };
    return concat<C>({
        {
            integer<C>("--width", "W", "image width in pixels", 1, 16384, STRATA_FIELD(settings.width)),
            integer<C>("--height", "H", "image height in pixels", 1, 16384, STRATA_FIELD(settings.height)),
            integer<C>("--reps", "R", "timed passes per ray set (the median is reported)", 1, 1000,
                       STRATA_FIELD(reps)),
            integer<C>("--spp", "N", "samples per pixel of the path-tracing section", 1, 1u << 20,
                       STRATA_FIELD(settings.spp)),
            text<C>("--reference", "REF.exr",
                    "a reference of the same size: the relMSE of the path-tracing image",
                    STRATA_FIELD(reference)),
            toggle<C>("--quick", "a small dispatch section and short path-tracing timings",
                      [](C& c) { c.quick = true; }),
            flag<C>("--only", "traversal", "run only the start-up, BVH and traversal sections",
                    [](C& c, const std::string&, const std::string& v) {
                        c.only = v;
                        if (c.only != "traversal") badFlag("--only takes 'traversal' (got '" + c.only + "')");
                    }),
            text<C>("--json", "FILE", "also write the results to FILE as JSON", STRATA_FIELD(json)),
        },
        pathFlags<C>(settings),
        traceFlags<C>(settings, false),
        envFlags<C>(),
        sceneFlags<C>(),
        deviceFlags<C>(),
    });
}

const CommandSpec<BenchCommand>& benchSpec() { return kept<kBenchText>(benchFlags); }

std::vector<Flag<DenoiseCommand>> denoiseFlags() {
    using C = DenoiseCommand;
    return concat<C>({
        {
            flag<C>("--output", "FILE", "write the denoised image to FILE: .exr or .png; may be given more than once",
                    [](C& c, const std::string&, const std::string& v) { c.outputs.push_back(v); })
                .withAlias("-o"),
            choice<C, DenoiseMethod>("--method",
                                     "nfor: first-order regression on the AOVs, the bandwidth chosen per pixel "
                                     "by the half-buffers' error; fast: the edge-aware a-trous filter",
                                     {{"nfor", DenoiseMethod::Nfor}, {"fast", DenoiseMethod::Fast}},
                                     STRATA_FIELD(method)),
            toggle<C>("--quiet", "print no device line or names of the files written",
                      [](C& c) { c.quiet = true; }),
        },
        deviceFlags<C>(),
    });
}

const CommandSpec<DenoiseCommand>& denoiseSpec() { return kept<kDenoiseText>(denoiseFlags); }

const CommandText kShadersText{"shaders", "[SCENE.gltf ...] [--all] [options]",
    "Print the shader feature table, or fill the shader cache.",
    "Without arguments: the feature axes (docs/architecture.md). With scenes: compiles,\n"
    "or finds in the shader cache, every module a render of each may use (any BVH,\n"
    "with and without --aov and the camera effects, either integrator, the denoiser);\n"
    "with --all, every module the table allows. Run it before a farm's jobs start on\n"
    "a shared --shader-cache folder.\n"};

std::vector<Flag<ShadersCommand>> shadersFlags() {
    using C = ShadersCommand;
    return {
        toggle<C>("--all", "every module the feature table allows", [](C& c) { c.all = true; }),
        text<C>("--out", "DIR", "also write each module as DIR/NAME.spv", STRATA_FIELD(out)),
        toggle<C>("--quiet", "print the summary line only", [](C& c) { c.quiet = true; }),
        shaderCacheFlag<C>(),
    };
}

const CommandSpec<ShadersCommand>& shadersSpec() { return kept<kShadersText>(shadersFlags); }

struct NoArgs {};

std::vector<Flag<NoArgs>> noFlags() { return {}; }

const CommandSpec<NoArgs>& devicesSpec() { return kept<kDevicesText>(noFlags); }

int listDevices(const std::vector<std::string>& args) {
    if (!args.empty()) badFlag("devices takes no arguments");
    for (const auto& d : vk::listDevices())
        std::printf("%u: %s | %s | %s | Vulkan %s\n", d.index, d.name.c_str(), d.type.c_str(), d.driver.c_str(),
                    d.apiVersion.c_str());
    return 0;
}


#undef STRATA_FIELD

}  // namespace

RenderCommand parseRender(const std::vector<std::string>& args) {
    Parsed parsed;
    return parseRenderLike("render", args, parsed);
}

RenderCommand parseReference(const std::vector<std::string>& args) {
    Parsed parsed;
    RenderCommand cmd = parseRenderLike("reference", args, parsed);
    bool exrGiven = false;
    for (const auto& o : cmd.outputs) exrGiven |= outputFormat(o) == ImageFormat::Exr;
    if (!parsed.has("--spp")) badFlag("reference needs --spp N (a high sample count)");
    if (!exrGiven) badFlag("reference needs an .exr output (-o REF.exr) to store the variance");
    cmd.variance = true;
    return cmd;
}

CompareArgs parseCompare(const std::vector<std::string>& args) {
    CompareArgs a = compareSpec().init;
    const Parsed parsed = parseFlags(compareSpec(), args, a);
    if (parsed.positional.size() != 2) badFlag("compare needs IMAGE and REFERENCE");
    a.image = parsed.positional[0];
    a.reference = parsed.positional[1];
    checkCompareFlags(a);
    return a;
}

// The scene of converge and bench: one positional argument.
template <class T>
T parseSceneCommand(const CommandSpec<T>& spec, const std::vector<std::string>& args) {
    T cmd = spec.init;
    const Parsed parsed = parseFlags(spec, args, cmd);
    if (parsed.positional.size() > 1) badFlag("unexpected argument '" + parsed.positional[1] + "'");
    if (parsed.positional.empty()) badFlag(spec.name + " needs a scene file");
    cmd.scene = parsed.positional[0];
    checkEnvFlags(parsed, cmd.env);
    checkViewFlags(cmd.view);
    checkLensFlags(cmd.settings);
    return cmd;
}

ConvergeCommand parseConverge(const std::vector<std::string>& given) {
    bool fast = false;
    ConvergeCommand cmd = parseSceneCommand(convergeSpec(), withoutDenoiseMethod(given, fast));
    if (fast) cmd.method = DenoiseMethod::Fast;
    if (cmd.reference.empty()) badFlag("converge needs --reference REF.exr");
    if (cmd.report.empty()) badFlag("converge needs -o REPORT.csv or REPORT.json");
    checkConvergeFlags(cmd);
    return cmd;
}

EdgesCommand parseEdges(const std::vector<std::string>& args) {
    EdgesCommand cmd = edgesSpec().init;
    const Parsed parsed = parseFlags(edgesSpec(), args, cmd);
    if (!parsed.positional.empty()) badFlag("unexpected argument '" + parsed.positional[0] + "'");
    checkEdgesFlags(cmd);
    return cmd;
}

BenchCommand parseBench(const std::vector<std::string>& args) {
    BenchCommand cmd = parseSceneCommand(benchSpec(), args);
    checkBenchFlags(cmd);
    return cmd;
}

MergeCommand parseMerge(const std::vector<std::string>& args) {
    MergeCommand cmd = mergeSpec().init;
    const Parsed parsed = parseFlags(mergeSpec(), args, cmd);
    if (parsed.positional.empty()) badFlag("merge needs the .state files of the shards");
    for (const std::string& in : parsed.positional)
        if (lowerExtension(in) != ".state") badFlag("merge takes .state files, got '" + in + "'");
    if (cmd.outputs.empty() && cmd.states.empty()) badFlag("merge needs -o OUT.exr, OUT.png or OUT.state");
    cmd.inputs = parsed.positional;
    checkMergeFlags(cmd);
    return cmd;
}

ShadersCommand parseShaders(const std::vector<std::string>& args) {
    ShadersCommand cmd = shadersSpec().init;
    cmd.scenes = parseFlags(shadersSpec(), args, cmd).positional;
    return cmd;
}

DenoiseCommand parseDenoise(const std::vector<std::string>& args) {
    DenoiseCommand cmd = denoiseSpec().init;
    const Parsed parsed = parseFlags(denoiseSpec(), args, cmd);
    if (parsed.positional.size() > 1) badFlag("unexpected argument '" + parsed.positional[1] + "' (one image)");
    if (parsed.positional.empty()) badFlag("denoise needs an EXR rendered with --aov");
    if (cmd.outputs.empty()) badFlag("denoise needs -o OUT.exr or OUT.png");
    cmd.input = parsed.positional[0];
    checkDenoiseFlags(cmd);
    return cmd;
}

const std::vector<CommandInfo>& commands() {
    static const std::vector<CommandInfo> list = {
        command(renderSpec("render"), [](const auto& a) { return runRender(parseRender(a)); }),
        command(renderSpec("reference"), [](const auto& a) { return runRender(parseReference(a)); }),
        viewCommand(),
        command(compareSpec(),
                [](const auto& a) {
                    const CompareArgs c = parseCompare(a);
                    return runCompare(c.image, c.reference, c.json);
                }),
        command(convergeSpec(), [](const auto& a) { return runConverge(parseConverge(a)); }),
        command(edgesSpec(), [](const auto& a) { return runEdges(parseEdges(a)); }),
        command(benchSpec(), [](const auto& a) { return runBench(parseBench(a)); }),
        command(denoiseSpec(), [](const auto& a) { return runDenoise(parseDenoise(a)); }),
        command(mergeSpec(), [](const auto& a) { return runMerge(parseMerge(a)); }),
        command(devicesSpec(), listDevices),
        command(shadersSpec(), [](const auto& a) { return runShaders(parseShaders(a)); }),
    };
    return list;
}

const CommandInfo* findCommand(const std::string& name) {
    for (const CommandInfo& c : commands())
        if (c.name == name) return &c;
    return nullptr;
}

std::string overview() {
    std::string out =
        "usage: strata COMMAND [ARGUMENTS]\n"
        "       strata --help | --version\n\n"
        "A path tracer for glTF 2.0 scenes on Vulkan compute shaders.\n\ncommands:\n";
    for (const CommandInfo& c : commands()) {
        std::string summary = c.summary;
        if (!summary.empty() && summary.back() == '.') summary.pop_back();
        out += "  " + c.name + std::string(12 - c.name.size(), ' ') + summary + "\n";
    }
    out +=
        "\n'strata COMMAND --help' gives each command's usage and options.\n"
        "Bad input (scene, flags, files) is one line 'FILE: error: ...' and exit status 2;\n"
        "device failures exit with 3.\n";
    return out;
}

}  // namespace strata::cli
