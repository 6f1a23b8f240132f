// Image error metrics against hand-computed values.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "image/metrics.h"

using namespace strata;

TEST_SUITE_BEGIN("unit");

namespace {
// Relative closeness: doctest::Approx's default scale of 1 would make its
// epsilon absolute for values below 1.
doctest::Approx rel(double value, double eps) { return doctest::Approx(value).epsilon(eps).scale(0.0); }
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr float kInff = std::numeric_limits<float>::infinity();
}  // namespace

TEST_CASE("metrics: every definition on a hand-computed example") {
    // differences 0, 1, -0.5, 2; eps 0.5 keeps the fractions simple.
    const std::vector<float> x = {1, 2, 0, 4};
    const std::vector<float> r = {1, 1, 0.5f, 2};
    const ErrorMetrics m = compareImages(x.data(), r.data(), x.size(), 0.5, 0.0);
    CHECK(m.values == 4);
    CHECK(m.nonFinite == 0);
    CHECK(m.eps == 0.5);
    CHECK(m.rmse == rel(std::sqrt(5.25 / 4), 1e-15));
    // (x-r)^2 / (r^2 + eps): 0, 1/1.5, 0.25/0.75, 4/4.5
    CHECK(m.relMse == rel((2.0 / 3 + 1.0 / 3 + 8.0 / 9) / 4, 1e-15));
    CHECK(m.relMseTrimmed == m.relMse);  // trimFraction 0 drops nothing
    CHECK(m.trimmed == 0);
    // |x-r| / (|r| + eps): 0, 1/1.5, 0.5/1, 2/2.5
    CHECK(m.mape == rel((2.0 / 3 + 0.5 + 0.8) / 4, 1e-15));
    // 2|x-r| / (|x| + |r| + eps): 0, 2/3.5, 1/1, 4/6.5
    CHECK(m.smape == rel((2 / 3.5 + 1.0 + 4 / 6.5) / 4, 1e-15));
    CHECK(m.maxAbs == 2.0);

    // trimFraction 0.25 of 4 values drops one term, the largest (8/9).
    const ErrorMetrics t = compareImages(x.data(), r.data(), x.size(), 0.5, 0.25);
    CHECK(t.trimmed == 1);
    CHECK(t.relMseTrimmed == rel((2.0 / 3 + 1.0 / 3) / 3, 1e-15));
    CHECK(t.relMse == m.relMse);
}

TEST_CASE("metrics: eps defaults to 1e-2 and bounds the relative terms at r = 0") {
    const float x[] = {0.1f, 0.0f}, r[] = {0.0f, 0.0f};
    const ErrorMetrics m = compareImages(x, r, 2);
    CHECK(m.eps == 0.01);
    const double d = 0.1f;  // the float value, widened
    CHECK(m.relMse == rel(d * d / 0.01 / 2, 1e-12));
    CHECK(m.mape == rel(d / 0.01 / 2, 1e-12));
    CHECK(m.smape == rel(2 * d / (d + 0.01) / 2, 1e-12));
    // An exact match scores 0 everywhere, with no division by zero.
    const ErrorMetrics z = compareImages(r, r, 2);
    CHECK(z.rmse == 0.0);
    CHECK(z.relMse == 0.0);
    CHECK(z.mape == 0.0);
    CHECK(z.smape == 0.0);
}

TEST_CASE("metrics: NaN and Inf are excluded from every mean and counted") {
    const std::vector<float> x = {1, 2, 0, 4, kNaNf, 1, -kInff};
    const std::vector<float> r = {1, 1, 0.5f, 2, 1, kInff, 1};
    const ErrorMetrics m = compareImages(x.data(), r.data(), x.size(), 0.5, 0.0);
    CHECK(m.nonFinite == 3);
    CHECK(m.values == 4);
    CHECK(m.rmse == rel(std::sqrt(5.25 / 4), 1e-15));
    CHECK(m.maxAbs == 2.0);
    CHECK(std::isfinite(m.relMse));
    CHECK(std::isfinite(m.smape));

    const ErrorMetrics none = compareImages(x.data() + 4, r.data() + 4, 3);
    CHECK(none.values == 0);
    CHECK(none.nonFinite == 3);
    CHECK(std::isnan(none.rmse));
    CHECK(std::isnan(none.relMseTrimmed));
}

TEST_CASE("metrics: trimming drops floor(fraction * values) of the largest terms") {
    // 2999 values: floor(2.999) = 2 dropped; 3000: 3 dropped; 999: none.
    for (std::size_t n : {999u, 1000u, 2999u, 3000u}) {
        const double nd = static_cast<double>(n);
        std::vector<float> r(n, 1.0f), x(n, 1.5f);  // every term 0.25 / 1.01
        x[7] = 1000.0f;                              // one firefly
        x[n - 1] = 50.0f;                            // and a smaller one
        const ErrorMetrics m = compareImages(x.data(), r.data(), n);
        const std::uint64_t k = n / 1000;
        CHECK(m.trimmed == k);
        const double base = 0.25 / 1.01;
        const double big = 999.0 * 999.0 / 1.01, mid = 49.0 * 49.0 / 1.01;
        CHECK(m.relMse == rel((base * (nd - 2) + big + mid) / nd, 1e-12));
        double expected = 0.0;
        if (k == 0) expected = (base * (nd - 2) + big + mid) / nd;
        if (k == 1) expected = (base * (nd - 2) + mid) / (nd - 1);  // firefly dropped
        if (k >= 2) expected = base;                              // both dropped, then ties
        CHECK(m.relMseTrimmed == rel(expected, 1e-12));
    }
    // A fraction whose product rounds just below an integer (0.29 * 100 =
    // 28.999999999999996 in double) still drops 29.
    std::vector<float> r(100, 0.0f), x(100, 0.0f);
    CHECK(compareImages(x.data(), r.data(), 100, 1e-2, 0.29).trimmed == 29);
}

TEST_CASE("metrics: trimming with ties at the threshold keeps the right number of them") {
    // terms 4, 4, 4, 1 (eps 1e-2 makes them 4/(1.01) and 1/(1.01)); drop 1 of 4.
    const float r[] = {1, 1, 1, 1}, x[] = {3, 3, 3, 2};
    const ErrorMetrics m = compareImages(x, r, 4, 1e-2, 0.25);
    CHECK(m.trimmed == 1);
    CHECK(m.relMseTrimmed == rel((4.0 + 4.0 + 1.0) / 1.01 / 3, 1e-14));
}

TEST_CASE("metrics: invalid arguments throw, and the text states eps and trimming") {
    const float a[] = {1, 2};
    CHECK_THROWS_AS(compareImages(a, a, 2, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(compareImages(a, a, 2, -1.0), std::invalid_argument);
    CHECK_THROWS_AS(compareImages(a, a, 2, 1e-2, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(compareImages(a, a, 2, 1e-2, -0.1), std::invalid_argument);
    const float b[] = {1, 3};
    const std::string text = metricsText(compareImages(a, b, 2));
    CHECK(text.find("eps 0.01") != std::string::npos);
    CHECK(text.find("RMSE") != std::string::npos);
    CHECK(text.find("relMSE trim") != std::string::npos);
    CHECK(text.find("0.1% of terms dropped: 0") != std::string::npos);
}

TEST_SUITE_END();
