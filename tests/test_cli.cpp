// The strata binary as a user runs it: exit codes, one-line errors, and no
// output file after any error.
#include <doctest/doctest.h>

#include "cli_util.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"

namespace fs = std::filesystem;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

const std::string kSmall = " --spp 1 --width 8 --height 8 --quiet";

// `strata ARGS` with its standard output only (or, with `stream` "2>&1
// >/dev/null", its standard error only).
Run runOneStream(const std::string& args, const std::string& stream = "2>/dev/null") {
    return runShell("{ " + std::string(STRATA_EXE) + " " + args + " " + stream + "; }");
}

}  // namespace

TEST_CASE("every broken file gives one error line naming it, exit 2 and no output" * doctest::test_suite("unit")) {
    const fs::path dir = fs::path(STRATA_SOURCE_DIR) / "tests/data/broken";
    std::size_t checked = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string file = entry.path().string();
        if (entry.path().filename() == "zero-area-emitter.gltf") continue;  // loads, with a warning
        if (entry.path().extension() == ".bin") continue;
        checkRenderRefuses(file);
        ++checked;
    }
    CHECK(checked >= 12);
}

TEST_CASE("a zero-area emitter is dropped with a warning and the scene still renders") {
    TempDir out;
    const std::string file = std::string(STRATA_SOURCE_DIR) + "/tests/data/broken/zero-area-emitter.gltf";
    const Run r = run("render " + file + " -o " + (out.path / "a.exr").string() + kSmall);
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(r.output.find(": warning: ") != std::string::npos);
    CHECK(fs::exists(out.path / "a.exr"));
}

TEST_CASE("bad flags are one-line errors with exit 2 and write nothing" * doctest::test_suite("unit")) {
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    TempDir out;
    const std::string o = " -o " + (out.path / "a.exr").string();
    for (const std::string& args : std::vector<std::string>
         {"render " + scene + o + " --spp 0", "render " + scene + o + " --spp ten",
          "render " + scene + o + " --bogus", "render " + scene + o + " --width",
          "render " + scene + " -o " + (out.path / "a.jpg").string(),
          "render " + scene + o + " --camera 5", "render " + scene + o + " --time -1",
          "render " + scene + o + " --traversal fast", "render " + scene + o + " --bvh 3",
          "render " + scene + o + " --bvh-stack heap", "render " + scene + o + " --integrator fast",
          "render " + scene + o + " --integrator",
          "render " + scene + o + " --bvh", "render", "frobnicate",
          "render " + scene + o + " --sampler regular --spp 10", "render " + scene + o + " --sampler magic",
          "render " + scene + o + " --sampler bluenoise --spp 12",
          "render /nonexistent/scene.gltf" + o}) {
        CAPTURE(args);
        // The small settings, without overriding a case's own --spp.
        const Run r = run(args + (args.find("--spp") == std::string::npos ? kSmall
                                                                           : " --width 8 --height 8 --quiet"));
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(lines(r.output) == 1);
        CHECK(r.output.find("error: ") != std::string::npos);
        CHECK(out.empty());
    }
}

TEST_CASE("conflicting flags are refused while parsing: before the missing scene, image or state is read"
          * doctest::test_suite("unit")) {
    TempDir out;
    const std::string missing = "/nonexistent/";
    struct Case {
        std::string args, line;  // the command line, and the one error line it gives
    };
    const std::string aov = " needs the megakernel integrator (--integrator megakernel); the wavefront integrator "
                            "keeps no AOVs";
    const std::vector<Case> cases = {
        {"render " + missing + "s.gltf --denoise --integrator wavefront -o " + out / "a.exr",
         "strata: error: --denoise" + aov},
        {"render " + missing + "s.gltf --aov --integrator wavefront -o " + out / "a.exr", "strata: error: --aov" + aov},
        {"reference " + missing + "s.gltf --spp 4 --denoise --integrator wavefront -o " + out / "r.exr",
         "strata: error: --denoise" + aov},
        {"render " + missing + "s.gltf --resume " + missing + "a.state --frames 0:1 -o " + out / "a_#.exr",
         "strata: error: --frames renders frame by frame: .state outputs, --resume and --shard are for one image"},
        {"render " + missing + "s.gltf --checkpoint-every 5 -o " + out / "a.exr",
         "strata: error: --checkpoint-every rewrites the .state outputs: add -o FILE.state"},
        {"render " + missing + "s.gltf --sampler bluenoise --spp 12 -o " + out / "a.exr",
         "strata: error: --sampler bluenoise needs a power-of-two spp, got 12"},
        {"render " + missing + "s.gltf -o " + out / "a.jpg",
         out / "a.jpg" + ": error: unsupported output format '.jpg' (use .exr or .png)"},
        {"converge " + missing + "s.gltf --reference " + missing + "r.exr -o " + out / "c.txt",
         out / "c.txt" + ": error: converge report must be .csv or .json"},
        {"bench " + missing + "s.gltf --json " + out / "b.txt", out / "b.txt" + ": error: bench report must be .json"},
        {"compare " + missing + "a.exr " + missing + "b.exr --json " + out / "m.txt",
         out / "m.txt" + ": error: compare report must be .json"},
        {"denoise " + missing + "in.exr -o " + out / "d.jpg",
         out / "d.jpg" + ": error: unsupported output format '.jpg' (use .exr or .png)"},
        {"merge " + missing + "a.state -o " + out / "m.jpg",
         out / "m.jpg" + ": error: unsupported output format '.jpg' (use .exr or .png)"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const Run r = run(c.args);
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(r.output == c.line + "\n");
        CHECK(r.output.find(missing) == std::string::npos);  // no file named by it was read
    }
    // Without the conflict the same lines get as far as the missing file.
    const Run plain = run("render " + missing + "s.gltf --denoise -o " + out / "a.exr");
    CHECK(plain.status == 2);
    CHECK(plain.output.rfind(missing + "s.gltf: error: ", 0) == 0);
    CHECK(out.empty());
}

TEST_CASE("an output that cannot be written fails before any work, and nothing is written" * doctest::test_suite("unit")) {
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    TempDir out;
    fs::create_directories(out.path / "d.exr");
    const std::string missing = (out.path / "missing").string();
    struct Case {
        std::string args, path, phrase;
    };
    // Without --quiet: work would print the device line (or the bench's
    // header) before the error.
    const std::string small = " --width 8 --height 8 --spp 1";
    const std::vector<Case> cases = {
        {"render " + scene + small + " -o " + out / "a.exr" + " --stats-json " + missing + "/s.json",
         missing + "/s.json", "directory '" + missing + "' does not exist"},
        {"render " + scene + small + " -o " + out / "a.exr" + " -o " + missing + "/a.png", missing + "/a.png",
         "directory '" + missing + "' does not exist"},
        {"render " + scene + small + " -o " + out / "d.exr", out / "d.exr", "it is a directory"},
        {"bench " + scene + small + " --quick --json " + missing + "/b.json", missing + "/b.json",
         "directory '" + missing + "' does not exist"},
        {"edges --spp 4 -o " + out / "t.csv" + " --plot " + missing + "/p.png", missing + "/p.png",
         "directory '" + missing + "' does not exist"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const Run r = run(c.args);
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(lines(r.output) == 1);
        CHECK(r.output.rfind(c.path + ": error: cannot write the file: " + c.phrase, 0) == 0);
        CHECK(!fs::exists(out.path / "a.exr"));
        CHECK(!fs::exists(out.path / "t.csv"));
    }
}

TEST_CASE("render writes EXR and PNG from one run, and devices lists the device") {
    TempDir out;
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    const Run r = run("render " + scene + " -o " + (out.path / "c.exr").string() + " -o " +
                      (out.path / "c.png").string() + " --stats-json " +
                      (out.path / "s.json").string() + kSmall);
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(fs::file_size(out.path / "c.exr") > 0);
    CHECK(fs::file_size(out.path / "c.png") > 0);
    CHECK(fs::file_size(out.path / "s.json") > 0);
    for (const auto& e : fs::directory_iterator(out.path))
        CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
    const Run d = run("devices");
    CHECK(d.status == 0);
    CHECK(d.output.find("0: ") == 0);
}

TEST_CASE("OpenImageIO is a module loaded for images only, and without it an image is a one-line error") {
    // strata itself does not link OpenImageIO (its libraries' start-up cost
    // every command ~0.25 s): the executable's dependencies do not name it.
    const Run deps = runShell("ldd " + std::string(STRATA_EXE));
    REQUIRE(deps.status == 0);
    CHECK(deps.output.find("libvulkan") != std::string::npos);
    CHECK(deps.output.find("OpenImageIO") == std::string::npos);
    // Reading or writing an image loads it; a missing module fails that one step.
    TempDir out;
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    const Run r = run("render " + scene + " -o " + (out.path / "c.png").string() + kSmall,
                      "STRATA_OIIO_MODULE=/nonexistent/libstrata_oiio.so");
    CAPTURE(r.output);
    CHECK(r.status == 2);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.find("c.png: error: image support (OpenImageIO) could not be loaded") != std::string::npos);
    CHECK(out.empty());
    const Run d = run("devices", "STRATA_OIIO_MODULE=/nonexistent/libstrata_oiio.so");
    CHECK(d.status == 0);  // no image involved
}

TEST_CASE("--time stops early and records the spp actually reached") {
    TempDir out;
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    const Run r = run("render " + scene + " -o " + (out.path / "t.exr").string() + " --stats-json " +
                      (out.path / "s.json").string() +
                      " --spp 1000000 --width 16 --height 16 --quiet --time 0.5");
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    std::ifstream f(out.path / "s.json");
    const std::string json((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const auto pos = json.find("\"spp\": ");
    REQUIRE(pos != std::string::npos);
    const unsigned long spp = std::stoul(json.substr(pos + 7));
    CHECK(spp >= 1);
    CHECK(spp < 1000000);
}

TEST_CASE("texture errors: missing, corrupt or empty image, a directory as image, bad texture index, missing TEXCOORD set" * doctest::test_suite("unit")) {
    const std::string dir = std::string(STRATA_SOURCE_DIR) + "/tests/data/textures/broken/";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"missing-image.gltf", "does-not-exist.png"},
        {"corrupt-image.gltf", "image 0 (\"corrupt.png\"): cannot decode"},
        {"empty-image.gltf", "unreadable file: uri \"empty.png\" refers to " + dir + "empty.png, which is an empty file"},
        {"directory-image.gltf", "unreadable file: uri \".\" refers to " + dir + "., which is a directory"},
        {"bad-texture-index.gltf", "emissiveTexture: texture 3 does not exist (1 textures)"},
        {"missing-texcoord.gltf", "reads TEXCOORD_1, which the primitive does not have"}};
    for (const auto& [name, what] : cases) {
        const std::string file = dir + name;
        CAPTURE(file);
        TempDir out;
        const Run r = run("render " + file + " -o " + (out.path / "a.exr").string() + kSmall);
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(lines(r.output) == 1);
        CHECK(r.output.rfind(file + ": error: ", 0) == 0);
        CHECK(r.output.find(what) != std::string::npos);
        CHECK(out.empty());
    }
}

TEST_CASE("samples whose float sums overflow are left out with one warning, and the image stays finite") {
    // The Cornell box with its lamp 1e38 times as bright: 64 samples of a
    // lamp pixel sum past the float range on the device.
    std::ifstream in(std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string key = "\"emissiveStrength\": 15.0";
    const auto at = text.find(key);
    REQUIRE(at != std::string::npos);
    text.replace(at, key.size(), "\"emissiveStrength\": 1e38");
    TempDir d;
    const std::string scene = (d.path / "hot.gltf").string();
    std::ofstream(scene) << text;
    const Run r = run("render " + scene + " --spp 64 --width 16 --height 16 --quiet -o " + (d.path / "hot.exr").string());
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.rfind(scene + ": warning: ", 0) == 0);
    CHECK(r.output.find(" of 16384 samples were NaN or Inf and were left out of the image") != std::string::npos);
    const Run c = run("compare " + (d.path / "hot.exr").string() + " " + (d.path / "hot.exr").string());
    CHECK(c.output.find(", 0 non-finite (excluded)") != std::string::npos);
}

TEST_CASE("strata --version prints the version, the git hash of a checkout and the Vulkan loader's version" * doctest::test_suite("unit")) {
    const Run r = run("--version");
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(lines(r.output) == 2);
    // "strata 0.21.0" or "strata 0.21.0 (git 1abe589-dirty)"
    REQUIRE(r.output.rfind("strata ", 0) == 0);
    const std::string version = r.output.substr(7, r.output.find_first_of(" \n", 7) - 7);
    CHECK(std::count(version.begin(), version.end(), '.') == 2);
    CHECK(version.find_first_not_of("0123456789.") == std::string::npos);
    // A git checkout of its own (not a tarball, nor a folder inside another checkout).
    const std::string source = STRATA_SOURCE_DIR;
    const std::string top = "$(git -C '" + source + "' rev-parse --show-toplevel 2>/dev/null)";
    const bool checkout = runShell("test \"" + top + "\" = \"$(cd '" + source + "' && pwd -P)\"").status == 0;
    CHECK((r.output.find(" (git ") != std::string::npos) == checkout);
    CHECK(r.output.find("\nVulkan loader 1.") != std::string::npos);
}

TEST_CASE("strata --help lists every command, and strata alone prints the same to stderr and exits 2" * doctest::test_suite("unit")) {
    for (const char* flag : {"--help", "-h", "help"}) {
        CAPTURE(flag);
        const Run r = runOneStream(flag);
        CHECK(r.status == 0);
        for (const char* command : {"render", "reference", "compare", "converge", "edges", "bench", "devices"})
            CHECK(r.output.find("\n  " + std::string(command) + " ") != std::string::npos);
        CHECK(r.output.find("'strata COMMAND --help'") != std::string::npos);
    }
    const Run bare = runOneStream("", "2>&1 >/dev/null");
    CHECK(bare.status == 2);
    CHECK(bare.output == runOneStream("--help").output);
}

TEST_CASE("COMMAND --help prints the command's usage and every flag of its table, and does nothing else" * doctest::test_suite("unit")) {
    for (const strata::cli::CommandInfo& c : strata::cli::commands()) {
        CAPTURE(c.name);
        const Run r = runOneStream(c.name + " --help");
        CHECK(r.status == 0);
        CHECK(r.output.rfind("usage: strata " + c.name, 0) == 0);
        const std::string tuning = c.tuningHelp().empty() ? "" : runOneStream(c.name + " --help-tuning").output;
        CHECK(tuning == c.tuningHelp());
        for (const std::string& flag : c.flags()) {
            CAPTURE(flag);
            CHECK((r.output.find(flag) != std::string::npos || tuning.find(flag) != std::string::npos));
        }
        CHECK(run("help " + c.name).output == r.output);
        CHECK(run(c.name + " -h").output == r.output);
    }
    const std::string render = run("render --help").output;
    for (const char* flag : {"--spp N", "--integrator megakernel|wavefront", "--env MAP", "-o, --output FILE"})
        CHECK(render.find(flag) != std::string::npos);
    CHECK(render.find("--reads auto|texel|storage") == std::string::npos);
    const Run tuning = runOneStream("render --help-tuning");
    CHECK(tuning.status == 0);
    for (const char* flag : {"--reads auto|texel|storage", "--traversal auto|texel|storage", "--bvh 2|4",
                             "--bvh-stack auto|registers|memory"})
        CHECK(tuning.output.find(flag) != std::string::npos);
    CHECK(tuning.output.find("--spp") == std::string::npos);
    CHECK(run("reference --help-tuning").output == run("reference --help-tuning /nonexistent/scene.gltf --bogus").output);
    CHECK(run("bench s.gltf --help-tuning").output ==
          "strata: error: unknown option '--help-tuning' (see 'strata bench --help')\n");
    CHECK(run("converge --help").output.find("--reference REF.exr") != std::string::npos);
    // Help ignores the rest of the line: no scene is loaded, no value checked,
    // no device opened, nothing written.
    TempDir out;
    for (const std::string& args : std::vector<std::string>{
             "render /nonexistent/scene.gltf --spp 0 --bogus -o " + out / "a.exr" + " --help",
             "reference --help /nonexistent/scene.gltf", "bench /nonexistent/scene.gltf -h --json " + out / "b.json",
             "render --help-tuning /nonexistent/scene.gltf --spp 0 -o " + out / "a.exr",
             "converge --device 99 --help", "edges --spp 0 -h -o " + out / "t.csv", "devices --help",
             "compare --help"}) {
        CAPTURE(args);
        const Run r = run(args, "STRATA_OIIO_MODULE=/nonexistent/libstrata_oiio.so");
        CHECK(r.status == 0);
        CHECK(r.output.find("error:") == std::string::npos);
        CHECK(r.output.find("strata: device") == std::string::npos);
        CHECK(out.empty());
    }
}

TEST_CASE("cli: render --reads and its old name --traversal both choose the read mode, and give the same image") {
    TempDir out;
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    for (const char* flag : {"--reads", "--traversal"}) {
        CAPTURE(flag);
        const std::string name = std::string(flag).substr(2);
        const Run r = run("render " + scene + kSmall + " " + flag + " storage -o " + out / (name + ".exr") +
                          " --stats-json " + out / (name + ".json"));
        CAPTURE(r.output);
        REQUIRE(r.status == 0);
        std::ifstream f(out / (name + ".json"));
        CHECK(nlohmann::json::parse(f)["render"]["reads"] == "storage");
    }
    const Run c = run("compare " + out / "reads.exr" + " " + out / "traversal.exr" + " --json " + out / "c.json");
    REQUIRE(c.status == 0);
    std::ifstream f(out / "c.json");
    CHECK(nlohmann::json::parse(f)["max_abs"].get<double>() == 0.0);
    const Run bad = run("render " + scene + kSmall + " --reads fast -o " + out / "bad.exr");
    CHECK(bad.status == 2);
    CHECK(bad.output == "strata: error: --reads expects auto, texel or storage, got 'fast'\n");
    CHECK(!fs::exists(out / "bad.exr"));
}

TEST_SUITE_END();
