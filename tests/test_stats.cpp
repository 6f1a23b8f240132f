// The statistical tests themselves: numerics against known values (reference
// values from mpmath at 40 digits), and each test's power to accept the right
// distribution and reject a slightly wrong one. Fixed seeds: deterministic.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "stats/stats.h"

using namespace strata::stats;

TEST_SUITE_BEGIN("unit");

namespace {

constexpr double kPi = std::numbers::pi;

// Relative closeness: doctest::Approx's default scale of 1 would make its
// epsilon absolute for values below 1.
doctest::Approx rel(double value, double eps) { return doctest::Approx(value).epsilon(eps).scale(0.0); }
bool relClose(double a, double b, double rel) { return std::abs(a - b) <= rel * std::abs(b); }

// Q(k, y) for integer k: e^-y sum_{i<k} y^i / i!  (chi-square with 2k dof).
double gammaQInteger(int k, double y) {
    double term = std::exp(-y), sum = 0.0;
    for (int i = 0; i < k; ++i) {
        sum += term;
        term *= y / (i + 1);
    }
    return sum;
}

// Triangle density on [0, 1] peaking at 1/2, the law of (U1 + U2) / 2.
double triangle(double t) { return t < 0.5 ? 4.0 * t : 4.0 * (1.0 - t); }

}  // namespace

TEST_CASE("stats: normalQuantile known values, edges and symmetry") {
    CHECK(relClose(normalQuantile(0.975), 1.9599639845400542, 1e-14));
    CHECK(relClose(normalQuantile(0.001), -3.0902323061678135, 1e-14));
    CHECK(relClose(normalQuantile(1e-10), -6.3613409024040562, 1e-14));
    CHECK(relClose(normalQuantile(1e-20), -9.2623400897984076, 1e-14));
    CHECK(relClose(normalQuantile(1e-300), -37.047096299361199, 1e-14));
    CHECK(normalQuantile(0.5) == 0.0);
    CHECK(normalQuantile(0.0) == -std::numeric_limits<double>::infinity());
    CHECK(normalQuantile(1.0) == std::numeric_limits<double>::infinity());
    CHECK(std::isnan(normalQuantile(-0.1)));
    CHECK(std::isnan(normalQuantile(1.5)));
    CHECK(std::isfinite(normalQuantile(5e-324)));  // smallest subnormal
    for (double p : {0.3, 0.1, 0.02, 0.0243, 0.0245, 1e-5})
        CHECK(normalQuantile(1.0 - p) == rel(-normalQuantile(p), 1e-10));
}

TEST_CASE("stats: normalCdf known values and round trip with normalQuantile") {
    CHECK(relClose(normalCdf(1.0), 0.84134474606854294859, 1e-15));
    CHECK(relClose(normalCdf(-5.0), 2.8665157187919391167e-7, 1e-14));
    CHECK(relClose(normalCdf(-30.0), 4.9067139271481870595e-198, 1e-14));
    CHECK(relClose(normalCdf(-35.0), 1.1249107064724062e-268, 1e-14));
    CHECK(normalCdf(0.0) == 0.5);
    double worst = 0.0;
    for (double lp = -300.0; lp <= std::log10(0.5); lp += 0.05) {  // lower tail, relative
        const double p = std::pow(10.0, lp);
        worst = std::max(worst, std::abs(normalCdf(normalQuantile(p)) - p) / p);
    }
    CHECK(worst < 1e-12);
    for (double p = 0.5; p < 1.0; p += 0.0137)  // upper half, absolute
        CHECK(std::abs(normalCdf(normalQuantile(p)) - p) < 1e-15);
}

TEST_CASE("stats: sidak keeps full precision for many tests") {
    CHECK(sidak(0.01, 1) == rel(0.01, 1e-15));
    CHECK(relClose(sidak(0.01, 1000000), 1.0050335802996815969e-8, 1e-13));
    const double s = sidak(0.05, 37);
    CHECK(std::pow(1.0 - s, 37.0) == rel(0.95, 1e-14));
    CHECK(sidak(0.0, 10) == 0.0);
    CHECK_THROWS_AS(sidak(0.01, 0), std::invalid_argument);
}

TEST_CASE("stats: chi2Sf against known values and closed forms") {
    CHECK(relClose(chi2Sf(3.841458820694124, 1), 0.050000000000000058397, 1e-12));
    CHECK(relClose(chi2Sf(18.307038053275146, 10), 0.050000000000000013496, 1e-12));
    struct Known {
        double dof, x, q;
    };
    const Known known[] = {
        {1000, 1106.9689, 0.010000052558951861646}, {1000, 900, 0.98928276190871025844},
        {10000, 10500, 0.00024794736798936085205},  {3, 50, 7.9891792449514711391e-11},
        {7, 0.5, 0.99944648139042496549},           {100000, 101000, 0.012868840377233669864},
        {1, 100, 1.5239706048321052132e-23},        {2, 1400, 9.8596765437597708567e-305},
        {50, 200, 7.8576107246547435634e-20},       {0.5, 1e-5, 0.94782998241933337329},
        {1000, 1500, 1.0454640385979657294e-22},    {2000000, 2006000, 0.0013617406462175914794},
        {2000000, 1994000, 0.99866189583268640031},
    };
    for (const Known& k : known) {
        INFO("dof ", k.dof, " x ", k.x);
        CHECK(relClose(chi2Sf(k.x, k.dof), k.q, 1e-12));
    }
    // dof 1: erfc(sqrt(x/2)); dof 2k: the finite Poisson sum.
    for (double x = 1e-6; x < 1400.0; x *= 1.7) {
        INFO("x ", x);
        CHECK(relClose(chi2Sf(x, 1), std::erfc(std::sqrt(x / 2)), 1e-12));
        CHECK(relClose(chi2Sf(x, 2), std::exp(-x / 2), 1e-12));
        if (x > 1.0 && x < 1200.0) {
            CHECK(relClose(chi2Sf(x, 40), gammaQInteger(20, x / 2), 1e-11));
            CHECK(relClose(chi2Sf(x, 600), gammaQInteger(300, x / 2), 1e-10));
        }
    }
    CHECK(chi2Sf(0.0, 5) == 1.0);
    CHECK(chi2Sf(-1.0, 5) == 1.0);
    CHECK(std::isnan(chi2Sf(1.0, 0)));
}

TEST_CASE("stats: histogram2D layout, closed domain, ignored samples") {
    const std::vector<std::pair<double, double>> s = {
        {0.0, 0.0}, {1.0, 1.0}, {0.99, 0.01}, {0.5, 0.7}, {-0.01, 0.5}, {0.5, 1.01}, {std::nan(""), 0.5}};
    const auto h = histogram2D(s, 3, 5, 0.0, 1.0, 0.0, 1.0);
    REQUIRE(h.size() == 15);
    CHECK(h[0] == 1);           // (0, 0)
    CHECK(h[4 * 3 + 2] == 1);   // (1, 1): the closed edge lands in the last cell
    CHECK(h[0 * 3 + 2] == 1);   // (0.99, 0.01)
    CHECK(h[3 * 3 + 1] == 1);   // (0.5, 0.7): iy = floor(3.5) = 3
    double total = 0.0;
    for (double c : h) total += c;
    CHECK(total == 4);  // the outside and NaN samples are not counted
}

TEST_CASE("stats: Gauss-Legendre integrates polynomials exactly, and expected counts sum to N") {
    std::vector<double> t, w;
    gaussLegendre(8, t, w);
    double s15 = 0.0, s14 = 0.0, sw = 0.0;
    for (int i = 0; i < 8; ++i) s15 += w[i] * std::pow(t[i], 15), s14 += w[i] * std::pow(t[i], 14), sw += w[i];
    CHECK(std::abs(s15) < 1e-15);
    CHECK(s14 == rel(2.0 / 15, 1e-14));
    CHECK(sw == rel(2.0, 1e-15));
    const auto e = integrateExpected([](double x, double y) { return 6.0 * x * y * y; }, 5, 7, 0, 1, 0, 1, 1000);
    CHECK(e[0] == rel(1000 * 0.04 * std::pow(1.0 / 7, 3), 1e-12));
    double total = 0.0;
    for (double v : e) total += v;
    CHECK(total == rel(1000, 1e-12));
}

TEST_CASE("stats: chi-square pooling merges small cells and counts dof") {
    SUBCASE("pooled cell still below 5 joins the smallest remaining cell") {
        // small cells 2, 1, 1.5 (sum 4.5 < 5) join the 20 cell; the 0/0 cell is ignored.
        const std::vector<double> exp = {100, 50, 2, 1, 1.5, 0, 20};
        const std::vector<double> obs = {98, 53, 3, 0, 2, 0, 19};
        const ChiSquareResult r = chiSquareTest(obs, exp, 0.01);
        CHECK(r.pooledCells == 3);
        CHECK(r.dof == 2);
        const double stat = 4.0 / 100 + 9.0 / 50 + 0.25 / 24.5;
        CHECK(r.statistic == rel(stat, 1e-14));
        CHECK(r.pValue == rel(std::exp(-stat / 2), 1e-12));
        CHECK(r.passed);
    }
    SUBCASE("pooled cell of 5 or more stands as its own cell") {
        const std::vector<double> exp = {100, 4, 3, 2, 50};
        const std::vector<double> obs = {100, 9, 0, 0, 50};
        const ChiSquareResult r = chiSquareTest(obs, exp, 0.01);
        CHECK(r.pooledCells == 3);
        CHECK(r.dof == 2);
        CHECK(r.statistic == doctest::Approx(0.0));
        CHECK(r.passed);
    }
    SUBCASE("samples where the expected count is 0 fail outright") {
        const ChiSquareResult r = chiSquareTest({10, 20, 1}, {10, 20, 0}, 0.01);
        CHECK_FALSE(r.passed);
        CHECK(r.pValue == 0.0);
        CHECK(std::isinf(r.statistic));
        CHECK(r.detail.find("cell 2") != std::string::npos);
        CHECK(r.detail.find("expected count is 0") != std::string::npos);
    }
    SUBCASE("one cell left after pooling fails: no degrees of freedom") {
        const ChiSquareResult r = chiSquareTest({2, 1, 1}, {1, 1, 2}, 0.01);
        CHECK(r.pooledCells == 3);
        CHECK(r.dof == 0);
        CHECK_FALSE(r.passed);
    }
    CHECK_THROWS_AS(chiSquareTest({1, 2}, {1}, 0.01), std::invalid_argument);
    CHECK_THROWS_AS(chiSquareTest({1, 2}, {1, -1}, 0.01), std::invalid_argument);
}

TEST_CASE("stats: chi-square p-values are uniform under the null hypothesis") {
    // 400 tests of a fair 11-sided die; the p-values of a correct test are U(0,1).
    std::mt19937 rng(12345);
    std::uniform_int_distribution<int> die(0, 10);
    const std::vector<double> exp(11, 2000.0 / 11);
    int below5 = 0, below50 = 0;
    double meanP = 0.0;
    for (int trial = 0; trial < 400; ++trial) {
        std::vector<double> obs(11, 0.0);
        for (int i = 0; i < 2000; ++i) obs[die(rng)] += 1;
        const ChiSquareResult r = chiSquareTest(obs, exp, 0.01);
        below5 += r.pValue < 0.05;
        below50 += r.pValue < 0.5;
        meanP += r.pValue / 400;
    }
    CHECK(below5 >= 8);  // Binomial(400, 0.05): 20 +- 4.4
    CHECK(below5 <= 35);
    CHECK(below50 >= 170);  // Binomial(400, 0.5): 200 +- 10
    CHECK(below50 <= 230);
    CHECK(meanP == rel(0.5, 0.1));
}

TEST_CASE("stats: chi-square accepts a cosine lobe and rejects a 5% tilt") {
    // Malley's method: uniform points on the unit disk projected up to the
    // hemisphere give directions with pdf cos(theta) / pi. On (cos theta, phi),
    // with d omega = d cos(theta) d phi, the density is u / pi.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const std::size_t n = 1000000;
    std::vector<std::pair<double, double>> s;
    s.reserve(n);
    while (s.size() < n) {
        const double x = 2 * U(rng) - 1, y = 2 * U(rng) - 1;
        if (x * x + y * y >= 1.0) continue;
        double phi = std::atan2(y, x);
        if (phi < 0) phi += 2 * kPi;
        s.emplace_back(std::sqrt(1.0 - x * x - y * y), phi);
    }
    const int rx = 17, ry = 33;
    const auto obs = histogram2D(s, rx, ry, 0, 1, 0, 2 * kPi);
    const auto good = integrateExpected([](double u, double) { return u / kPi; }, rx, ry, 0, 1, 0, 2 * kPi, n);
    const ChiSquareResult ok = chiSquareTest(obs, good, 0.01);
    INFO(ok.detail);
    CHECK(ok.passed);
    CHECK(ok.dof == rx * ry - 1);
    const auto tilted = integrateExpected([](double u, double phi) { return u / kPi * (1 + 0.05 * std::cos(phi)); },
                                          rx, ry, 0, 1, 0, 2 * kPi, n);
    const ChiSquareResult bad = chiSquareTest(obs, tilted, 0.01);
    INFO(bad.detail);
    CHECK_FALSE(bad.passed);
}

TEST_CASE("stats: chi-square on a product of triangles, and a 5% tilted sampler is rejected") {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const std::size_t n = 1000000;
    const int res = 17;
    const auto expected = integrateExpected([](double x, double y) { return triangle(x) * triangle(y); }, res, res,
                                            0, 1, 0, 1, n, 16);
    std::vector<std::pair<double, double>> right, tilted;
    right.reserve(n);
    tilted.reserve(n);
    for (std::size_t i = 0; i < n; ++i) right.emplace_back((U(rng) + U(rng)) / 2, (U(rng) + U(rng)) / 2);
    while (tilted.size() < n) {  // rejection to density triangle(x) (1 + 0.05 (2x - 1)) triangle(y)
        const double x = (U(rng) + U(rng)) / 2, y = (U(rng) + U(rng)) / 2;
        if (U(rng) * 1.05 < 1.0 + 0.05 * (2 * x - 1)) tilted.emplace_back(x, y);
    }
    const ChiSquareResult ok = chiSquareTest(histogram2D(right, res, res, 0, 1, 0, 1), expected, 0.01);
    INFO(ok.detail);
    CHECK(ok.passed);
    const ChiSquareResult bad = chiSquareTest(histogram2D(tilted, res, res, 0, 1, 0, 1), expected, 0.01);
    INFO(bad.detail);
    CHECK_FALSE(bad.passed);
}

TEST_CASE("stats: per-pixel Z-test accepts an equal render and rejects a 1% bias") {
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> U(0.5, 2.0);
    std::normal_distribution<double> N01(0.0, 1.0);
    const std::size_t n = 300000;
    std::vector<float> x(n), vx(n), r(n), vr(n), biased(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double truth = U(rng), sx = 1e-3 * truth, sr = 5e-4 * truth;
        x[i] = static_cast<float>(truth + sx * N01(rng));
        r[i] = static_cast<float>(truth + sr * N01(rng));
        biased[i] = static_cast<float>(1.01 * truth + sx * N01(rng));
        vx[i] = static_cast<float>(sx * sx);
        vr[i] = static_cast<float>(sr * sr);
    }
    const ZTestResult ok = perPixelZTest(x.data(), vx.data(), r.data(), vr.data(), n);
    CHECK(ok.pixels == n);
    CHECK(ok.passed);
    CHECK(ok.acceptedFraction > 0.9999);
    CHECK(ok.zThreshold == rel(-normalQuantile(sidak(0.01, n) / 2), 1e-15));
    const ZTestResult bad = perPixelZTest(biased.data(), vx.data(), r.data(), vr.data(), n);
    CHECK_FALSE(bad.passed);
    CHECK(bad.acceptedFraction < 0.01);

    // Zero variance: accepted only on exact equality; NaN never.
    const float a[] = {1, 2, std::nanf("")}, b[] = {1, 2.0001f, std::nanf("")}, z[] = {0, 0, 0};
    const ZTestResult zr = perPixelZTest(a, z, b, z, 3, 0.01, 0.0);
    CHECK(zr.accepted == 1);
    const ZTestResult one = perPixelZTest(a, z, a, z, 1);
    CHECK(one.zThreshold == rel(2.575829303548900761, 1e-14));
    CHECK(one.passed);
    CHECK_FALSE(perPixelZTest(a, z, a, z, 0).passed);
}

TEST_CASE("stats: meanTest against exact answers") {
    const std::vector<double> ones(100, 1.0), vars(100, 0.01);  // stdError = sqrt(1) / 100
    const MeanTestResult near = meanTest(ones, vars, 1.03);
    CHECK(near.stdError == rel(0.01, 1e-14));
    CHECK(near.z == rel(-3.0, 1e-12));
    CHECK(near.passed);
    CHECK_FALSE(meanTest(ones, vars, 1.05).passed);
    const std::vector<double> none(100, 0.0);
    CHECK(meanTest(ones, none, 1.0).passed);
    CHECK_FALSE(meanTest(ones, none, 1.0 + 1e-15).passed);
    CHECK_FALSE(meanTest({}, {}, 0.0).passed);
    // Estimates with their true variance pass at 4 sigma; with a bias of 10
    // standard errors they fail.
    std::mt19937 rng(5);
    std::normal_distribution<double> N(2.0, 0.3);
    int passed = 0, biasedPassed = 0;
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<double> v(400), var(400, 0.09), b(400);
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = N(rng), b[i] = v[i] + 10 * 0.3 / 20;
        passed += meanTest(v, var, 2.0).passed;
        biasedPassed += meanTest(b, var, 2.0).passed;
    }
    CHECK(passed == 50);
    CHECK(biasedPassed == 0);
}

TEST_CASE("stats: log-log slope and bias-floor fits") {
    std::vector<double> n, inv, invSqrt;
    for (double N = 1; N <= 65536; N *= 2) n.push_back(N), inv.push_back(3.0 / N), invSqrt.push_back(7 / std::sqrt(N));
    CHECK(fitLogLogSlope(n, inv) == rel(-1.0, 1e-12));
    CHECK(fitLogLogSlope(n, invSqrt) == rel(-0.5, 1e-12));
    CHECK_THROWS_AS(fitLogLogSlope({1, 1}, {1, 2}), std::invalid_argument);
    CHECK_THROWS_AS(fitLogLogSlope({1, 2}, {1, 0}), std::invalid_argument);

    // Exact data MSE = b2 + c / N.
    std::vector<double> mse;
    for (double N : n) mse.push_back(1e-4 + 0.5 / N);
    BiasFit f = fitBiasFloor(n, mse);
    CHECK(f.b2 == rel(1e-4, 1e-9));
    CHECK(f.c == rel(0.5, 1e-9));
    // An unbiased estimator: the floor is 0 (clamped when the free fit dips below).
    std::vector<double> unbiased;
    for (double N : n) unbiased.push_back(0.5 / N * (1.0 - 1e-3 * std::log2(N) / 16));
    f = fitBiasFloor(n, unbiased);
    CHECK(f.b2 >= 0.0);
    CHECK(f.b2 < 1e-8);
    CHECK(f.c == rel(0.5, 1e-2));
    // Noisy data (2% lognormal noise per point) recovers both within tolerance.
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.02);
    std::vector<double> noisy;
    for (double N : n) noisy.push_back((1e-4 + 0.5 / N) * std::exp(noise(rng)));
    f = fitBiasFloor(n, noisy);
    CHECK(f.b2 == rel(1e-4, 0.05));
    CHECK(f.c == rel(0.5, 0.05));
}

TEST_SUITE_END();
