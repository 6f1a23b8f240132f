// The command-line parser and help (host/cli) without running the binary:
// the flag tables set the command structs, keep the one-line errors, and
// the help of each command lists every flag its table has.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "../shaders/shared/types.h"
#include "cli/commands.h"
#include "util/error.h"

using namespace strata;
using Args = std::vector<std::string>;

TEST_SUITE_BEGIN("unit");

namespace {

// The one-line error `parse(args)` throws, or "" when it throws none.
template <class Parse>
std::string errorOf(Parse parse, const Args& args) {
    try {
        parse(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// `text` with every run of spaces and line breaks made one space: help as
// words, whatever its wrapping.
std::string flat(const std::string& text) {
    std::string out;
    for (char c : text) {
        const bool space = c == ' ' || c == '\n';
        if (!space) out += c;
        else if (!out.empty() && out.back() != ' ') out += ' ';
    }
    return out;
}

// Whether flat help text lists the flag `name` as a row ("NAME METAVAR",
// "-o, --output"; the usage line and the help of other flags do not name a
// flag followed by a space).
bool lists(const std::string& help, const std::string& name) {
    return help.find(" " + name + " ") != std::string::npos || help.find(" " + name + ", ") != std::string::npos;
}

}  // namespace

TEST_CASE("cli parser: render's defaults, -o and --output, and a switch") {
    RenderCommand cmd = cli::parseRender({"dir/box.gltf"});
    CHECK(cmd.scene == "dir/box.gltf");
    CHECK(cmd.outputs == Args{"box.exr", "box.png"});
    CHECK(cmd.settings.spp == 64);
    CHECK(cmd.settings.progress);
    CHECK(cmd.device == -1);
    cmd = cli::parseRender({"-o", "a.exr", "box.gltf", "--output", "b.png", "--spp", "9", "--quiet", "--camera", "2"});
    CHECK(cmd.outputs == Args{"a.exr", "b.png"});
    CHECK(cmd.settings.spp == 9);
    CHECK(cmd.quiet);
    CHECK_FALSE(cmd.settings.progress);
    CHECK(cmd.view.camera == 2);
}

TEST_CASE("cli parser: --filter-radius overrides the filter's own radius in either order") {
    for (const Args& args : {Args{"s.gltf", "--filter", "tent", "--filter-radius", "3"},
                             Args{"s.gltf", "--filter-radius", "3", "--filter", "tent"}}) {
        const RenderCommand cmd = cli::parseRender(args);
        CHECK(cmd.settings.filter.kind == FilterKind::Tent);
        CHECK(cmd.settings.filter.radius == 3.0f);
    }
    CHECK(cli::parseRender({"s.gltf", "--filter", "gaussian"}).settings.filter.radius == 1.5f);
}

TEST_CASE("cli parser: --reads and its old name --traversal set the read mode") {
    CHECK(cli::parseRender({"s.gltf", "--reads", "storage"}).settings.reads == ReadMode::Storage);
    CHECK(cli::parseRender({"s.gltf", "--traversal", "texel"}).settings.reads == ReadMode::Texel);
    CHECK(cli::parseBench({"s.gltf", "--reads", "texel"}).settings.reads == ReadMode::Texel);
    CHECK(cli::parseBench({"s.gltf", "--traversal", "storage"}).settings.reads == ReadMode::Storage);
    // The error names the flag as written.
    CHECK(errorOf(cli::parseRender, {"s.gltf", "--reads", "fast"}) ==
          "strata: error: --reads expects auto, texel or storage, got 'fast'");
    CHECK(errorOf(cli::parseBench, {"s.gltf", "--traversal", "fast"}) ==
          "strata: error: --traversal expects auto, texel or storage, got 'fast'");
}

TEST_CASE("cli parser: the shared groups set each command's own fields") {
    const BenchCommand b = cli::parseBench({"s.gltf", "--seed", "7", "--max-depth", "3", "--bvh", "2", "--env-color",
                                            "1,2,3", "--env-rotate", "-30", "--integrator", "wavefront"});
    CHECK(b.settings.seed == 7);
    CHECK(b.settings.maxDepth == 3);
    CHECK(b.settings.bvhWidth == 2);
    CHECK(b.env.hasColor);
    CHECK(b.env.color.z == 3.0f);
    CHECK(b.env.rotateDegrees == -30.0);
    CHECK(b.settings.integrator == IntegratorKind::Wavefront);
    const ConvergeCommand c = cli::parseConverge(
        {"s.gltf", "--reference", "r.exr", "-o", "r.csv", "--seed", "5", "--spp", "1,4,16", "--sampler", "all"});
    CHECK(c.settings.seed == 5);
    CHECK(c.spp == std::vector<std::uint32_t>{1, 4, 16});
    CHECK(c.allSamplers);
    CHECK(cli::parseConverge({"s.gltf", "--reference", "r.exr", "-o", "r.csv"}).spp.size() == 9);  // 1 .. 256
    const EdgesCommand e = cli::parseEdges({"--spp", "16", "--sampler", "regular", "--seed", "4"});
    CHECK(e.settings.spp == 16);
    CHECK(e.settings.seed == 4);
    CHECK(e.settings.samplers == std::vector<std::uint32_t>{gpu::kSamplerRegular});
    const cli::CompareArgs a = cli::parseCompare({"a.exr", "--json", "m.json", "b.exr"});
    CHECK(a.image == "a.exr");
    CHECK(a.reference == "b.exr");
    CHECK(a.json == "m.json");
}

TEST_CASE("cli parser: bad flags are the same one-line errors as before") {
    const std::vector<std::pair<Args, std::string>> cases = {
        {{"s.gltf", "--bogus"}, "unknown option '--bogus' (see 'strata render --help')"},
        {{"s.gltf", "--width"}, "--width needs a value"},
        {{"s.gltf", "-o"}, "-o needs a value"},
        {{"s.gltf", "--spp", "0"}, "--spp expects an integer in [1, 1073741824], got '0'"},
        {{"s.gltf", "--seed", "-1"}, "--seed expects an integer in [0, 4294967295], got '-1'"},
        {{"s.gltf", "--time", "-1"}, "--time expects seconds in (0, 1000000000], got '-1'"},
        {{"s.gltf", "--filter-radius", "17"}, "--filter-radius expects a radius in pixels in (0, 16], got '17'"},
        {{"s.gltf", "--bvh", "3"}, "--bvh expects 2 or 4, got '3'"},
        {{"s.gltf", "--bvh-stack", "heap"}, "--bvh-stack expects auto, registers or memory, got 'heap'"},
        {{"s.gltf", "--mis", "both"}, "--mis expects power, bsdf or light, got 'both'"},
        {{"s.gltf", "--env-rotate", "10"}, "--env-rotate needs --env or --env-color"},
        {{"s.gltf", "--env", "a.hdr", "--env-color", "1,1,1"}, "--env and --env-color exclude each other"},
        {{"s.gltf", "--env-color", "0,0,0"}, "--env-color is black; leave out --env-color for no environment"},
        {{"a.gltf", "b.gltf"}, "unexpected argument 'b.gltf' (one scene per render)"},
        {{}, "render needs a scene file (see 'strata render --help')"},
    };
    for (const auto& [args, what] : cases) {
        CAPTURE(what);
        CHECK(errorOf(cli::parseRender, args) == "strata: error: " + what);
    }
    CHECK(errorOf(cli::parseReference, {"s.gltf", "-o", "r.exr"}) ==
          "strata: error: reference needs --spp N (a high sample count)");
    CHECK(errorOf(cli::parseReference, {"s.gltf", "--spp", "4", "-o", "r.png"}) ==
          "strata: error: reference needs an .exr output (-o REF.exr) to store the variance");
    CHECK(errorOf(cli::parseConverge, {"s.gltf", "-o", "r.csv"}) ==
          "strata: error: converge needs --reference REF.exr");
    CHECK(errorOf(cli::parseConverge, {"s.gltf", "--reference", "r.exr", "-o", "r.csv", "--spp", "4,2"}) ==
          "strata: error: --spp values must be ascending, got '4,2'");
    CHECK(errorOf(cli::parseBench, {"s.gltf", "--only", "paths"}) ==
          "strata: error: --only takes 'traversal' (got 'paths')");
    CHECK(errorOf(cli::parseBench, {}) == "strata: error: bench needs a scene file");
    CHECK(errorOf(cli::parseEdges, {"x"}) == "strata: error: unexpected argument 'x'");
    CHECK(errorOf(cli::parseCompare, {"a.exr"}) == "strata: error: compare needs IMAGE and REFERENCE");
    CHECK(errorOf(cli::parseDenoise, {}) == "strata: error: denoise needs an EXR rendered with --aov");
    CHECK(errorOf(cli::parseDenoise, {"a.exr"}) == "strata: error: denoise needs -o OUT.exr or OUT.png");
    CHECK(errorOf(cli::parseDenoise, {"a.exr", "b.exr", "-o", "c.exr"}) ==
          "strata: error: unexpected argument 'b.exr' (one image)");
    CHECK(errorOf(cli::parseDenoise, {"a.exr", "-o", "c.exr", "--method", "slow"}).find("--method") !=
          std::string::npos);
    CHECK(errorOf(cli::parseCompare, {"a.exr", "b.exr", "--plot", "p.png"}) ==
          "strata: error: unknown option '--plot' (see 'strata compare --help')");
}

TEST_CASE("cli help: each command's help shows every flag of its table, with metavar and default") {
    CHECK(cli::commands().size() == 11);  // render, reference, view ... devices, shaders
    for (const cli::CommandInfo& c : cli::commands()) {
        CAPTURE(c.name);
        const std::string help = flat(c.help()), tuning = flat(c.tuningHelp());
        const std::vector<std::string> knobs = c.tuningFlags();
        CHECK(help.rfind("usage: strata " + c.name, 0) == 0);
        for (const std::string& name : c.flags()) {
            CAPTURE(name);
            const bool knob = std::find(knobs.begin(), knobs.end(), name) != knobs.end();
            CHECK(lists(knob ? tuning : help, name));
        }
        CHECK(help.find("-h, --help") != std::string::npos);
    }
    const std::string render = flat(cli::findCommand("render")->help());
    CHECK(render.find("--spp N ") != std::string::npos);
    CHECK(render.find("in [1, 1073741824] (default: 64)") != std::string::npos);
    const std::string renderTuning = flat(cli::findCommand("render")->tuningHelp());
    CHECK(renderTuning.find("--reads auto|texel|storage") != std::string::npos);
    CHECK(renderTuning.find("--traversal auto|texel|storage") != std::string::npos);
    CHECK(renderTuning.find("(old name of --reads)") != std::string::npos);
    CHECK(render.find("(default: sobol)") != std::string::npos);
    CHECK(flat(cli::findCommand("converge")->help()).find("(default: 1,2,4,8,16,32,64,128,256)") != std::string::npos);
    CHECK(flat(cli::findCommand("edges")->help()).find("(default: all)") != std::string::npos);
    CHECK(cli::findCommand("frobnicate") == nullptr);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

TEST_CASE("cli: --denoise takes an optional method and turns the AOVs on, and --aov alone does not denoise") {
    const RenderCommand plain = cli::parseRender({"s.gltf", "--denoise"});
    CHECK(plain.denoise);
    CHECK(!plain.denoiseFast);
    CHECK(plain.settings.aov);
    const RenderCommand fast = cli::parseRender({"s.gltf", "--denoise", "fast", "--spp", "4"});
    CHECK(fast.denoiseFast);
    CHECK(fast.settings.spp == 4);
    CHECK(fast.scene == "s.gltf");
    const RenderCommand aov = cli::parseRender({"s.gltf", "--aov"});
    CHECK(aov.settings.aov);
    CHECK(!aov.denoise);
    const ConvergeCommand conv = cli::parseConverge({"s.gltf", "--reference", "r.exr", "-o", "c.csv", "--denoise", "fast"});
    CHECK(conv.denoise);
    CHECK(conv.method == DenoiseMethod::Fast);
    const DenoiseCommand d = cli::parseDenoise({"in.exr", "-o", "out.exr", "--method", "fast"});
    CHECK(d.input == "in.exr");
    CHECK(d.method == DenoiseMethod::Fast);
}

TEST_CASE("cli checks: combinations the flags alone refuse are one-line errors of the parser") {
    const std::string wavefrontAov =
        " needs the megakernel integrator (--integrator megakernel); the wavefront integrator keeps no AOVs";
    const std::vector<std::pair<Args, std::string>> render = {
        {{"s.gltf", "--denoise", "--integrator", "wavefront"}, "strata: error: --denoise" + wavefrontAov},
        {{"s.gltf", "--integrator", "wavefront", "--aov"}, "strata: error: --aov" + wavefrontAov},
        {{"s.gltf", "-o", "a.jpg"}, "a.jpg: error: unsupported output format '.jpg' (use .exr or .png)"},
        {{"s.gltf", "--sampler", "regular", "--spp", "10"},
         "strata: error: --sampler regular needs a square spp (n x n grid), got 10; try 9 or 16"},
        {{"s.gltf", "--checkpoint-every", "60", "-o", "a.exr"},
         "strata: error: --checkpoint-every rewrites the .state outputs: add -o FILE.state"},
        {{"s.gltf", "--resume", "a.state", "--frames", "0:2", "-o", "a_#.exr"},
         "strata: error: --frames renders frame by frame: .state outputs, --resume and --shard are for one image"},
        {{"s.gltf", "--resume", "a.exr"}, "strata: error: --resume takes a .state file, got 'a.exr'"},
    };
    for (const auto& [args, what] : render) {
        CAPTURE(what);
        CHECK(errorOf(cli::parseRender, args) == what);
    }
    CHECK(errorOf(cli::parseReference, {"s.gltf", "--spp", "16", "-o", "r.exr", "--denoise", "--integrator",
                                        "wavefront"}) == "strata: error: --denoise" + wavefrontAov);
    CHECK(errorOf(cli::parseRender, {"s.gltf", "--spp", "100", "--shard", "2/4"}).find("fewer than 4 shards") !=
          std::string::npos);
    CHECK(errorOf(cli::parseConverge, {"s.gltf", "--reference", "r.exr", "-o", "r.txt"}) ==
          "r.txt: error: converge report must be .csv or .json");
    CHECK(errorOf(cli::parseConverge, {"s.gltf", "--reference", "r.exr", "-o", "r.csv", "--plot", "p.jpg"}) ==
          "p.jpg: error: unsupported output format '.jpg' (use .exr or .png)");
    CHECK(errorOf(cli::parseConverge, {"s.gltf", "--reference", "r.exr", "-o", "r.csv", "--sampler", "regular",
                                       "--spp", "4,8"}) ==
          "strata: error: --sampler regular needs a square spp (n x n grid), got 8; try 4 or 9");
    CHECK(errorOf(cli::parseConverge, {"s.gltf", "--reference", "r.exr", "-o", "r.csv", "--sampler", "all",
                                       "--spp", "4,8"}) == "");
    CHECK(errorOf(cli::parseEdges, {"-o", "t.txt"}) == "t.txt: error: edges table must be .csv");
    CHECK(errorOf(cli::parseEdges, {"--plot", "p.jpg"}) ==
          "p.jpg: error: unsupported output format '.jpg' (use .exr or .png)");
    CHECK(errorOf(cli::parseEdges, {"--sampler", "regular", "--spp", "10"})
              .rfind("strata: error: no requested sampler suits --spp 10 (regular: skipped: ", 0) == 0);
    CHECK(errorOf(cli::parseBench, {"s.gltf", "--json", "b.txt"}) == "b.txt: error: bench report must be .json");
    CHECK(errorOf(cli::parseCompare, {"a.exr", "b.exr", "--json", "m.txt"}) ==
          "m.txt: error: compare report must be .json");
    CHECK(errorOf(cli::parseDenoise, {"a.exr", "-o", "b.jpg"}) ==
          "b.jpg: error: unsupported output format '.jpg' (use .exr or .png)");
    CHECK(errorOf(cli::parseMerge, {"a.state", "-o", "b.jpg"}) ==
          "b.jpg: error: unsupported output format '.jpg' (use .exr or .png)");
    // What the flags allow still parses.
    CHECK(errorOf(cli::parseRender, {"s.gltf", "--aov", "--sampler", "regular", "--spp", "16", "-o", "a.state",
                                     "--checkpoint-every", "60", "-o", "a.EXR"}) == "");
}

TEST_CASE("cli help: --help leaves the tuning flags to --help-tuning, and they parse as before") {
    const Args knobs = {"--bvh", "--bvh-stack", "--reads", "--traversal"};
    for (const char* name : {"render", "reference"}) {
        CAPTURE(name);
        const cli::CommandInfo& c = *cli::findCommand(name);
        const std::string help = c.help(), tuning = c.tuningHelp();
        CHECK(c.tuningFlags() == knobs);
        for (const std::string& knob : knobs) {
            CAPTURE(knob);
            CHECK_FALSE(lists(flat(help), knob));
            CHECK(lists(flat(tuning), knob));
        }
        CHECK(lists(flat(help), "--integrator"));
        // The help's last line points at the tuning flags.
        const std::string last = help.substr(help.rfind('\n', help.size() - 2) + 1);
        CHECK(last == "Tuning flags, for measurements and tests: 'strata " + std::string(name) + " --help-tuning'.\n");
        CHECK(tuning.rfind("usage: strata " + std::string(name), 0) == 0);
        CHECK(tuning.find("-h, --help") == std::string::npos);
    }
    // bench measures them: its own help lists them, and it has no tuning part.
    const cli::CommandInfo& bench = *cli::findCommand("bench");
    CHECK(bench.tuningHelp().empty());
    CHECK(bench.tuningFlags().empty());
    for (const std::string& knob : knobs) CHECK(lists(flat(bench.help()), knob));
    for (const cli::CommandInfo& c : cli::commands())
        CHECK((c.help().find("--help-tuning") == std::string::npos || !c.tuningHelp().empty()));
    const RenderCommand r = cli::parseRender({"s.gltf", "--bvh", "2", "--bvh-stack", "memory", "--reads", "storage"});
    CHECK(r.settings.bvhWidth == 2);
    CHECK(r.settings.bvhStack == BvhStack::Memory);
    CHECK(r.settings.reads == ReadMode::Storage);
    CHECK(cli::parseReference({"s.gltf", "--spp", "4", "-o", "r.exr", "--traversal", "texel"}).settings.reads ==
          ReadMode::Texel);
}

TEST_SUITE_END();
