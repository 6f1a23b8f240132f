// strata reference / compare / converge as a user runs them.
#include <doctest/doctest.h>

#include "cli_util.h"


#include <filesystem>
#include <fstream>
#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/image_io.h"

namespace fs = std::filesystem;
using namespace strata::test;

namespace {

const std::string kBox = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";

}  // namespace

TEST_CASE("reference stores per-pixel variance; compare measures against it; converge reports") {
    TempDir d;
    Run r = run("reference " + kBox + " --spp 64 --width 16 --height 16 --quiet -o " + (d / "ref.exr"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    const strata::RgbImage ref = strata::readRgb(d / "ref.exr");
    CHECK(ref.width == 16);
    REQUIRE(ref.variance.size() == ref.rgb.size());
    std::size_t positive = 0;
    for (float v : ref.variance) positive += v > 0.0f;
    CHECK(positive > ref.variance.size() / 2);

    // An image against itself: every error is exactly zero.
    r = run("compare " + (d / "ref.exr") + " " + (d / "ref.exr") + " --json " + (d / "m.json"));
    CAPTURE(r.output);
    CHECK(r.status == 0);
    std::ifstream mj(d / "m.json");
    const std::string m((std::istreambuf_iterator<char>(mj)), std::istreambuf_iterator<char>());
    CHECK(m.find("\"relmse\": 0.0") != std::string::npos);

    r = run("converge " + kBox + " --reference " + (d / "ref.exr") + " --spp 1,4,16 --seeds 2 --quiet -o " +
            (d / "c.json") + " --plot " + (d / "c.png"));
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(fs::file_size(d / "c.png") > 1000);
    std::ifstream cj(d / "c.json");
    const std::string c((std::istreambuf_iterator<char>(cj)), std::istreambuf_iterator<char>());
    CHECK(c.find("\"slope_relmse_vs_spp\"") != std::string::npos);
    CHECK(c.find("\"bias_floor_b2\"") != std::string::npos);
}

TEST_CASE("measurement commands reject bad input with one line and exit 2") {
    TempDir d;
    REQUIRE(run("render " + kBox + " --spp 1 --width 8 --height 8 --quiet -o " + (d / "a.exr")).status == 0);
    REQUIRE(run("render " + kBox + " --spp 1 --width 8 --height 4 --quiet -o " + (d / "b.exr")).status == 0);
    std::ofstream(d / "junk.exr") << "not an image";
    for (const std::string& args : std::vector<std::string>{
             "compare " + (d / "a.exr") + " " + (d / "b.exr"), "compare " + (d / "a.exr"),
          "compare " + (d / "junk.exr") + " " + (d / "a.exr"), "compare " + (d / "a.exr") + " " + (d / "none.exr"),
          "reference " + kBox + " -o " + (d / "r.exr"), "reference " + kBox + " --spp 4 -o " + (d / "r.png"),
          "converge " + kBox + " -o " + (d / "c.csv"),
          "converge " + kBox + " --reference " + (d / "a.exr") + " -o " + (d / "c.txt"),
          "converge " + kBox + " --reference " + (d / "a.exr") + " --spp 4,2 -o " + (d / "c.csv")}) {
        CAPTURE(args);
        const Run r = run(args);
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
        CHECK(r.output.find("error: ") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(d / "r.exr"));
    CHECK_FALSE(fs::exists(d / "c.csv"));
}

TEST_CASE("bench traces the peer's three ray sets and reports consistent counts") {
    TempDir d;
    const Run r = run("bench " + kBox + " --width 64 --height 48 --reps 1 --json " + (d / "b.json"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    std::ifstream f(d / "b.json");
    const nlohmann::json j = nlohmann::json::parse(f);
    const auto& rays = j["rays"];
    CHECK(rays["primary"]["rays"].get<int>() == 64 * 48);
    // One diffuse ray per primary hit; occlusion rays only from hits facing the point.
    CHECK(rays["diffuse"]["rays"].get<int>() == rays["primary"]["hits"].get<int>());
    CHECK(rays["occlusion"]["rays"].get<int>() <= rays["primary"]["hits"].get<int>());
    CHECK(rays["primary"]["hits"].get<int>() > 64 * 48 / 2);
    for (const char* set : {"primary", "diffuse", "occlusion"}) CHECK(rays[set]["mrays_per_s"].get<double>() > 0.0);
    CHECK(j["bvh"]["nodes"].get<int>() == 33);
    CHECK(run("bench " + kBox + " --json " + (d / "b.txt")).status == 2);
}
