// Host-side accumulation and the emitter alias table.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "image/film.h"
#include "pack/gpu_scene.h"

using namespace strata;

TEST_SUITE_BEGIN("unit");

TEST_CASE("film folds device batches and reports mean and variance of the mean") {
    Film f(2, 1);
    // Two batches; pixel 0 gets samples {1, 3} then {5}, pixel 1 gets {2}.
    const float b1[16] = {4, 4, 4, 2, 10, 10, 10, 0, 2, 2, 2, 1, 4, 4, 4, 0};
    const float b2[16] = {5, 5, 5, 1, 25, 25, 25, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    f.fold(b1);
    f.fold(b2);
    CHECK(f.count[0] == 3);
    CHECK(f.count[1] == 1);
    const auto m = f.mean();
    CHECK(m[0] == doctest::Approx(3.0));
    CHECK(m[3] == doctest::Approx(2.0));
    const auto v = f.varianceOfMean();
    CHECK(v[0] == doctest::Approx(4.0 / 3.0));  // sample variance 4, over 3 samples
    CHECK(v[3] == 0.0f);                        // one sample: unknown, reported 0
}

TEST_CASE("film leaves out a batch whose float sum overflowed, and counts its samples") {
    Film f(2, 1);
    const float inf = std::numeric_limits<float>::infinity();
    // Pixel 0: samples {1, 3}; pixel 1: 64 finite samples whose float sum overflowed.
    const float b1[16] = {4, 4, 4, 2, 10, 10, 10, 0, inf, 1, 1, 64, inf, 1, 1, 0};
    // Pixel 0: a sample of 3e19, whose square is beyond float: kept (the mean
    // is right; the variance reads infinite). Pixel 1: sample {2}.
    const float b2[16] = {3e19f, 3e19f, 3e19f, 1, inf, inf, inf, 0, 2, 2, 2, 1, 4, 4, 4, 0};
    f.fold(b1);
    f.fold(b2);
    CHECK(f.overflowed == 64);
    CHECK(f.count[0] == 3);
    CHECK(f.count[1] == 1);
    const auto m = f.mean();
    CHECK(m[0] == doctest::Approx((4.0 + 3e19) / 3.0));
    CHECK(m[3] == doctest::Approx(2.0));
    CHECK(std::isinf(f.varianceOfMean()[0]));
}

TEST_CASE("alias table selects each emitter with its share of the weight") {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> w(0.0, 10.0);
    for (int n : {1, 2, 7, 100}) {
        std::vector<double> weights(n);
        double total = 0.0;
        for (auto& x : weights) x = (n > 2 && rng() % 5 == 0) ? 0.0 : w(rng), total += x;
        if (total == 0.0) weights[0] = total = 1.0;
        std::vector<gpu::Emitter> e(n);
        buildAliasTable(weights, e);
        // Exact selection probability of the table: slot i kept with aliasProb,
        // otherwise its alias; each slot chosen with 1/n.
        std::vector<double> p(n, 0.0);
        for (int i = 0; i < n; ++i) {
            p[i] += e[i].aliasProb / n;
            p[e[i].alias] += (1.0 - e[i].aliasProb) / n;
        }
        for (int i = 0; i < n; ++i) {
            CHECK(p[i] == doctest::Approx(weights[i] / total).epsilon(1e-6));
            CHECK(e[i].pmf == doctest::Approx(weights[i] / total).epsilon(1e-6));
        }
    }
}

TEST_SUITE_END();
