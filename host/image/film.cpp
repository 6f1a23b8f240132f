#include "image/film.h"

#include <cmath>

namespace strata {

Film::Film(int w, int h, bool withAov)
    : width(w), height(h), sum(pixels() * 3, 0.0), sumSq(pixels() * 3, 0.0), count(pixels(), 0), aov(withAov) {
    if (aov) aovSum.assign(pixels() * kAovSums, 0.0);
}

void Film::fold(const float* batch) {
    const std::size_t n = pixels();
    const float* aovBatch = batch + n * 8;
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = batch + i * 8;
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            overflowed += static_cast<std::uint64_t>(p[3]);
            continue;
        }
        for (int c = 0; c < 3; ++c) {
            sum[i * 3 + c] += p[c];
            sumSq[i * 3 + c] += p[4 + c];
        }
        count[i] += static_cast<std::uint64_t>(p[3]);
        if (aov)
            for (int k = 0; k < kAovSums; ++k) aovSum[i * kAovSums + k] += aovBatch[i * kAovSums + k];
    }
}

std::vector<float> Film::mean() const {
    std::vector<float> out(pixels() * 3, 0.0f);
    for (std::size_t i = 0; i < pixels(); ++i)
        if (count[i])
            for (int c = 0; c < 3; ++c) out[i * 3 + c] = static_cast<float>(sum[i * 3 + c] / count[i]);
    return out;
}

std::vector<float> Film::varianceOfMean() const {
    std::vector<float> out(pixels() * 3, 0.0f);
    for (std::size_t i = 0; i < pixels(); ++i) {
        const double n = static_cast<double>(count[i]);
        if (n < 2) continue;
        for (int c = 0; c < 3; ++c) {
            const double m = sum[i * 3 + c] / n;
            const double var = (sumSq[i * 3 + c] - n * m * m) / (n - 1.0);
            out[i * 3 + c] = static_cast<float>(var > 0.0 ? var / n : 0.0);
        }
    }
    return out;
}

}  // namespace strata
