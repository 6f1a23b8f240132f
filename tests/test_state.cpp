// State files, resume, shards and merge (render/state.h, render/merge.h):
// fixed-point sums that add exactly, the file's checks, and the real binary
// on lavapipe rendering shards, resuming and merging to the bits of a single
// render.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "cli_util.h"
#include "image/image_io.h"
#include "render/state.h"
#include "test_util.h"
#include "util/error.h"

using namespace strata;
using namespace strata::test;

namespace {

// A film of `w` x 1 pixels and its batches: `batches` device batches of
// floats spread over twelve orders of magnitude, with AOVs.
std::vector<std::vector<float>> randomBatches(int w, int batches, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), e(-6.0f, 6.0f);
    const Film shape(w, 1, true);
    std::vector<std::vector<float>> out(batches, std::vector<float>(shape.batchFloats()));
    for (auto& b : out)
        for (std::size_t i = 0; i < b.size(); ++i) {
            const bool countSlot = i < std::size_t(w) * 8 && i % 8 == 3;
            b[i] = countSlot ? 64.0f : u(rng) * std::pow(10.0f, e(rng)) * (i % 5 == 4 ? -1.0f : 1.0f);
        }
    return out;
}

bool sameSums(const Film& a, const Film& b) {
    return a.sum == b.sum && a.sumSq == b.sumSq && a.count == b.count && a.aovSum == b.aovSum &&
           a.overflowed == b.overflowed;
}

RenderState sampleState(std::uint32_t seed) {
    RenderState st;
    st.info.scene = "scene.gltf";
    st.info.sceneHash = "0123456789abcdef";
    st.info.settings = {{"width", 5}, {"height", 1}, {"seed", 0}, {"max-depth", 16}};
    st.info.implementation = {{"device", "a device"}, {"driver", "a driver"}, {"integrator", "megakernel"}, {"bvh", 4}};
    st.info.spp = 300;
    st.info.shard = 2;
    st.info.shards = 4;
    const auto batches = randomBatches(5, 3, seed);
    st.acc.film = Film(5, 1, true);
    st.acc.film.fold(batches[0].data());
    st.acc.film.fold(batches[1].data());
    st.acc.film.overflowed = 7;
    st.acc.pending = batches[2];
    st.acc.begin = 128;
    st.acc.folded = 192;
    st.acc.end = 200;
    st.acc.nonFinite = 3;
    return st;
}

std::string slurp(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void spit(const std::string& path, const std::string& bytes) {
    std::ofstream f(path, std::ios::binary);
    f << bytes;
}

std::string readError(const std::string& path) {
    try {
        readState(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("state: fixed-point film sums are the same bits whatever the grouping of the batches") {
    const auto batches = randomBatches(64, 12, 1);
    Film whole(64, 1, true);
    for (const auto& b : batches) whole.fold(b.data());
    // Split into runs (shards) summed apart and added, in another order.
    for (const std::vector<int>& cuts : {std::vector<int>{0, 3, 6, 9, 12}, {0, 1, 11, 12}, {0, 5, 12}}) {
        std::vector<Film> parts;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
            Film part(64, 1, true);
            for (int j = cuts[k]; j < cuts[k + 1]; ++j) part.fold(batches[j].data());
            parts.push_back(part);
        }
        Film merged(64, 1, true);
        for (auto it = parts.rbegin(); it != parts.rend(); ++it) merged.add(*it);
        CHECK(sameSums(merged, whole));
        CHECK(merged.mean() == whole.mean());
    }
    // The same data in double, grouped the same ways, does not agree bit for
    // bit: the test's data is hard enough for the exactness to matter.
    int doubleDiffers = 0;
    for (std::size_t i = 0; i < batches[0].size(); ++i) {
        double seq = 0.0, a = 0.0, b = 0.0;
        for (int j = 0; j < 12; ++j) seq += batches[j][i];
        for (int j = 0; j < 6; ++j) a += batches[j][i];
        for (int j = 6; j < 12; ++j) b += batches[j][i];
        doubleDiffers += seq != a + b;
    }
    CHECK(doubleDiffers > 0);
}

TEST_CASE("state: fixed-point sums convert floats exactly and keep what is beyond their range infinite") {
    for (float x : {0.0f, 1.0f, 0.1f, 1.0e-7f, 123456.789f, -2.5f, 1.0e20f, 5.0e23f})
        CHECK(fromFixed(toFixed(x)) == static_cast<double>(x));
    CHECK(fromFixed(toFixed(1.0e-30f)) == 0.0);  // below 2^-48: truncated
    const float inf = std::numeric_limits<float>::infinity();
    CHECK(std::isinf(fromFixed(toFixed(inf))));
    CHECK(std::isinf(fromFixed(toFixed(1.0e24f))));  // 2^79 and beyond
    CHECK(fromFixed(toFixed(-inf)) < 0.0);
    CHECK(addFixed(toFixed(inf), toFixed(1.0f)) == kFixedInf);
    CHECK(addFixed(toFixed(4.0e23f), toFixed(4.0e23f)) == kFixedInf);  // the sum beyond the range
    CHECK(fromFixed(addFixed(toFixed(1.5f), toFixed(-0.25f))) == 1.25);
}

TEST_CASE("state: a state file reads back whole, and every damaged or foreign file is one clear error") {
    TempDir dir;
    const RenderState st = sampleState(2);
    writeState(dir / "a.state", st);
    const RenderState back = readState(dir / "a.state");
    CHECK(sameSums(back.acc.film, st.acc.film));
    CHECK(back.acc.pending == st.acc.pending);
    CHECK(back.acc.begin == 128);
    CHECK(back.acc.folded == 192);
    CHECK(back.acc.end == 200);
    CHECK(back.acc.nonFinite == 3);
    CHECK(back.info.settings == st.info.settings);
    CHECK(back.info.implementation == st.info.implementation);
    CHECK(back.info.sceneHash == st.info.sceneHash);
    CHECK(back.info.shard == 2);
    CHECK(back.info.shards == 4);
    CHECK(back.info.spp == 300);
    CHECK(std::filesystem::exists(dir / "a.state.tmp") == false);

    const std::string bytes = slurp(dir / "a.state");
    const std::string p = dir / "bad.state";
    const auto expectFails = [&](const std::string& content, const std::string& what) {
        spit(p, content);
        const std::string e = readError(p);
        CAPTURE(what);
        CHECK(e.rfind(p + ": error: ", 0) == 0);
        CHECK(e.find(what) != std::string::npos);
        CHECK(e.find('\n') == std::string::npos);
    };
    for (std::size_t keep : {std::size_t(0), std::size_t(10), std::size_t(40), bytes.size() / 2, bytes.size() - 1})
        expectFails(bytes.substr(0, keep), keep < 16 ? "not a strata state file" : "truncated");
    expectFails(bytes + "x", "corrupted state file");
    for (std::size_t at : {bytes.size() - 200, bytes.size() - 4}) {  // the sums, the checksum
        std::string flipped = bytes;
        flipped[at] ^= 0x10;
        expectFails(flipped, "checksum does not match");
    }
    std::string version = bytes;
    version[8] = 9;
    expectFails(version, "state file format version 9; this strata reads version 1");
    std::string magic = bytes;
    magic[0] = 'X';
    expectFails(magic, "not a strata state file");
    std::string header = bytes;
    header.replace(header.find("\"folded\":192"), 12, "\"folded\":191");
    expectFails(header, "corrupted state file: samples 128-200 (folded to 191)");
    std::string shard = bytes;
    shard.replace(shard.find("\"shard\":[2,4]"), 13, "\"shard\":[4,4]");
    expectFails(shard, "shard 4/4 (I must be below K)");
    std::string json = bytes;
    json[20] = '{';
    expectFails(json, "its header is not readable");
    std::string format = bytes;  // valid JSON of the wrong type
    format.replace(format.find("\"strata state\""), 14, "12345678901234");
    expectFails(format, "its header is not readable");
    CHECK(readError(dir / "missing.state").find("cannot read the state file") != std::string::npos);
}

TEST_CASE("state: shards are contiguous runs of whole batches that cover the samples, or a clear error") {
    for (std::uint32_t spp : {64u, 200u, 256u, 1000u, 4096u})
        for (std::uint32_t k = 1; k <= 16; ++k) {
            if ((spp + 63) / 64 < k) {
                CHECK_THROWS_AS(shardRange(spp, 0, k, 64), Error);
                continue;
            }
            std::uint32_t next = 0, fewest = ~0u, most = 0;
            for (std::uint32_t i = 0; i < k; ++i) {
                const SampleRange r = shardRange(spp, i, k, 64);
                CHECK(r.begin == next);
                CHECK(r.begin % 64 == 0);
                CHECK(r.end > r.begin);
                next = r.end;
                fewest = std::min(fewest, (r.end - r.begin + 63) / 64);
                most = std::max(most, (r.end - r.begin + 63) / 64);
            }
            CHECK(next == spp);
            CHECK(most - fewest <= 1);
        }
    CHECK_THROWS_WITH_AS(shardRange(256, 4, 4, 64), doctest::Contains("I must be below K"), Error);
}

TEST_CASE("state: states of another scene or with other settings do not combine, and the difference is named") {
    StateInfo a = sampleState(1).info, b = a;
    CHECK(stateMismatch(a, "a.state", b, "b.state").empty());
    b.settings["max-depth"] = 8;
    CHECK(stateMismatch(a, "a.state", b, "b.state") ==
          "settings differ: max-depth is 8 in b.state, 16 in a.state");
    b = a;
    b.settings.erase("seed");
    CHECK(stateMismatch(a, "a.state", b, "b.state") == "settings differ: seed is unset in b.state, 0 in a.state");
    b = a;
    b.sceneHash = "fedcba9876543210";
    CHECK(stateMismatch(a, "a.state", b, "b.state").rfind("not the same scene", 0) == 0);
    b = a;
    b.implementation["device"] = "another device";  // may combine (statistically)
    CHECK(stateMismatch(a, "a.state", b, "b.state").empty());
    CHECK_FALSE(sameImplementation(a, b));
    CHECK(sameImplementation(a, a));
    b.implementation["device"] = 7;  // whatever a header holds reads as text
    CHECK(implementationText(b.implementation) == "7 (a driver), megakernel, bvh 4");
}

TEST_SUITE_END();

namespace {

const std::string kCornell = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
const std::string kSmall = " --width 32 --height 32 --quiet";

void renderOk(const std::string& args) {
    const Run r = run("render " + kCornell + kSmall + " " + args);
    CAPTURE(args);
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
}

void mergeOk(const std::string& args) {
    const Run r = run("merge --quiet " + args);
    CAPTURE(args);
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
}

// Exit 2, one line naming `file`, and no output file: the command's outputs
// are all in `out`, which it leaves as it was.
void expectRefused(const std::string& args, const std::string& file, const std::string& what, const TempDir& out) {
    std::vector<std::string> before;
    for (const auto& e : std::filesystem::directory_iterator(out.path)) before.push_back(e.path().string());
    const Run r = run(args);
    CAPTURE(args);
    CAPTURE(r.output);
    CHECK(r.status == 2);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.rfind(file + ": error: ", 0) == 0);
    CHECK(r.output.find(what) != std::string::npos);
    std::vector<std::string> after;
    for (const auto& e : std::filesystem::directory_iterator(out.path)) after.push_back(e.path().string());
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    CHECK(after == before);
}

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("state: shards merged in any order are the bits of a single render, also with a partial last batch and "
          "AOVs") {
    TempDir d;
    // 200 spp: four batches, the last of 8 samples; three shards of 1, 1 and
    // 2 batches, the last ending inside its second batch.
    renderOk("--spp 200 --aov -o " + d / "one.exr" + " -o " + d / "one.state");
    std::string shards;
    for (int i : {2, 0, 1}) {
        renderOk("--spp 200 --aov --shard " + std::to_string(i) + "/3 -o " + d / ("s" + std::to_string(i) + ".state"));
        shards += " " + d / ("s" + std::to_string(i) + ".state");
    }
    mergeOk(shards + " -o " + d / "merged.exr" + " -o " + d / "merged.state");
    const Image one = readImage(d / "one.exr"), merged = readImage(d / "merged.exr");
    CHECK(merged.channelNames == one.channelNames);
    CHECK(merged.pixels == one.pixels);  // every channel, the AOV layers too
    CHECK(merged.attributes == one.attributes);
    CHECK(slurp(d / "merged.state") == slurp(d / "one.state"));
    // Merged in two steps: the first two shards into a partial state, then the rest.
    mergeOk(d / "s1.state" + " " + d / "s0.state" + " -o " + d / "part.state");
    mergeOk(d / "part.state" + " " + d / "s2.state" + " -o " + d / "two-step.exr");
    CHECK(readImage(d / "two-step.exr").pixels == one.pixels);
}

TEST_CASE("state: a render resumed from its state, also one stopped by SIGINT, is the bits of an uninterrupted one" *
          doctest::test_suite("slow")) {
    TempDir d;
    renderOk("--spp 300 -o " + d / "full.exr" + " -o " + d / "full.state");
    // Stopped at 100 (inside the second batch), resumed to 300.
    renderOk("--spp 100 -o " + d / "part.state");
    renderOk("--spp 300 --resume " + d / "part.state" + " -o " + d / "resumed.exr" + " -o " + d / "resumed.state");
    CHECK(readRgb(d / "resumed.exr").rgb == readRgb(d / "full.exr").rgb);
    CHECK(slurp(d / "resumed.state") == slurp(d / "full.state"));
    // A shard resumed: shard 1/2 of 200 spp (samples 128-200) continued as
    // shard 1/2 of 300 (samples 128-300).
    renderOk("--spp 200 --shard 1/2 -o " + d / "s1-part.state");
    renderOk("--spp 300 --shard 1/2 --resume " + d / "s1-part.state" + " -o " + d / "s1.state");
    renderOk("--spp 300 --shard 0/2 -o " + d / "s0.state");
    mergeOk(d / "s0.state" + " " + d / "s1.state" + " -o " + d / "merged.exr");
    CHECK(readRgb(d / "merged.exr").rgb == readRgb(d / "full.exr").rgb);

    // SIGINT: the state holds the samples reached and resumes to the same bits.
    const Run r = signalled(" render " + kCornell + " --width 32 --height 32 --spp 1000000 -o " + d / "i.state",
                            {"-INT"}, 1.0, 0.0, d / "log");
    CAPTURE(r.output);
    REQUIRE(statusOf(r) == 130);
    const RenderState st = readState(d / "i.state");
    CAPTURE(st.acc.end);
    CHECK(st.acc.end > 0);
    const std::string n = std::to_string(st.acc.end + 70);
    renderOk("--spp " + n + " --resume " + d / "i.state" + " -o " + d / "i.exr");
    renderOk("--spp " + n + " -o " + d / "i-fresh.exr");
    CHECK(readRgb(d / "i.exr").rgb == readRgb(d / "i-fresh.exr").rgb);
}

TEST_CASE("state: --checkpoint-every leaves a state that survives SIGKILL and resumes to the same bits") {
    TempDir d;
    const std::string st = d / "c.state";
    const Run r = runShell("sh -c '" + std::string(STRATA_EXE) + " render " + kCornell +
                           " --width 32 --height 32 --spp 1000000 --checkpoint-every 0.5 -o " + st +
                           " >/dev/null 2>&1 & p=$!; n=0; while [ ! -f " + st +
                           " ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done; sleep 0.7; kill -KILL $p; "
                           "wait $p; echo status=$?'");
    CAPTURE(r.output);
    REQUIRE(r.output.find("status=137") != std::string::npos);
    const RenderState s = readState(st);  // whole: the rename is atomic
    CAPTURE(s.acc.end);
    CHECK(s.acc.end > 0);
    CHECK(s.acc.end < 1000000);
    const std::string n = std::to_string(s.acc.end + 40);
    renderOk("--spp " + n + " --resume " + st + " -o " + d / "resumed.exr");
    renderOk("--spp " + n + " -o " + d / "fresh.exr");
    CHECK(readRgb(d / "resumed.exr").rgb == readRgb(d / "fresh.exr").rgb);
}

TEST_CASE("state: a device lost or out of memory during a render is exit 3, one line and no image, "
          "and the latest checkpoint is kept and resumes to the same bits") {
    TempDir d;
    const std::string st = d / "c.state";
    // STRATA_FAULT (vk/buffer.cpp): the process's 8th submission ends as on
    // a lost device, and every later one; a checkpoint follows each submission.
    const Run r = run("render " + kCornell + kSmall + " --spp 1000000 --checkpoint-every 0.001 -o " + d / "c.exr" +
                          " -o " + st,
                      "STRATA_FAULT=device-lost:8");
    CAPTURE(r.output);
    CHECK(r.status == 3);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.rfind("strata: error: the Vulkan device was lost: ", 0) == 0);
    const RenderState s = readState(st);
    CAPTURE(s.acc.end);
    CHECK(s.acc.end > 0);
    CHECK(r.output.find("; the latest checkpoint (" + std::to_string(s.acc.end) + " spp) is kept in " + st +
                        ": go on with --resume " + st) != std::string::npos);
    std::vector<std::string> left;
    for (const auto& e : std::filesystem::directory_iterator(d.path)) left.push_back(e.path().string());
    CHECK(left == std::vector<std::string>{st});  // no image, no temporary file
    const std::string n = std::to_string(s.acc.end + 40);
    renderOk("--spp " + n + " --resume " + st + " -o " + d / "resumed.exr");
    renderOk("--spp " + n + " -o " + d / "fresh.exr");
    CHECK(readRgb(d / "resumed.exr").rgb == readRgb(d / "fresh.exr").rgb);

    // Out of device memory at the first submission: nothing to go on from, nothing written.
    TempDir e;
    const Run m = run("render " + kCornell + kSmall + " --spp 64 --checkpoint-every 0.001 -o " + e / "m.exr" + " -o " +
                          e / "m.state",
                      "STRATA_FAULT=out-of-device-memory:1");
    CAPTURE(m.output);
    CHECK(m.status == 3);
    CHECK(lines(m.output) == 1);
    CHECK(m.output.rfind("strata: error: the Vulkan device ran out of memory: ", 0) == 0);
    CHECK(m.output.find("; no checkpoint was written (--checkpoint-every SECONDS writes them)") != std::string::npos);
    CHECK(e.empty());
    // A malformed fault is refused, not ignored.
    const Run bad = run("render " + kCornell + kSmall + " --spp 1 -o " + e / "b.exr", "STRATA_FAULT=device-lost");
    CHECK(bad.status == 3);
    CHECK(bad.output.find("STRATA_FAULT=device-lost: expected device-lost:N or out-of-device-memory:N") !=
          std::string::npos);
    CHECK(e.empty());
}

TEST_CASE("state: mismatched, overlapping, missing and damaged states are refused with one line and no output") {
    TempDir d, out;
    renderOk("--spp 256 --shard 0/4 -o " + d / "s0.state");
    renderOk("--spp 256 --shard 1/4 -o " + d / "s1.state");
    renderOk("--spp 256 --shard 3/4 -o " + d / "s3.state");
    renderOk("--spp 256 --shard 1/4 --max-depth 3 -o " + d / "depth.state");
    const std::string o = " -o " + out / "m.exr" + " -o " + out / "m.state";
    expectRefused("merge " + d / "s0.state" + " " + d / "s1.state" + " " + d / "s3.state" + o, d / "s3.state",
                  "samples 128-192 of 256 are in no state (shard 2/4)", out);
    expectRefused("merge " + d / "s0.state" + " " + d / "s1.state" + o, d / "s1.state",
                  "samples 128-256 of 256 are in no state (shard 2/4, 3/4)", out);
    expectRefused("merge " + d / "s0.state" + " " + d / "s1.state" + " " + d / "s1.state" + o, d / "s1.state",
                  "overlap", out);
    expectRefused("merge " + d / "s0.state" + " " + d / "depth.state" + o, d / "depth.state",
                  "settings differ: max-depth is 3 in " + d / "depth.state" + ", 16 in " + d / "s0.state", out);
    std::string bytes = slurp(d / "s1.state");
    spit(d / "cut.state", bytes.substr(0, bytes.size() / 3));
    expectRefused("merge " + d / "s0.state" + " " + d / "cut.state" + o, d / "cut.state", "truncated state file", out);
    bytes[bytes.size() / 2] ^= 1;
    spit(d / "flip.state", bytes);
    expectRefused("merge " + d / "s0.state" + " " + d / "flip.state" + o, d / "flip.state", "checksum", out);

    const std::string render = "render " + kCornell + kSmall + " -o " + out / "r.exr" + " -o " + out / "r.state";
    expectRefused(render + " --spp 256 --shard 1/4 --max-depth 3 --resume " + d / "s1.state", d / "s1.state",
                  "cannot resume: settings differ: max-depth is 3 in this render, 16 in " + d / "s1.state", out);
    expectRefused(render + " --spp 256 --shard 2/4 --resume " + d / "s1.state", d / "s1.state",
                  "this render is shard 2/4, samples 128-192", out);
    expectRefused(render + " --spp 256 --resume " + d / "s1.state", d / "s1.state", "this render is the whole render",
                  out);
    expectRefused("render " + std::string(STRATA_SOURCE_DIR) + "/scenes/furnace.gltf" + kSmall + " -o " +
                      out / "r.exr --spp 256 --shard 1/4 --resume " + d / "s1.state",
                  d / "s1.state", "cannot resume: not the same scene", out);
    expectRefused(render + " --spp 256 --resume " + d / "cut.state", d / "cut.state", "truncated state file", out);
    expectRefused(render + " --spp 256 --shard 4/4", "strata", "I must be below K", out);
    expectRefused(render + " --spp 100 --shard 2/4", "strata", "fewer than 4 shards", out);
    expectRefused(render + " --spp 256 --checkpoint-every 0", "strata", "--checkpoint-every", out);
    expectRefused("merge " + d / "s0.state" + " " + out / "r.exr" + " -o " + out / "m.exr", "strata",
                  "merge takes .state files", out);
    CHECK(out.empty());
}

// Shards from different devices: each device's arithmetic gives other
// samples of the same estimator, so the merged image is statistically the
// single render's, not its bits. This machine has one Vulkan device (and
// lavapipe's 128- and 256-bit modes give the same bits), so a shard
// rendered with another seed stands in for the other device's samples; its
// header names another device. The check: per pixel, the merged and the
// single image differ by at most 4 combined standard errors in all but 0.5%
// of the pixels, and their image means by at most 4 standard errors.
TEST_CASE("state: shards from different devices merge to an image statistically equivalent to a single render") {
    TempDir d;
    const Scene scene = loadGltf(kCornell);
    const GpuScene gpu = buildAndPack(scene);
    const Camera& camera = scene.cameras.at(0);
    const DeviceScene dev = uploadScene(context(), gpu, {});
    RenderSettings s;
    s.width = s.height = 32;
    s.spp = 512;
    const RenderResult single = render(context(), dev, camera, s);

    StateInfo info;
    info.scene = kCornell;
    info.sceneHash = sceneContentHash(gpu, camera);
    info.settings = stateSettings(s, camera, false);
    info.spp = s.spp;
    info.shards = 2;
    std::string files;
    for (std::uint32_t i = 0; i < 2; ++i) {
        const SampleRange r = shardRange(s.spp, i, 2, 64);
        RenderSettings shard = s;
        shard.seed = i == 1 ? 7u : 0u;  // the other device's samples
        SampleRun run;
        run.begin = r.begin;
        run.end = r.end;
        run.keep = true;
        RenderState st{info, render(context(), dev, camera, shard, {}, {}, run).state};
        st.info.shard = i;
        st.info.implementation = stateImplementation(i == 1 ? "another device" : context().info.name, "driver", s);
        writeState(d / ("s" + std::to_string(i) + ".state"), st);
        files += " " + d / ("s" + std::to_string(i) + ".state");
    }
    CHECK(vk::validationMessageCount() == 0);
    const Run m = run("merge" + files + " --variance -o " + d / "merged.exr");
    CAPTURE(m.output);
    REQUIRE(m.status == 0);
    CHECK(m.output.find("statistically equivalent to a single render, not the same bits") != std::string::npos);

    const RgbImage merged = readRgb(d / "merged.exr");
    const std::vector<float> mean = single.film.mean(), var = single.film.varianceOfMean();
    REQUIRE(merged.variance.size() == var.size());
    CHECK(merged.rgb != mean);  // other samples
    int outliers = 0;
    double diff = 0.0, diffVar = 0.0;
    for (std::size_t i = 0; i < mean.size(); ++i) {
        const double dv = double(merged.rgb[i]) - mean[i], v = double(merged.variance[i]) + var[i];
        outliers += std::abs(dv) > 4.0 * std::sqrt(v) + 1e-7;
        diff += dv;
        diffVar += v;
    }
    CAPTURE(outliers);
    CAPTURE(diff / std::sqrt(diffVar));
    CHECK(outliers <= int(0.005 * mean.size()));
    CHECK(std::abs(diff) <= 4.0 * std::sqrt(diffVar));
}

TEST_SUITE_END();
