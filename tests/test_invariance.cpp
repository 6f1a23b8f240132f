// Translation and scale invariance: the Cornell box moved by 10^4 and scaled
// by 10^-3 and 10^3 (coordinates baked into the vertex data, camera moved
// with it; tests/data/invariance/) renders the same image as the original,
// by the per-pixel Z-test (Mitsuba 3's render tests: at least 99.75% of values
// accepted at alpha = 0.01 with Sidak correction).
#include <doctest/doctest.h>

#include "stats/stats.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

TEST_CASE("the Cornell box moved by 1e4 and scaled by 1e-3 and 1e3 matches the original") {
    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.spp = 128;
    s.maxDepth = 16;
    s.seed = 100;
    Rendered original = renderFile("scenes/cornell-box.gltf", s);
    const auto refMean = original.result.film.mean();
    const auto refVar = original.result.film.varianceOfMean();
    int seed = 200;
    for (const std::string& file : std::vector<std::string>{"tests/data/invariance/cornell-moved.gltf", "tests/data/invariance/cornell-small.gltf",
                             "tests/data/invariance/cornell-large.gltf"}) {
        CAPTURE(file);
        s.seed = seed++;  // independent samples: the test has its full power
        Rendered r = renderFile(file, s);
        const auto mean = r.result.film.mean();
        const auto var = r.result.film.varianceOfMean();
        const stats::ZTestResult z = stats::perPixelZTest(mean.data(), var.data(), refMean.data(),
                                                          refVar.data(), mean.size());
        CAPTURE(z.acceptedFraction);
        CAPTURE(z.zThreshold);
        CHECK(z.passed);
        CHECK(r.result.nonFinite == 0);
    }
    CHECK(original.result.nonFinite == 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
