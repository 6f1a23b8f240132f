// Error metrics of a rendered image against a reference. Values are compared
// one by one with channels flattened (the caller passes interleaved RGB, so
// `count` = 3 * pixels). For value i, x = image[i], r = reference[i]:
//
//   RMSE            = sqrt( mean (x - r)^2 )
//   relMSE          = mean (x - r)^2 / (r^2 + eps)
//   relMSE trimmed  = the relMSE mean after dropping the largest
//                     floor(trimFraction * values) per-value terms (pbrt-v4 /
//                     Mitsuba practice of discarding fireflies; default: the
//                     top 0.1%)
//   MAPE            = mean |x - r| / (|r| + eps)
//   SMAPE           = mean 2 |x - r| / (|x| + |r| + eps)        (in [0, 2))
//   maxAbs          = max |x - r|
//
// A value where x or r is NaN or +-Inf is counted in `nonFinite` and excluded
// from every mean and from maxAbs; `values` counts the values that were
// compared (count - nonFinite). All sums are accumulated in double. When no
// value is finite, every metric is NaN.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace strata {

struct ErrorMetrics {
    double rmse = 0.0;
    double relMse = 0.0;
    double relMseTrimmed = 0.0;
    double mape = 0.0;
    double smape = 0.0;
    double maxAbs = 0.0;
    std::uint64_t nonFinite = 0;  // values with x or r NaN/Inf (excluded)
    std::uint64_t values = 0;     // values compared (finite pairs)
    double eps = 0.0;             // the eps of relMSE, MAPE and SMAPE
    double trimFraction = 0.0;    // the fraction of relMSE terms asked to be trimmed
    std::uint64_t trimmed = 0;    // relMSE terms dropped: floor(trimFraction * values)
};

// Compares `count` values of `image` with `reference`. eps > 0 (default 1e-2,
// as pbrt-v4's imgtool and Mitsuba use for relMSE); trimFraction in [0, 1).
// Throws std::invalid_argument for eps or trimFraction out of range.
ErrorMetrics compareImages(const float* image, const float* reference, std::size_t count,
                           double eps = 1e-2, double trimFraction = 0.001);

// A few aligned lines ("RMSE      1.234e-02"), stating eps and the trimming.
std::string metricsText(const ErrorMetrics& m);

}  // namespace strata
