// strata reference / compare / converge as a user runs them.
#include <doctest/doctest.h>

#include "cli_util.h"


#include <filesystem>
#include <fstream>
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/image_io.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

const std::string kBox = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";

// Bad input: exit 2 and one line that says "error: ".
void checkRejected(const std::string& args) {
    CAPTURE(args);
    const Run r = run(args);
    CAPTURE(r.output);
    CHECK(r.status == 2);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
    CHECK(r.output.find("error: ") != std::string::npos);
}

}  // namespace

TEST_CASE("reference stores per-pixel variance, compare measures against it, converge reports") {
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
          "compare " + (d / "a.exr") + " " + (d / "a.exr") + " --json " + (d / "m.txt"),
          "reference " + kBox + " -o " + (d / "r.exr"), "reference " + kBox + " --spp 4 -o " + (d / "r.png"),
          "converge " + kBox + " -o " + (d / "c.csv"),
          "converge " + kBox + " --reference " + (d / "a.exr") + " -o " + (d / "c.txt"),
          "converge " + kBox + " --reference " + (d / "a.exr") + " --spp 4,2 -o " + (d / "c.csv")}) {
        checkRejected(args);
    }
    CHECK_FALSE(fs::exists(d / "r.exr"));
    CHECK_FALSE(fs::exists(d / "c.csv"));
    CHECK_FALSE(fs::exists(d / "m.txt"));
    // An empty file and a directory are named as such, not in the image
    // library's words.
    std::ofstream(d / "empty.exr").close();
    fs::create_directory(d / "dir.exr");
    const Run empty = run("compare " + (d / "empty.exr") + " " + (d / "a.exr"));
    CHECK(empty.output == (d / "empty.exr") + ": error: cannot read image: empty file\n");
    const Run dir = run("compare " + (d / "a.exr") + " " + (d / "dir.exr"));
    CHECK(dir.output == (d / "dir.exr") + ": error: cannot read image: is a directory\n");
    // A reference with a NaN: compare counts and excludes it, but converge and
    // bench, whose error figures would leave it out unsaid, refuse it.
    {
        std::ofstream f(d / "nan.pfm", std::ios::binary);
        f << "PF\n8 8\n-1.0\n";
        for (int i = 0; i < 8 * 8 * 3; ++i) {
            const float v = i == 100 ? std::numeric_limits<float>::quiet_NaN() : 0.25f;
            f.write(reinterpret_cast<const char*>(&v), sizeof v);
        }
    }
    const Run counted = run("compare " + (d / "a.exr") + " " + (d / "nan.pfm"));
    CHECK(counted.status == 0);
    CHECK(counted.output.find("1 non-finite (excluded)") != std::string::npos);
    for (const std::string& args :
         {"converge " + kBox + " --reference " + (d / "nan.pfm") + " --spp 1,2 -o " + (d / "n.csv"),
          "bench " + kBox + " --reference " + (d / "nan.pfm") + " --width 8 --height 8 --spp 1 --quick"}) {
        checkRejected(args);
        CHECK(run(args).output.find("has a non-finite value (NaN or Inf)") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(d / "n.csv"));
    // A truncated image, for which OpenImageIO gives no reason, still gets one.
    std::ofstream(d / "cut.pfm", std::ios::binary) << "PF\n8 8\n-1.0\n0123456789";
    const Run cut = run("compare " + (d / "a.exr") + " " + (d / "cut.pfm"));
    CHECK(cut.output == (d / "cut.pfm") + ": error: cannot read image: the file is truncated or corrupt\n");
}

namespace {

nlohmann::json readJson(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f);
}

}  // namespace

TEST_CASE("bench reports every section with consistent numbers") {
    TempDir d;
    const Run r = run("bench " + kBox + " --quick --width 64 --height 48 --spp 2 --reps 1 --json " + (d / "b.json"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    for (const char* section : {"start-up:", "BVH:", "traversal (", "path tracing (", "dispatch throughput ("})
        CHECK(r.output.find(section) != std::string::npos);
    const nlohmann::json j = readJson(d / "b.json");
    for (const char* key : {"features", "startup", "bvh", "traversal", "path_tracing", "dispatch", "memory"})
        CHECK(j.contains(key));
    CHECK(j["memory"]["scene_device_bytes"].get<double>() >= j["memory"]["scene_packed_bytes"].get<double>());
    CHECK(j["memory"]["host_peak_rss_bytes"].get<double>() > 0.0);

    // Traversal: the peer's three ray sets.
    // lavapipe (a CPU device) traces the bench's rays through the work queue.
    CHECK(j["traversal"]["work_queue"].get<bool>() == (j["device_type"] == "CPU"));
    const auto& rays = j["traversal"]["rays"];
    CHECK(rays["primary"]["rays"].get<int>() == 64 * 48);
    // One diffuse ray per primary hit; occlusion rays only from hits facing the point.
    CHECK(rays["diffuse"]["rays"].get<int>() == rays["primary"]["hits"].get<int>());
    CHECK(rays["occlusion"]["rays"].get<int>() <= rays["primary"]["hits"].get<int>());
    CHECK(rays["primary"]["hits"].get<int>() > 64 * 48 / 2);
    for (const char* set : {"primary", "diffuse", "occlusion"}) CHECK(rays[set]["mrays_per_s"].get<double>() > 0.0);

    // BVH and features: the Cornell box has emissive triangles and nothing else.
    CHECK(j["bvh"]["nodes"].get<int>() == 33);
    CHECK(j["features"] == nlohmann::json::array({"lights"}));

    // Path tracing: counts from the device's ray counters.
    const auto& p = j["path_tracing"];
    const auto samples = p["samples"].get<std::uint64_t>();
    CHECK(samples == 64u * 48u * 2u);
    const auto closest = p["closest_rays"].get<std::uint64_t>(), shadow = p["shadow_rays"].get<std::uint64_t>();
    CHECK(p["rays"].get<std::uint64_t>() == closest + shadow);
    CHECK(closest >= samples);  // every path traces its camera ray
    CHECK(shadow > 0);
    const int maxDepth = p["max_depth"].get<int>();
    CHECK(maxDepth == 16);
    const double length = p["mean_path_length"].get<double>();
    CHECK(length == doctest::Approx(static_cast<double>(closest) / samples));
    CHECK(length > 1.0);
    CHECK(length <= maxDepth + 1.0);
    CHECK(p["shadow_rays_per_sample"].get<double>() <= maxDepth);  // at most one per scattering vertex
    CHECK(p["msamples_per_s"].get<double>() > 0.0);
    CHECK(p["mrays_per_s"].get<double>() >= p["msamples_per_s"].get<double>());
    CHECK(p["non_finite"].get<int>() == 0);
    CHECK(p["relmse"].is_null());  // no reference given
    CHECK(p["ray_counting"]["device_s_counting"].get<double>() > 0.0);
    CHECK(p["ray_counting"]["device_s_not_counting"].get<double>() > 0.0);

    // Dispatch throughput: one dispatch per sample below the tile size.
    const auto& sizes = j["dispatch"]["sizes"];
    REQUIRE(sizes.size() == 2);
    CHECK(sizes[0]["size"].get<int>() == 64);
    CHECK(sizes[1]["size"].get<int>() == 128);
    int renders = 0;
    for (const auto& row : sizes) {
        CAPTURE(row.dump());
        ++renders;
        CHECK(row["dispatches_per_sample"].get<int>() == 1);
        CHECK(row["dispatches"].get<int>() == row["spp"].get<int>() * row["dispatches_per_sample"].get<int>());
        CHECK(row["submissions"].get<int>() >= 1);
        CHECK(row["submissions"].get<int>() <= row["dispatches"].get<int>());
        CHECK(row["dispatches_per_submission"].get<double>() * row["submissions"].get<int>() ==
              doctest::Approx(row["dispatches"].get<int>()));
        CHECK(row["device_ms_per_dispatch"].get<double>() > 0.0);
        CHECK(row["host_ms_per_submit"].get<double>() > 0.0);
        CHECK(row["dispatches_per_s"].get<double>() > 0.0);
    }
    const auto& batching = j["dispatch"]["batching"];
    const int spp = batching["spp"].get<int>();
    for (const auto& run : batching["runs"]) {
        CAPTURE(run.dump());
        ++renders;
        const int n = run["recorded_per_submission"].get<int>();
        CHECK(run["dispatches"].get<int>() == spp);
        CHECK(run["submissions"].get<int>() == (spp + n - 1) / n);
    }
    CHECK(batching["runs"].size() == 3);

    // Start-up: one pipeline per render the bench made.
    const auto& su = j["startup"];
    renders += 1 + 2 * p["ray_counting"]["pairs"].get<int>();
    CHECK(su["pipelines_created"].get<int>() == renders);
    CHECK(su["pipeline_ms"].get<double>() > 0.0);
    CHECK(su["load_ms"].get<double>() > 0.0);
    CHECK(su["first_dispatch_pixels"].get<int>() == 64 * 48);
    CHECK(su["first_dispatch_device_ms_64"].get<double>() > 0.0);
    CHECK(su["first_dispatch_device_ms"].get<double>() > 0.0);
    CHECK(su["bvh_build_ms"].get<double>() == j["bvh"]["build_ms"].get<double>());
}

TEST_CASE("bench relMSE: zero against a reference of the same seed, positive against another seed" * doctest::test_suite("slow")) {
    TempDir d;
    const std::string size = " --width 32 --height 24 --spp 2";
    for (int seed : {0, 1}) {
        const Run r = run("reference " + kBox + size + " --seed " + std::to_string(seed) + " --quiet -o " +
                          (d / ("ref" + std::to_string(seed) + ".exr")));
        CAPTURE(r.output);
        REQUIRE(r.status == 0);
    }
    for (int seed : {0, 1}) {
        CAPTURE(seed);
        const Run r = run("bench " + kBox + size + " --quick --reps 1 --seed 0 --reference " +
                          (d / ("ref" + std::to_string(seed) + ".exr")) + " --json " + (d / "b.json"));
        CAPTURE(r.output);
        REQUIRE(r.status == 0);
        CHECK(r.output.find("relMSE ") != std::string::npos);
        const nlohmann::json p = readJson(d / "b.json")["path_tracing"];
        REQUIRE(p["relmse"].is_number());
        if (seed == 0) {
            CHECK(p["relmse"].get<double>() == 0.0);  // the same render, bit for bit
            CHECK(p["efficiency"].is_null());
        } else {
            CHECK(p["relmse"].get<double>() > 0.0);
            CHECK(p["efficiency"].get<double>() > 0.0);
        }
    }
}

TEST_CASE("bench takes render's environment flags: its image is the reference's, and the default white environment without them" * doctest::test_suite("slow")) {
    TempDir d;
    const std::string board = std::string(STRATA_SOURCE_DIR) + "/scenes/materials-board-env.gltf";
    const std::string sky = std::string(STRATA_SOURCE_DIR) + "/scenes/env/sky.hdr";
    const std::string env = " --env " + sky + " --env-intensity 2 --env-rotate 30";
    const std::string size = " --width 32 --height 24 --spp 2 --seed 0";
    Run r = run("reference " + board + size + env + " --quiet -o " + (d / "ref.exr"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    // The board's only light is the environment.
    r = run("bench " + board + size + env + " --quick --reps 1 --reference " + (d / "ref.exr") + " --json " +
            (d / "b.json"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    CHECK(r.output.find("environment " + sky) != std::string::npos);
    nlohmann::json j = readJson(d / "b.json");
    CHECK(j["environment"] == sky);
    const auto& features = j["features"];
    CHECK(std::find(features.begin(), features.end(), "environment-map") != features.end());
    CHECK(j["path_tracing"]["relmse"].get<double>() == 0.0);  // the same render, bit for bit
    CHECK(j["path_tracing"]["shadow_rays"].get<double>() > 0.0);
    // Without the flags nothing in the file emits: bench, as render, lights
    // the board with the default white environment, not the sky.
    r = run("bench " + board + size + " --quick --reps 1 --reference " + (d / "ref.exr") + " --json " +
            (d / "b.json"));
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    j = readJson(d / "b.json");
    CHECK(j["environment"] == strata::kDefaultEnvironment);
    CHECK(j["path_tracing"]["shadow_rays"].get<double>() > 0.0);
    CHECK(j["path_tracing"]["relmse"].get<double>() > 0.1);
}

TEST_CASE("bench --reads chooses the read mode, and texel views and storage buffers find the same hits") {
    TempDir d;
    std::vector<nlohmann::json> rays;
    for (const char* mode : {"texel", "storage"}) {
        CAPTURE(mode);
        const Run r = run("bench " + kBox + " --only traversal --width 32 --height 24 --reps 1 --reads " +
                          mode + " --json " + (d / "b.json"));
        CAPTURE(r.output);
        REQUIRE(r.status == 0);
        const nlohmann::json j = readJson(d / "b.json")["traversal"];
        CHECK(j["reads"] == mode);
        rays.push_back(j["rays"]);
    }
    for (const char* set : {"primary", "diffuse"}) CHECK(rays[0][set]["hits"] == rays[1][set]["hits"]);
    CHECK(rays[0]["occlusion"]["occluded"] == rays[1]["occlusion"]["occluded"]);
    CHECK(rays[0]["primary"]["hits"].get<int>() > 32 * 24 / 2);
}

TEST_CASE("bench rejects bad flags and a mismatched reference with one line and exit 2") {
    TempDir d;
    REQUIRE(run("render " + kBox + " --spp 1 --width 16 --height 8 --quiet -o " + (d / "r.exr")).status == 0);
    for (const std::string& args : std::vector<std::string>{
             "bench", "bench " + kBox + " --spp 0", "bench " + kBox + " --width 0", "bench " + kBox + " --bogus",
             "bench " + kBox + " --spp", "bench " + kBox + " --max-depth -1",
             "bench " + kBox + " --traversal fast", "bench " + kBox + " --bvh 3",
             "bench " + kBox + " --bvh-stack heap", "bench " + kBox + " --texture-max-size 0",
             "bench " + kBox + " --texture-max-size 65537",
             "bench " + kBox + " --quick --reference " + (d / "r.exr"),  // 1024x768 against 16x8
             "bench " + kBox + " --quick --width 16 --height 16 --reference " + (d / "r.exr"),
             "bench " + kBox + " --quick --width 16 --height 8 --reference " + (d / "none.exr"),
             "bench " + kBox + " --quick --json " + (d / "b.txt"),
             "bench " + kBox + " --quick --env-rotate 30",  // needs --env or --env-color
             "bench " + kBox + " --quick --env-color 1,1,1 --env " + (d / "r.exr"),
             "bench " + kBox + " --quick --env " + (d / "none.hdr")}) {
        checkRejected(args);
    }
    CHECK_FALSE(fs::exists(d / "b.txt"));
}

TEST_SUITE_END();
