#include "settings/filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../../shaders/shared/types.h"
#include "util/error.h"

namespace strata {

PixelFilter filterByName(const std::string& name) {
    if (name == "box") return {FilterKind::Box, 0.5f};
    if (name == "tent") return {FilterKind::Tent, 1.0f};
    if (name == "gaussian") return {FilterKind::Gaussian, 1.5f};
    if (name == "blackman-harris") return {FilterKind::BlackmanHarris, 2.0f};
    throw Error("strata: error: unknown filter '" + name + "' (filters: box, tent, gaussian, blackman-harris)");
}

const char* filterName(FilterKind kind) {
    switch (kind) {
        case FilterKind::Box: return "box";
        case FilterKind::Tent: return "tent";
        case FilterKind::Gaussian: return "gaussian";
        case FilterKind::BlackmanHarris: return "blackman-harris";
    }
    return "box";
}

double filterValue(const PixelFilter& f, double x) {
    const double r = f.radius, ax = std::abs(x);
    if (ax > r) return 0.0;
    switch (f.kind) {
        case FilterKind::Box: return 1.0;
        case FilterKind::Tent: return r - ax;
        case FilterKind::Gaussian: {
            const double sigma = r / 3.0;
            return std::max(0.0, std::exp(-x * x / (2.0 * sigma * sigma)) - std::exp(-r * r / (2.0 * sigma * sigma)));
        }
        case FilterKind::BlackmanHarris: {
            const double t = 2.0 * std::numbers::pi * (x + r) / (2.0 * r);  // window over [0, 2 pi]
            return std::max(0.0, 0.35875 - 0.48829 * std::cos(t) + 0.14128 * std::cos(2.0 * t) -
                                     0.01168 * std::cos(3.0 * t));
        }
    }
    return 0.0;
}

std::vector<float> filterInverseCdf(const PixelFilter& f) {
    constexpr int kCells = 1 << 20;
    const double r = f.radius;
    std::vector<double> cdf(kCells + 1, 0.0);
    for (int i = 0; i < kCells; ++i) {
        const double x0 = -r + 2.0 * r * i / kCells, x1 = -r + 2.0 * r * (i + 1) / kCells;
        cdf[i + 1] = cdf[i] + 0.5 * (filterValue(f, x0) + filterValue(f, x1)) * (x1 - x0);
    }
    const double total = cdf.back();
    const int entries = static_cast<int>(gpu::kFilterTableEntries);
    std::vector<float> table(entries);
    for (int k = 0; k < entries; ++k) {
        const double target = total * k / (entries - 1);
        const auto it = std::lower_bound(cdf.begin(), cdf.end(), target);
        const int i = std::clamp(static_cast<int>(it - cdf.begin()) - 1, 0, kCells - 1);
        const double span = cdf[i + 1] - cdf[i];
        const double t = span > 0.0 ? std::clamp((target - cdf[i]) / span, 0.0, 1.0) : 0.0;
        table[k] = static_cast<float>(-r + 2.0 * r * (i + t) / kCells);
    }
    table.front() = -f.radius;
    table.back() = f.radius;
    return table;
}

}  // namespace strata
