// The light options of the strata binary: --env, --env-color, --env-intensity,
// --env-rotate, and KHR_lights_punctual files. Bad input: exit 2, one line
// naming the file (or "strata: error:" for a flag), no output file.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli_util.h"
#include "image/image_io.h"

namespace fs = std::filesystem;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

const std::string kSmall = " --spp 1 --width 8 --height 8 --quiet";

std::string lights(const std::string& name) { return std::string(STRATA_SOURCE_DIR) + "/tests/data/lights/" + name; }

}  // namespace

TEST_CASE("lights cli: every broken light file gives one error line naming it, exit 2 and no output" * doctest::test_suite("unit")) {
    std::size_t checked = 0;
    for (const auto& entry : fs::directory_iterator(lights("broken"))) {
        const std::string file = entry.path().string();
        expectError("render " + file, file + ": error: ");
        ++checked;
    }
    CHECK(checked >= 7);
}

TEST_CASE("lights cli: bad environment input is one line, exit 2, no output" * doctest::test_suite("unit")) {
    const std::string sphere = "render " + lights("sphere.gltf");
    const std::string missing = lights("does-not-exist.hdr");
    expectError(sphere + " --env " + missing, missing + ": error: ");
    for (const char* bad : {"1,2", "1,2,3,4", "a,b,c", "1,-1,0", "0,0,0", "nan,1,1", "1,,1", ""})
        expectError(sphere + " --env-color '" + std::string(bad) + "'", "strata: error: --env-color ");
    expectError(sphere + " --env-color 1,1,1 --env-intensity 0", "strata: error: --env-intensity ");
    expectError(sphere + " --env-color 1,1,1 --env-intensity -2", "strata: error: --env-intensity ");
    expectError(sphere + " --env-color 1,1,1 --env-intensity inf",
                "strata: error: --env-intensity expects a factor in (0, 1e+30], got 'inf'");
    // Radiance beyond float would make every sample that sees it Inf.
    expectError(sphere + " --env-color 1e39,1,1",
                "strata: error: --env-color expects R,G,B, three numbers in [0, 1e+30], got '1e39,1,1'");
    expectError(sphere + " --env-color 3e29,1,1 --env-intensity 1e10",
                "strata: error: --env-color times --env-intensity is 3e+39, beyond the float range (3.4e+38)");
    expectError(sphere + " --env-color 1,1,1 --env-rotate ten", "strata: error: --env-rotate ");
    expectError(sphere + " --env-color 1,1,1 --env-rotate inf", "strata: error: --env-rotate ");
    expectError(sphere + " --env-rotate 10", "strata: error: --env-rotate needs --env or --env-color");
    expectError(sphere + " --env " + lights("sky.hdr") + " --env-color 1,1,1", "strata: error: --env and --env-color");

    // Maps with a negative, a non-finite and only black texels.
    TempDir maps;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<std::pair<std::string, std::vector<float>>> cases = {
        {"negative.exr", {1, 1, 1, 1, -0.5f, 1, 1, 1, 1, 1, 1, 1}},
        {"nan.exr", {1, 1, 1, 1, 1, 1, nan, 1, 1, 1, 1, 1}},
        {"black.exr", std::vector<float>(12, 0.0f)},
    };
    for (const auto& [name, rgb] : cases) {
        const std::string path = maps / name;
        strata::writeImages({path}, 2, 2, rgb);
        expectError(sphere + " --env " + path, path + ": error: environment map ");
    }
    // A map whose brightest texel, scaled, passes the float range.
    const std::string bright = maps / "bright.exr";
    strata::writeImages({bright}, 2, 2, {1, 1, 1, 1e30f, 1, 1, 1, 1, 1, 1, 1, 1});
    expectError(sphere + " --env " + bright + " --env-intensity 1e9",
                bright + ": error: the brightest texel times --env-intensity is 1e+39, beyond the float range (3.4e+38)");
}

TEST_CASE("lights cli: a bad --light-candidates is one line, exit 2, no output" * doctest::test_suite("unit")) {
    const std::string room = "render " + std::string(STRATA_SOURCE_DIR) + "/scenes/many-lights.gltf";
    for (const char* bad : {"0", "9", "-1", "two", "1.5", ""})
        expectError(room + " --light-candidates '" + std::string(bad) + "'",
                    "strata: error: --light-candidates expects an integer in [1, 8], got '" + std::string(bad) + "'");
    expectError(room + " --light-sampler power --light-candidates 2",
                "strata: error: --light-candidates resamples the light tree's choices: not with --light-sampler power");
}

TEST_CASE("lights cli: a scene lit only by the environment renders with render, reference and a map" * doctest::test_suite("slow")) {
    TempDir out;
    const std::string sphere = lights("sphere.gltf");
    Run r = run("render " + sphere + " --env-color 0.5,0.6,0.7 --env-intensity 2 --env-rotate 45 -o " + out / "c.exr" + kSmall);
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(fs::exists(out / "c.exr"));
    r = run("reference " + sphere + " --env " + lights("sky.hdr") + " --env-rotate -30 -o " + out / "r.exr" + kSmall);
    CAPTURE(r.output);
    CHECK(r.status == 0);
    const strata::RgbImage ref = strata::readRgb(out / "r.exr");
    CHECK(ref.variance.size() == ref.rgb.size());
    r = run("render " + sphere + " --env " + lights("sky.hdr") + " --stats -o " + out / "m.exr" + kSmall);
    CHECK(r.status == 0);
    CHECK(r.output.find("environment, environment-map") != std::string::npos);
    // Whole turns change nothing, bit for bit, however many (before, 370
    // degrees was carried as such and rounded differently from 10).
    const std::string map = " --env " + lights("sky.hdr") + " --quiet";
    REQUIRE(run("render " + sphere + map + " --env-rotate 10 -o " + out / "t1.exr" + kSmall).status == 0);
    for (const char* turns : {"370", "3600010", "-350"}) {
        CAPTURE(turns);
        REQUIRE(run("render " + sphere + map + " --env-rotate " + turns + " -o " + out / "t2.exr" + kSmall).status == 0);
        CHECK(strata::readRgb(out / "t1.exr").rgb == strata::readRgb(out / "t2.exr").rgb);
    }
}

TEST_CASE("lights cli: a light's range is ignored with one warning") {
    TempDir out;
    const Run r = run("render " + lights("range.gltf") + " -o " + out / "a.exr" + kSmall);
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.find(": warning: 1 punctual light(s) give a range") != std::string::npos);
}

TEST_SUITE_END();
