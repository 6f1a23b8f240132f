// Image error metrics; definitions in metrics.h.
#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <vector>

namespace strata {
namespace {

bool finitePair(float x, float r) { return std::isfinite(x) && std::isfinite(r); }

double relTerm(double x, double r, double eps) {
    const double d = x - r;
    return d * d / (r * r + eps);
}

// floor(fraction * n), where a product within 1e-9 (relative) of an integer
// counts as that integer (0.29 * 100 is 28.999999999999996 in double).
std::uint64_t trimCount(double fraction, std::uint64_t n) {
    if (n == 0 || fraction <= 0.0) return 0;
    const double p = fraction * static_cast<double>(n);
    const auto k = static_cast<std::uint64_t>(std::floor(p + 1e-9 * std::max(1.0, p)));
    return std::min<std::uint64_t>(k, n - 1);
}

}  // namespace

ErrorMetrics compareImages(const float* image, const float* reference, std::size_t count, double eps,
                           double trimFraction) {
    if (!(eps > 0.0) || !std::isfinite(eps))
        throw std::invalid_argument("compareImages: eps must be finite and > 0");
    if (!(trimFraction >= 0.0 && trimFraction < 1.0))
        throw std::invalid_argument("compareImages: trimFraction must be in [0, 1)");

    ErrorMetrics m;
    m.eps = eps;
    m.trimFraction = trimFraction;

    // Pass 1: plain sums, and the count of finite pairs.
    double se = 0.0, rel = 0.0, ape = 0.0, sape = 0.0, maxAbs = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        const float xf = image[i], rf = reference[i];
        if (!finitePair(xf, rf)) {
            ++m.nonFinite;
            continue;
        }
        const double x = xf, r = rf, a = std::abs(x - r);
        se += a * a;
        rel += relTerm(x, r, eps);
        ape += a / (std::abs(r) + eps);
        sape += 2.0 * a / (std::abs(x) + std::abs(r) + eps);
        maxAbs = std::max(maxAbs, a);
        ++m.values;
    }
    if (m.values == 0) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        m.rmse = m.relMse = m.relMseTrimmed = m.mape = m.smape = m.maxAbs = nan;
        return m;
    }
    const double n = static_cast<double>(m.values);
    m.rmse = std::sqrt(se / n);
    m.relMse = rel / n;
    m.mape = ape / n;
    m.smape = sape / n;
    m.maxAbs = maxAbs;

    // Trimmed relMSE. Pass 2 finds the k largest terms with a min-heap of size
    // k (O(k) memory); pass 3 sums the kept terms directly, rather than
    // subtracting the dropped ones, so a firefly does not cancel the rest.
    m.trimmed = trimCount(trimFraction, m.values);
    const std::uint64_t k = m.trimmed;
    if (k == 0) {
        m.relMseTrimmed = m.relMse;
        return m;
    }
    std::priority_queue<double, std::vector<double>, std::greater<double>> top;
    for (std::size_t i = 0; i < count; ++i) {
        if (!finitePair(image[i], reference[i])) continue;
        const double t = relTerm(image[i], reference[i], eps);
        if (top.size() < k) {
            top.push(t);
        } else if (t > top.top()) {
            top.pop();
            top.push(t);
        }
    }
    // threshold = the k-th largest term; of the terms equal to it, only as
    // many as the top k did not take are kept.
    const double threshold = top.top();
    double keptSum = 0.0;
    std::uint64_t above = 0, equal = 0;
    for (std::size_t i = 0; i < count; ++i) {
        if (!finitePair(image[i], reference[i])) continue;
        const double t = relTerm(image[i], reference[i], eps);
        if (t < threshold)
            keptSum += t;
        else if (t > threshold)
            ++above;
        else
            ++equal;
    }
    const std::uint64_t equalKept = equal - (k - above);
    keptSum += static_cast<double>(equalKept) * threshold;
    m.relMseTrimmed = keptSum / static_cast<double>(m.values - k);
    return m;
}

std::string metricsText(const ErrorMetrics& m) {
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "values        %llu compared, %llu non-finite (excluded)\n"
                  "RMSE          %.6e\n"
                  "relMSE        %.6e  (eps %g)\n"
                  "relMSE trim   %.6e  (largest %g%% of terms dropped: %llu)\n"
                  "MAPE          %.6e  (eps %g)\n"
                  "SMAPE         %.6e  (eps %g)\n"
                  "max |x - r|   %.6e\n",
                  static_cast<unsigned long long>(m.values), static_cast<unsigned long long>(m.nonFinite),
                  m.rmse, m.relMse, m.eps, m.relMseTrimmed, 100.0 * m.trimFraction,
                  static_cast<unsigned long long>(m.trimmed), m.mape, m.eps, m.smape, m.eps, m.maxAbs);
    return buf;
}

}  // namespace strata
