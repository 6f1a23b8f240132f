// SIGINT and SIGTERM during `strata render` (util/interrupt.h): the first
// signal stops the render after the submission in progress and writes every
// output with the samples reached (the EXR header's strata:spp, the stats'
// spp), exit 130 or 143; a second one ends the process at once and leaves no
// partial file. The real binary on lavapipe, signalled by a shell.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "image/image_io.h"

using namespace strata;
using namespace strata::test;

namespace {

int headerInt(const Image& img, const std::string& name) {
    for (const auto& [n, v] : img.attributes)
        if (n == name) return v;
    return -1;
}

// Files of `dir` whose name holds ".tmp" (an unfinished write).
int temporaries(const TempDir& dir) {
    int n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path))
        n += e.path().filename().string().find(".tmp") != std::string::npos;
    return n;
}

const std::string kScene = " render " + std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf --width 64 --height 64";

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("interrupt: SIGINT writes every output with the samples reached, the same bits as a render of that many "
          "samples, and exits 130, SIGTERM 143") {
    TempDir out;
    const Run r = signalled(kScene + " --spp 1000000 -o " + out / "a.exr" + " -o " + out / "a.png" + " --stats-json " +
                                out / "a.json",
                            {"-INT"}, 1.0, 0.0, out / "log");
    CAPTURE(r.output);
    REQUIRE(statusOf(r) == 130);
    REQUIRE(std::filesystem::exists(out / "a.png"));
    const Image img = readImage(out / "a.exr");
    const int spp = headerInt(img, "strata:spp");
    CAPTURE(spp);
    CHECK(spp >= 1);
    CHECK(spp < 1000000);
    CHECK(headerInt(img, "strata:sppRequested") == 1000000);
    std::ifstream statsFile(out / "a.json");
    const nlohmann::json stats = nlohmann::json::parse(statsFile);
    CHECK(stats["render"]["spp"].get<int>() == spp);
    CHECK(stats["render"]["interrupted"].get<std::string>() == "SIGINT");
    std::ifstream logFile(out / "log");
    const std::string log((std::istreambuf_iterator<char>(logFile)), std::istreambuf_iterator<char>());
    CHECK(log.find("strata: interrupted by SIGINT: the outputs hold " + std::to_string(spp) + " of 1000000 spp") !=
          std::string::npos);
    CHECK(temporaries(out) == 0);
    // Folds happen at fixed sample counts and at the end: the interrupted
    // image is the image of a render asked for exactly that many samples.
    REQUIRE(run(kScene + " --spp " + std::to_string(spp) + " --quiet -o " + out / "b.exr").status == 0);
    CHECK(readRgb(out / "a.exr").rgb == readRgb(out / "b.exr").rgb);
    CHECK(headerInt(readImage(out / "b.exr"), "strata:spp") == spp);

    const Run t = signalled(kScene + " --spp 1000000 -o " + out / "t.exr", {"-TERM"}, 0.5, 0.0, out / "log2");
    CAPTURE(t.output);
    CHECK(statusOf(t) == 143);
    CHECK(headerInt(readImage(out / "t.exr"), "strata:spp") >= 1);
}

TEST_CASE("interrupt: a second signal ends the render at once and leaves no partial file") {
    // 1024x1024: one sample is a submission of several tenths of a second
    // on lavapipe, so the second signal, 0.1 s after the first, comes before
    // that submission ends (and then nothing is written) or, rarely, while
    // the outputs are written (then their temporary files are removed).
    TempDir out;
    const Run r = signalled(" render " + std::string(STRATA_SOURCE_DIR) +
                                "/scenes/cornell-box.gltf --width 1024 --height 1024 --spp 1000000 -o " +
                                out / "a.exr" + " -o " + out / "a.png" + " --stats-json " + out / "a.json",
                            {"-INT", "-INT"}, 0.5, 0.1, out / "log");
    CAPTURE(r.output);
    CHECK(statusOf(r) == 130);
    CHECK(temporaries(out) == 0);
    std::filesystem::remove(out / "log");
    // Whatever is there is whole: an image that reads and holds samples.
    for (const char* f : {"a.exr", "a.png"}) {
        if (!std::filesystem::exists(out / f)) continue;
        CHECK(readImage(out / f).width == 1024);
    }
    if (std::filesystem::exists(out / "a.exr")) CHECK(headerInt(readImage(out / "a.exr"), "strata:spp") >= 1);
}

TEST_SUITE_END();
