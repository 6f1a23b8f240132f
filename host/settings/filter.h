// Pixel reconstruction filters, applied by filter importance sampling
// (Ernst et al. 2006, "Filter Importance Sampling"): each camera sample is
// offset from the pixel centre with the density of the (non-negative,
// separable) filter and carries weight 1, so progressive accumulation stays
// a plain average.
#pragma once
#include <string>
#include <vector>

namespace strata {

enum class FilterKind { Box, Tent, Gaussian, BlackmanHarris };

struct PixelFilter {
    FilterKind kind = FilterKind::Box;
    float radius = 0.5f;  // in pixels; the filter is zero outside [-radius, radius]^2
};


// "box", "tent", "gaussian", "blackman-harris" with their default radii
// (0.5, 1, 1.5, 2 pixels). Throws strata::Error for another name.
PixelFilter filterByName(const std::string& name);
const char* filterName(FilterKind kind);

// The 1D filter profile at x (pixels), >= 0; the 2D filter is f(x) f(y).
// gaussian: exp(-x^2 / (2 sigma^2)) - exp(-r^2 / (2 sigma^2)), sigma = r / 3;
// blackman-harris: the 4-term window (Harris 1978) stretched over [-r, r].
double filterValue(const PixelFilter& f, double x);

// Offsets (pixels) at u = i / (gpu::kFilterTableEntries - 1): the inverse of
// the normalised CDF of filterValue, from a fine piecewise-linear
// integration, kFilterTableEntries (16385) entries: the chi-square test at
// 500k samples cannot tell its piecewise-linear inverse from the filter,
// where it can with 1025 entries in the Gaussian's and Blackman-Harris's
// tails.
std::vector<float> filterInverseCdf(const PixelFilter& f);

}  // namespace strata
