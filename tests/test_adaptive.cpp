// Adaptive sampling (render/adaptive.h, --noise-threshold, --min-spp): a
// threshold met everywhere stops at the minimum; no pixel passes the cap and
// the blocks that stop keep their counts; the image agrees with a
// non-adaptive render (per-pixel Z-test); the bits do not depend on how the
// submissions were cut, and a render stopped and resumed from its state is
// the bits of one that ran through.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "render/adaptive.h"
#include "cli_util.h"
#include "image/aov.h"
#include "stats/stats.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("unit");

TEST_CASE("adaptive: the pixel error is the relMSE term's root, infinite below two samples, and blocks retire whole") {
    Film f(9, 1);
    // Pixel 0: samples 1 and 3 in every channel: mean 2, variance of the mean 1.
    for (int c = 0; c < 3; ++c) f.sum[c] = toFixed(4.0f), f.sumSq[c] = toFixed(10.0f);
    f.count[0] = 2;
    CHECK(pixelError(f, 0) == doctest::Approx(1.0 / std::sqrt(4.01)));
    f.count[1] = 1;
    CHECK(std::isinf(pixelError(f, 1)));
    // Pixels 1-7 (the rest of block 0) and pixel 8 (block 1): no noise.
    for (std::size_t i = 1; i < 9; ++i) {
        f.count[i] = 4;
        for (int c = 0; c < 3; ++c) f.sum[i * 3 + c] = toFixed(2.0f), f.sumSq[i * 3 + c] = toFixed(1.0f);
    }
    ActiveBlocks b(9, 1);
    REQUIRE(b.active.size() == 2);
    CHECK(b.activePixels(9, 1) == 9);
    retireConverged(f, 0.4, b);  // pixel 0's error, 0.4994, keeps block 0
    CHECK(b.active == std::vector<std::uint32_t>{1u, 0u});
    CHECK(b.activePixels(9, 1) == 8);
    retireConverged(f, 0.5, b);
    CHECK(b.activeCount() == 0);
}

TEST_CASE("adaptive: a bad threshold or minimum, or a shard, is one error line, exit 2, no output") {
    const std::string r = "render " + sourcePath("scenes/cornell-box.gltf");
    expectError(r + " --noise-threshold -0.1", "strata: error: --noise-threshold expects a threshold in (0, 1e+30]");
    expectError(r + " --noise-threshold nan", "strata: error: --noise-threshold expects a threshold");
    expectError(r + " --noise-threshold 0", "strata: error: --noise-threshold expects a threshold");
    expectError(r + " --noise-threshold 0.1 --min-spp 4", "strata: error: --min-spp 4 is above the cap --spp 1");
    expectError(r + " --min-spp 4", "strata: error: --min-spp needs --noise-threshold");
    expectError(r + " --noise-threshold 0.1 --shard 0/2", "strata: error: --shard and --noise-threshold exclude");
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("render");

namespace {

RenderSettings adaptiveSettings() {
    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.spp = 200;  // not a multiple of the step: the cap cuts the last batch
    s.maxDepth = 8;
    s.seed = 5;
    s.noiseThreshold = 0.08;
    return s;
}

}  // namespace

TEST_CASE("adaptive: a threshold met everywhere stops at the minimum, the first multiple of 16 from --min-spp") {
    RenderSettings s = adaptiveSettings();
    s.noiseThreshold = 1e3;
    Rendered r = renderFile("scenes/cornell-box.gltf", s);
    CHECK(r.result.spp == 16);
    CHECK(std::all_of(r.result.film.count.begin(), r.result.film.count.end(), [](auto n) { return n == 16; }));
    s.minSpp = 40;
    r = renderFile("scenes/cornell-box.gltf", s);
    CHECK(r.result.spp == 48);
    CHECK(std::all_of(r.result.film.count.begin(), r.result.film.count.end(), [](auto n) { return n == 48; }));
    CHECK(r.result.samplesTaken == 48u * 32u * 32u);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("adaptive: no pixel passes the cap, converged blocks keep their counts, and the image agrees (Z-test)") {
    const RenderSettings s = adaptiveSettings();
    const Rendered a = renderFile("scenes/cornell-box.gltf", s);
    const Film& f = a.result.film;
    std::set<std::uint64_t> counts;
    std::uint64_t total = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const std::uint64_t n = f.count[std::size_t(y) * f.width + x];
            CHECK(n <= s.spp);
            CHECK((n == s.spp || n % kAdaptiveStep == 0));
            // One count per block (the Cornell box gives no non-finite sample).
            CHECK(n == f.count[std::size_t(y / 8 * 8) * f.width + x / 8 * 8]);
            counts.insert(n);
            total += n;
        }
    MESSAGE("mean spp " << double(total) / f.pixels() << ", " << counts.size() << " distinct counts");
    CHECK(counts.size() >= 2);     // some blocks stopped before others
    CHECK(*counts.begin() < s.spp);
    CHECK(total == a.result.samplesTaken);
    // Each pixel's mean against a render of every pixel to 256 spp.
    RenderSettings full = s;
    full.noiseThreshold = 0.0;
    full.spp = 256;
    full.seed = 9;
    const Rendered b = renderFile("scenes/cornell-box.gltf", full);
    const auto mean = f.mean(), var = f.varianceOfMean();
    const auto refMean = b.result.film.mean(), refVar = b.result.film.varianceOfMean();
    const stats::ZTestResult z = stats::perPixelZTest(mean.data(), var.data(), refMean.data(), refVar.data(), mean.size());
    CAPTURE(z.acceptedFraction);
    CHECK(z.passed);
    CHECK(vk::validationMessageCount() == 0);
}

// The AOVs divide each pixel's sums by its own count: the albedo of an
// adaptive render is the full render's, and each pixel's halves weighted by
// their counts give its mean.
TEST_CASE("adaptive: the AOV layers read each pixel's own sample count") {
    RenderSettings s = adaptiveSettings();
    s.aov = true;
    const Rendered a = renderFile("scenes/cornell-box.gltf", s);
    RenderSettings full = s;
    full.noiseThreshold = 0.0;
    full.spp = 64;
    const Rendered b = renderFile("scenes/cornell-box.gltf", full);
    const AovImages x = aovImages(a.result.film), y = aovImages(b.result.film);
    const Film& f = a.result.film;
    REQUIRE(*std::min_element(f.count.begin(), f.count.end()) < s.spp);
    std::size_t close = 0;
    for (std::size_t i = 0; i < f.pixels(); ++i) {
        double diff = 0.0;
        for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(double(x.albedo[i * 3 + c]) - y.albedo[i * 3 + c]));
        close += diff < 0.05;
        const double n = double(f.count[i]), nA = std::ceil(n / 2.0);  // even sample indices 0, 2, ...
        const double weighted = (nA * x.halfA[i * 3] + (n - nA) * x.halfB[i * 3]) / n;
        CHECK(weighted == doctest::Approx(x.color[i * 3]).epsilon(1e-4));
    }
    CAPTURE(close);
    CHECK(close >= f.pixels() * 98 / 100);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("adaptive: the same bits however the submissions are cut, by either integrator, and a render resumed from its state") {
    const RenderSettings s = adaptiveSettings();
    SceneRequest request = keptRequest(s);
    request.file = sourcePath("scenes/cornell-box.gltf");
    const HostScene host = prepareScene(request);
    const DeviceScene dev = uploadPrepared(context(), request, host.gpu);
    const RenderResult whole = render(context(), dev, host.camera, s);
    RenderTuning oneByOne;
    oneByOne.fixedBatch = 1;
    CHECK(sameImage(render(context(), dev, host.camera, s, oneByOne).film, whole.film));
    // The wavefront integrator skips the same blocks: the same counts and sums.
    RenderSettings wave = s;
    wave.integrator = IntegratorKind::Wavefront;
    const RenderResult waved = render(context(), dev, host.camera, wave);
    CHECK(waved.spp == whole.spp);
    CHECK(waved.film.count == whole.film.count);
    CHECK(sameImage(waved.film, whole.film));
    // Stopped inside the batch after the first blocks retired, then resumed:
    // the resumed render must skip those blocks from its first sample on.
    const std::uint32_t firstRetired =
        static_cast<std::uint32_t>(*std::min_element(whole.film.count.begin(), whole.film.count.end()));
    REQUIRE(firstRetired + 8 < whole.spp);
    SampleRun first;
    first.end = firstRetired + 8;
    first.keep = true;
    const RenderResult part = render(context(), dev, host.camera, s, {}, {}, first);
    REQUIRE(part.state.end == first.end);
    SampleRun rest;
    rest.resume = &part.state;
    const RenderResult resumed = render(context(), dev, host.camera, s, {}, {}, rest);
    CHECK(resumed.spp == whole.spp);
    CHECK(resumed.film.count == whole.film.count);
    CHECK(resumed.film.sum == whole.film.sum);
    CHECK(resumed.film.sumSq == whole.film.sumSq);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
