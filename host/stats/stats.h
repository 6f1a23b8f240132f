// The statistical tests of the test suite, in the style of Mitsuba 3's
// ChiSquareTest and pbrt-v4's sampling tests, with their numerics (normal
// quantile, chi-square tail) implemented here on the C++ standard library.
//
// Invalid arguments (mismatched sizes, negative counts or variances, too few
// points for a fit) are programming errors and throw std::invalid_argument.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace strata::stats {

// --- distributions -------------------------------------------------------

// Standard normal CDF, 0.5 * erfc(-z / sqrt 2), with the rounding error of
// z / sqrt 2 compensated: ~1e-15 relative in the lower tail down to z = -37.
double normalCdf(double z);

// Inverse of normalCdf for p in [0, 1]; -inf at 0, +inf at 1, NaN outside.
// P. J. Acklam's rational approximation (rel. error 1.15e-9) refined by one
// Halley step on erfc, which brings it to ~1e-15 relative. p > 0.5 is
// answered as -normalQuantile(1 - p) (1 - p is exact there).
double normalQuantile(double p);

// Sidak-corrected per-test significance level for `tests` independent tests
// with family-wise level alpha: 1 - (1 - alpha)^(1/tests), computed as
// -expm1(log1p(-alpha) / tests) so it keeps full precision for many tests.
double sidak(double alpha, std::size_t tests);

// Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a), a > 0,
// x >= 0: the series for P when x < a + 1, otherwise the continued fraction
// for Q evaluated by the modified Lentz method (Numerical Recipes 3rd ed.,
// sec. 6.2). The prefactor x^a e^-x / Gamma(a) is formed for a >= 10 from
// Loader's deviance and Stirling's series, not from lgamma, so large a keeps
// full precision: within 4e-14 relative of mpmath from dof 0.5 to 2e6 and
// down to Q = 1e-304 in the tests.
double gammaQ(double a, double x);

// Chi-square upper tail probability P(X > x) for `dof` degrees of freedom:
// Q(dof / 2, x / 2).
double chi2Sf(double x, double dof);

// --- Pearson chi-square goodness-of-fit test ------------------------------

struct ChiSquareResult {
    double statistic = 0.0;      // sum over (pooled) cells of (O - E)^2 / E
    double pValue = 0.0;         // chi2Sf(statistic, dof)
    int dof = 0;                 // cells after pooling - 1
    std::size_t pooledCells = 0; // original cells merged into the pooled cell
    bool passed = false;         // pValue > sidak(alpha, testCount) and dof >= 1
    std::string detail;          // one line: statistic, dof, p, threshold; or why it failed
};

// Tests observed counts against expected counts cell by cell. As Mitsuba's
// ChiSquareTest: cells with 0 < expected < minExpected are merged into one
// pooled cell; if that cell's expected count is still < minExpected it is
// merged into the remaining cell with the smallest expected count. Cells with
// expected == 0 and observed == 0 are ignored; an observed count in a cell
// with expected == 0 fails the test outright (statistic +inf, p 0). Fails
// when fewer than 2 cells remain (dof < 1). The test passes when the p-value
// exceeds the Sidak-corrected level for `testCount` tests at level alpha.
ChiSquareResult chiSquareTest(const std::vector<double>& observed, const std::vector<double>& expected,
                              double alpha, std::size_t testCount = 1, double minExpected = 5.0);

// Counts of 2D samples on a resX x resY grid over [x0, x1] x [y0, y1],
// row-major: cell (ix, iy) at index iy * resX + ix, ix = floor((x - x0) /
// (x1 - x0) * resX). The domain is closed (x == x1 lands in the last column);
// samples outside it, and NaN samples, are ignored. Odd resolutions (e.g. 17
// x 33) are the convention, so bin edges do not align with symmetric features.
std::vector<double> histogram2D(const std::vector<std::pair<double, double>>& samples, int resX, int resY,
                                double x0, double x1, double y0, double y1);

// Expected counts on the same grid: sampleCount * the integral of `pdf` (a
// density with respect to dx dy on the grid's domain; the caller includes any
// Jacobian, e.g. sin(theta) for (theta, phi)) over each cell, by tensor-product
// Gauss-Legendre quadrature with `subdiv` nodes per axis per cell (exact for
// polynomials of degree 2 subdiv - 1 in each variable).
std::vector<double> integrateExpected(const std::function<double(double, double)>& pdf, int resX, int resY,
                                      double x0, double x1, double y0, double y1, std::size_t sampleCount,
                                      int subdiv = 8);

// Gauss-Legendre nodes and weights on [-1, 1] (Newton iteration on the
// Legendre recurrence, as Numerical Recipes' gauleg).
void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

// --- renders against references --------------------------------------------

struct ZTestResult {
    std::size_t pixels = 0;      // values tested (channels flattened)
    std::size_t accepted = 0;
    double acceptedFraction = 0.0;
    double alpha = 0.0;          // family-wise level asked for
    double zThreshold = 0.0;     // two-sided normal quantile at sidak(alpha, pixels)
    bool passed = false;
};

// Per-value Z-test of a render (mean, variance of the mean) against a
// reference that stores its variance: z = (x - r) / sqrt(varX + varR); a value
// is accepted when |z| <= zThreshold, the two-sided normal quantile at the
// Sidak-corrected level sidak(alpha, values); when varX + varR == 0 it is
// accepted only if x == r exactly; non-finite values are never accepted.
// Passes when accepted / values >= requiredFraction (the criterion:
// 99.75% accepted at alpha = 0.01 with Sidak correction). values == 0 fails.
ZTestResult perPixelZTest(const float* mean, const float* varMean, const float* refMean,
                          const float* refVarMean, std::size_t values, double alpha = 0.01,
                          double requiredFraction = 0.9975);

struct MeanTestResult {
    double mean = 0.0;
    double stdError = 0.0;  // sqrt(sum of variances) / n
    double z = 0.0;         // (mean - exact) / stdError (0 or +-inf when stdError == 0)
    bool passed = false;
};

// Mean of independent values with known variances against an exact answer:
// passes when |mean - exact| <= sigmas * stdError, and, when stdError == 0,
// only when mean == exact exactly. An empty input fails.
MeanTestResult meanTest(const std::vector<double>& values, const std::vector<double>& varianceOfEach,
                        double exact, double sigmas = 4.0);

// --- convergence fits -------------------------------------------------------

// Least-squares slope of log y against log x (x, y > 0, at least 2 distinct x):
// the convergence order, -1 for an unbiased estimator's MSE against N.
double fitLogLogSlope(const std::vector<double>& x, const std::vector<double>& y);

struct BiasFit {
    double b2 = 0.0;  // squared bias: the MSE floor as N -> inf (>= 0)
    double c = 0.0;   // variance coefficient: MSE = b2 + c / N
};

// Fits MSE(N) = b2 + c / N by linear least squares in u = 1/N, each point
// weighted by 1 / mse^2 (relative least squares, so small errors count as much
// as large ones); b2 is constrained >= 0 (when the free fit's b2 is negative
// the constrained optimum has b2 = 0, and c is refitted alone). N, mse > 0.
BiasFit fitBiasFloor(const std::vector<double>& n, const std::vector<double>& mse);

}  // namespace strata::stats
