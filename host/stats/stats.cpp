// Statistical tests for the test suite; contracts in stats.h.
#include "stats/stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace strata::stats {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void require(bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(what);
}

// Acklam's approximation of the lower normal quantile for 0 < p <= 0.5,
// relative error < 1.15e-9 (P. J. Acklam, "An algorithm for computing the
// inverse normal cumulative distribution function", 2003).
double acklamLower(double p) {
    static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                   1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
    static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                   6.680131188771972e+01,  -1.328068155288572e+01};
    static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                   -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
    static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                   3.754408661907416e+00};
    constexpr double pLow = 0.02425;
    if (p < pLow) {
        const double q = std::sqrt(-2.0 * std::log(p));
        return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
               ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    }
    const double q = p - 0.5, r = q * q;
    return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
           (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

// t - log(1 + t), accurate also for small |t| (series there), the "bd0"
// deviance term of C. Loader, "Fast and accurate computation of binomial
// probabilities" (2000).
double deviance(double t) {
    if (std::abs(t) >= 0.1) return t - std::log1p(t);
    // sum_{k>=2} (-1)^k t^k / k
    double term = t * t, sum = 0.0;
    for (int k = 2; k < 60; ++k) {
        const double add = term / k;
        sum += (k % 2 == 0) ? add : -add;
        if (std::abs(add) < 1e-18 * std::abs(sum)) break;
        term *= t;
    }
    return sum;
}

// log(Gamma(a)) - ((a - 0.5) log a - a + 0.5 log(2 pi)), Stirling's series
// (Abramowitz & Stegun 6.1.41), used for a >= 10 where 5 terms give < 1e-14.
double stirlingError(double a) {
    const double r = 1.0 / a, r2 = r * r;
    return r * (1.0 / 12 - r2 * (1.0 / 360 - r2 * (1.0 / 1260 - r2 * (1.0 / 1680 - r2 / 1188))));
}

// log(x^a e^-x / Gamma(a)), the prefactor of both P and Q. For a >= 10 it is
// formed as -a * deviance((x - a) / a) + 0.5 log(a / 2 pi) - stirlingError(a),
// which avoids the cancellation of a log x - x - lgamma(a) at large a.
double logPrefactor(double a, double x) {
    if (a < 10.0) return a * std::log(x) - x - std::lgamma(a);
    return -a * deviance((x - a) / a) + 0.5 * std::log(a / (2.0 * std::numbers::pi)) - stirlingError(a);
}

// P(a, x) by its series, for x < a + 1 (Numerical Recipes 3rd ed., 6.2.5).
double gammaPSeries(double a, double x) {
    double ap = a, del = 1.0 / a, sum = del;
    const int maxIter = 1000 + static_cast<int>(100.0 * std::sqrt(a));
    for (int n = 0; n < maxIter; ++n) {
        ap += 1.0;
        del *= x / ap;
        sum += del;
        if (std::abs(del) < std::abs(sum) * 1e-17) break;
    }
    return sum * std::exp(logPrefactor(a, x));
}

// Q(a, x) by its continued fraction, for x >= a + 1, evaluated with the
// modified Lentz method (Numerical Recipes 3rd ed., 6.2.7).
double gammaQFraction(double a, double x) {
    constexpr double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    const int maxIter = 1000 + static_cast<int>(100.0 * std::sqrt(a));
    for (int i = 1; i < maxIter; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1.0) < 1e-16) break;
    }
    return std::exp(logPrefactor(a, x)) * h;
}

char* formatDouble(char* buf, std::size_t n, double v) {
    std::snprintf(buf, n, "%.6g", v);
    return buf;
}

}  // namespace

double normalCdf(double z) {
    // x = -z / sqrt 2 carries a rounding error that erfc amplifies by 2 x^2 in
    // the tail (1e-13 relative at z = -30); its residual `err` (exact product
    // residual by fma, plus the low half of 1/sqrt 2) is added back to first
    // order: erfc(x + err) = erfc(x) - err 2/sqrt(pi) e^(-x^2).
    constexpr double invSqrt2Hi = 0.7071067811865476, invSqrt2Lo = -4.8336466567264565e-17;
    const double x = -z * invSqrt2Hi;
    const double err = std::fma(-z, invSqrt2Hi, -x) + -z * invSqrt2Lo;
    return 0.5 * std::erfc(x) - err * std::exp(-x * x) * std::numbers::inv_sqrtpi;
}

double normalQuantile(double p) {
    if (std::isnan(p) || p < 0.0 || p > 1.0) return kNaN;
    if (p == 0.0) return -kInf;
    if (p == 1.0) return kInf;
    if (p > 0.5) return -normalQuantile(1.0 - p);  // exact subtraction for p in [0.5, 1]
    double x = acklamLower(p);
    // One Halley step on f(x) = Phi(x) - p (Acklam's refinement):
    // u = f / phi(x), x -= u / (1 + x u / 2). u is formed in log space so that
    // phi(x) may underflow (p below ~1e-300).
    const double e = normalCdf(x) - p;
    if (e != 0.0) {
        const double logU = std::log(std::abs(e)) + 0.5 * x * x + 0.5 * std::log(2.0 * std::numbers::pi);
        const double u = std::copysign(std::exp(logU), e);
        x -= u / (1.0 + 0.5 * x * u);
    }
    return x;
}

double sidak(double alpha, std::size_t tests) {
    require(tests > 0, "sidak: tests must be > 0");
    require(alpha >= 0.0 && alpha <= 1.0, "sidak: alpha must be in [0, 1]");
    if (alpha == 1.0) return 1.0;
    return -std::expm1(std::log1p(-alpha) / static_cast<double>(tests));
}

double gammaQ(double a, double x) {
    if (!(a > 0.0) || std::isnan(x) || x < 0.0) return kNaN;
    if (x == 0.0) return 1.0;
    if (std::isinf(x)) return 0.0;
    if (x < a + 1.0) return 1.0 - gammaPSeries(a, x);
    return gammaQFraction(a, x);
}

double chi2Sf(double x, double dof) {
    if (!(dof > 0.0) || std::isnan(x)) return kNaN;
    if (x <= 0.0) return 1.0;
    return gammaQ(0.5 * dof, 0.5 * x);
}

ChiSquareResult chiSquareTest(const std::vector<double>& observed, const std::vector<double>& expected,
                              double alpha, std::size_t testCount, double minExpected) {
    require(observed.size() == expected.size(), "chiSquareTest: observed and expected differ in size");
    require(minExpected >= 0.0, "chiSquareTest: minExpected must be >= 0");
    struct Cell {
        double o, e;
        long index;  // original cell, -1 for the pooled cell
    };
    std::vector<Cell> cells;
    Cell pool{0.0, 0.0, -1};
    ChiSquareResult res;
    std::size_t zeroExpectedHits = 0, firstZeroHit = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        const double o = observed[i], e = expected[i];
        require(std::isfinite(o) && o >= 0.0, "chiSquareTest: observed counts must be finite and >= 0");
        require(std::isfinite(e) && e >= 0.0, "chiSquareTest: expected counts must be finite and >= 0");
        if (e == 0.0) {
            if (o > 0.0 && zeroExpectedHits++ == 0) firstZeroHit = i;
            continue;
        }
        if (e < minExpected) {
            pool.o += o;
            pool.e += e;
            ++res.pooledCells;
        } else {
            cells.push_back({o, e, static_cast<long>(i)});
        }
    }
    // The small cells form one pooled cell; if it is still below minExpected
    // it joins the remaining cell with the smallest expected count.
    if (res.pooledCells > 0) {
        if (pool.e < minExpected && !cells.empty()) {
            auto smallest = std::min_element(cells.begin(), cells.end(),
                                             [](const Cell& l, const Cell& r) { return l.e < r.e; });
            smallest->o += pool.o;
            smallest->e += pool.e;
            smallest->index = -1;
        } else {
            cells.push_back(pool);
        }
    }
    res.dof = static_cast<int>(cells.size()) - 1;
    const double threshold = sidak(alpha, testCount);
    char buf[512], b1[32], b2[32];
    if (zeroExpectedHits > 0) {
        res.statistic = kInf;
        res.pValue = 0.0;
        res.passed = false;
        std::snprintf(buf, sizeof buf,
                      "chi-square: cell %zu has %s samples where the expected count is 0 "
                      "(%zu such cells): the pdf misses part of the sampled domain",
                      firstZeroHit, formatDouble(b1, sizeof b1, observed[firstZeroHit]), zeroExpectedHits);
        res.detail = buf;
        return res;
    }
    double worst = -1.0;
    const Cell* worstCell = nullptr;
    for (const Cell& c : cells) {
        const double term = (c.o - c.e) * (c.o - c.e) / c.e;
        res.statistic += term;
        if (term > worst) worst = term, worstCell = &c;
    }
    if (res.dof < 1) {
        res.pValue = kNaN;
        res.passed = false;
        std::snprintf(buf, sizeof buf,
                      "chi-square: %zu cell(s) after pooling (%zu pooled, min expected %g): "
                      "too few degrees of freedom; take more samples or fewer cells",
                      cells.size(), res.pooledCells, minExpected);
        res.detail = buf;
        return res;
    }
    res.pValue = chi2Sf(res.statistic, res.dof);
    res.passed = res.pValue > threshold;
    int len = std::snprintf(buf, sizeof buf,
                            "chi-square = %.6g, dof = %d, p = %.4g %s %.4g (alpha %g, Sidak over %zu tests); "
                            "%zu cells pooled",
                            res.statistic, res.dof, res.pValue, res.passed ? ">" : "<=", threshold, alpha,
                            testCount, res.pooledCells);
    if (worstCell && len > 0 && static_cast<std::size_t>(len) < sizeof buf) {
        char where[48];
        if (worstCell->index >= 0)
            std::snprintf(where, sizeof where, "cell %ld", worstCell->index);
        else
            std::snprintf(where, sizeof where, "the pooled cell");
        std::snprintf(buf + len, sizeof buf - len, "; largest term %.4g at %s (observed %s, expected %s)", worst,
                      where, formatDouble(b1, sizeof b1, worstCell->o), formatDouble(b2, sizeof b2, worstCell->e));
    }
    res.detail = buf;
    return res;
}

std::vector<double> histogram2D(const std::vector<std::pair<double, double>>& samples, int resX, int resY,
                                double x0, double x1, double y0, double y1) {
    require(resX > 0 && resY > 0, "histogram2D: resolution must be > 0");
    require(x1 > x0 && y1 > y0, "histogram2D: empty domain");
    std::vector<double> counts(static_cast<std::size_t>(resX) * resY, 0.0);
    const double sx = resX / (x1 - x0), sy = resY / (y1 - y0);
    for (const auto& [x, y] : samples) {
        if (!(x >= x0 && x <= x1 && y >= y0 && y <= y1)) continue;  // also drops NaN
        const int ix = std::min(static_cast<int>((x - x0) * sx), resX - 1);
        const int iy = std::min(static_cast<int>((y - y0) * sy), resY - 1);
        counts[static_cast<std::size_t>(iy) * resX + ix] += 1.0;
    }
    return counts;
}

void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    require(n > 0, "gaussLegendre: n must be > 0");
    nodes.assign(n, 0.0);
    weights.assign(n, 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        // Newton on P_n from the asymptotic guess for its i-th largest root.
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), pp = 1.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p1 = 1.0, p2 = 0.0;
            for (int j = 0; j < n; ++j) {  // (j+1) P_{j+1} = (2j+1) z P_j - j P_{j-1}
                const double p3 = p2;
                p2 = p1;
                p1 = ((2.0 * j + 1.0) * z * p2 - j * p3) / (j + 1.0);
            }
            pp = n * (z * p1 - p2) / (z * z - 1.0);  // P_n'(z)
            const double z1 = z;
            z = z1 - p1 / pp;
            if (std::abs(z - z1) <= 1e-15) break;
        }
        nodes[i] = -z;
        nodes[n - 1 - i] = z;
        weights[i] = weights[n - 1 - i] = 2.0 / ((1.0 - z * z) * pp * pp);
    }
}

std::vector<double> integrateExpected(const std::function<double(double, double)>& pdf, int resX, int resY,
                                      double x0, double x1, double y0, double y1, std::size_t sampleCount,
                                      int subdiv) {
    require(resX > 0 && resY > 0, "integrateExpected: resolution must be > 0");
    require(x1 > x0 && y1 > y0, "integrateExpected: empty domain");
    require(subdiv > 0, "integrateExpected: subdiv must be > 0");
    std::vector<double> t, w;
    gaussLegendre(subdiv, t, w);
    const double hx = (x1 - x0) / resX, hy = (y1 - y0) / resY;
    const double scale = static_cast<double>(sampleCount) * 0.25 * hx * hy;
    std::vector<double> expected(static_cast<std::size_t>(resX) * resY, 0.0);
    for (int iy = 0; iy < resY; ++iy) {
        const double cy = y0 + (iy + 0.5) * hy;
        for (int ix = 0; ix < resX; ++ix) {
            const double cx = x0 + (ix + 0.5) * hx;
            double sum = 0.0;
            for (int j = 0; j < subdiv; ++j)
                for (int i = 0; i < subdiv; ++i)
                    sum += w[i] * w[j] * pdf(cx + 0.5 * hx * t[i], cy + 0.5 * hy * t[j]);
            expected[static_cast<std::size_t>(iy) * resX + ix] = scale * sum;
        }
    }
    return expected;
}

ZTestResult perPixelZTest(const float* mean, const float* varMean, const float* refMean,
                          const float* refVarMean, std::size_t values, double alpha, double requiredFraction) {
    ZTestResult r;
    r.pixels = values;
    r.alpha = alpha;
    if (values == 0) return r;
    r.zThreshold = -normalQuantile(0.5 * sidak(alpha, values));
    for (std::size_t i = 0; i < values; ++i) {
        const double x = mean[i], ref = refMean[i];
        const double s = static_cast<double>(varMean[i]) + static_cast<double>(refVarMean[i]);
        bool ok;
        if (!std::isfinite(x) || !std::isfinite(ref) || !std::isfinite(s) || s < 0.0)
            ok = false;
        else if (s == 0.0)
            ok = x == ref;
        else
            ok = std::abs(x - ref) <= r.zThreshold * std::sqrt(s);
        r.accepted += ok ? 1 : 0;
    }
    r.acceptedFraction = static_cast<double>(r.accepted) / static_cast<double>(values);
    r.passed = r.acceptedFraction >= requiredFraction;
    return r;
}

MeanTestResult meanTest(const std::vector<double>& values, const std::vector<double>& varianceOfEach,
                        double exact, double sigmas) {
    require(values.size() == varianceOfEach.size(), "meanTest: values and variances differ in size");
    MeanTestResult r;
    if (values.empty()) {
        r.mean = r.stdError = r.z = kNaN;
        return r;
    }
    double sum = 0.0, var = 0.0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        require(varianceOfEach[i] >= 0.0, "meanTest: variances must be >= 0");
        sum += values[i];
        var += varianceOfEach[i];
    }
    const double n = static_cast<double>(values.size());
    r.mean = sum / n;
    r.stdError = std::sqrt(var) / n;
    const double diff = r.mean - exact;
    if (r.stdError > 0.0) {
        r.z = diff / r.stdError;
        r.passed = std::abs(diff) <= sigmas * r.stdError;
    } else {
        r.z = diff == 0.0 ? 0.0 : std::copysign(kInf, diff);
        r.passed = diff == 0.0;
    }
    return r;
}

double fitLogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
    require(x.size() == y.size(), "fitLogLogSlope: x and y differ in size");
    require(x.size() >= 2, "fitLogLogSlope: at least 2 points");
    const double n = static_cast<double>(x.size());
    double mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        require(x[i] > 0.0 && y[i] > 0.0, "fitLogLogSlope: x and y must be > 0");
        mx += std::log(x[i]);
        my += std::log(y[i]);
    }
    mx /= n;
    my /= n;
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double dx = std::log(x[i]) - mx, dy = std::log(y[i]) - my;
        sxy += dx * dy;
        sxx += dx * dx;
    }
    require(sxx > 0.0, "fitLogLogSlope: x values must not all be equal");
    return sxy / sxx;
}

BiasFit fitBiasFloor(const std::vector<double>& n, const std::vector<double>& mse) {
    require(n.size() == mse.size(), "fitBiasFloor: n and mse differ in size");
    require(n.size() >= 2, "fitBiasFloor: at least 2 points");
    // Weighted least squares of m = b2 + c u, u = 1/N, weights 1/m^2, in the
    // centred form (weighted means first) to avoid cancellation.
    double sw = 0.0, su = 0.0, sm = 0.0;
    for (std::size_t i = 0; i < n.size(); ++i) {
        require(n[i] > 0.0 && mse[i] > 0.0, "fitBiasFloor: N and mse must be > 0");
        const double w = 1.0 / (mse[i] * mse[i]);
        sw += w;
        su += w / n[i];
        sm += w * mse[i];
    }
    const double uBar = su / sw, mBar = sm / sw;
    double suu = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < n.size(); ++i) {
        const double w = 1.0 / (mse[i] * mse[i]), du = 1.0 / n[i] - uBar;
        suu += w * du * du;
        sum += w * du * (mse[i] - mBar);
    }
    require(suu > 0.0, "fitBiasFloor: N values must not all be equal");
    BiasFit f;
    f.c = sum / suu;
    f.b2 = mBar - f.c * uBar;
    if (f.b2 < 0.0) {
        // Constrained optimum on b2 = 0: minimise sum w (c u - m)^2.
        double wuu = 0.0, wum = 0.0;
        for (std::size_t i = 0; i < n.size(); ++i) {
            const double w = 1.0 / (mse[i] * mse[i]), u = 1.0 / n[i];
            wuu += w * u * u;
            wum += w * u * mse[i];
        }
        f.b2 = 0.0;
        f.c = wum / wuu;
    }
    return f;
}

}  // namespace strata::stats
