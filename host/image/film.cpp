#include "image/film.h"

#include <cmath>

namespace strata {

FixedSum toFixed(float x) {
    const double d = static_cast<double>(x);
    if (!(std::abs(d) < kFixedLimit)) return std::signbit(d) && !std::isnan(d) ? -kFixedInf : kFixedInf;
    return static_cast<FixedSum>(std::ldexp(d, kFixedFracBits));  // exact scaling, then truncation
}

double fromFixed(FixedSum v) {
    if (v == kFixedInf) return HUGE_VAL;
    if (v == -kFixedInf) return -HUGE_VAL;
    return std::ldexp(static_cast<double>(v), -kFixedFracBits);
}

FixedSum addFixed(FixedSum a, FixedSum b) {
    if (a == kFixedInf || b == kFixedInf) return kFixedInf;
    if (a == -kFixedInf || b == -kFixedInf) return -kFixedInf;
    FixedSum r;
    if (__builtin_add_overflow(a, b, &r) || r == kFixedInf || r == -kFixedInf) return a > 0 ? kFixedInf : -kFixedInf;
    return r;
}

Film::Film(int w, int h, bool withAov)
    : width(w), height(h), sum(pixels() * 3, 0), sumSq(pixels() * 3, 0), count(pixels(), 0), aov(withAov) {
    if (aov) aovSum.assign(pixels() * kAovSums, 0);
}

void Film::fold(const float* batch) {
    const std::size_t n = pixels();
    const float* aovBatch = batch + n * 8;
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = batch + i * 8;
        if (!(std::abs(p[0]) < kFixedLimit) || !(std::abs(p[1]) < kFixedLimit) || !(std::abs(p[2]) < kFixedLimit)) {
            overflowed += static_cast<std::uint64_t>(p[3]);
            continue;
        }
        for (int c = 0; c < 3; ++c) {
            sum[i * 3 + c] = addFixed(sum[i * 3 + c], toFixed(p[c]));
            sumSq[i * 3 + c] = addFixed(sumSq[i * 3 + c], toFixed(p[4 + c]));
        }
        count[i] += static_cast<std::uint64_t>(p[3]);
        if (aov)
            for (int k = 0; k < kAovSums; ++k)
                aovSum[i * kAovSums + k] = addFixed(aovSum[i * kAovSums + k], toFixed(aovBatch[i * kAovSums + k]));
    }
}

void Film::add(const Film& o) {
    for (std::size_t i = 0; i < sum.size(); ++i) {
        sum[i] = addFixed(sum[i], o.sum[i]);
        sumSq[i] = addFixed(sumSq[i], o.sumSq[i]);
    }
    for (std::size_t i = 0; i < count.size(); ++i) count[i] += o.count[i];
    for (std::size_t i = 0; i < aovSum.size(); ++i) aovSum[i] = addFixed(aovSum[i], o.aovSum[i]);
    overflowed += o.overflowed;
}

std::vector<float> Film::mean() const {
    std::vector<float> out(pixels() * 3, 0.0f);
    for (std::size_t i = 0; i < pixels(); ++i)
        if (count[i])
            for (int c = 0; c < 3; ++c) out[i * 3 + c] = static_cast<float>(sumAt(i, c) / count[i]);
    return out;
}

std::vector<float> Film::varianceOfMean() const {
    std::vector<float> out(pixels() * 3, 0.0f);
    for (std::size_t i = 0; i < pixels(); ++i) {
        const double n = static_cast<double>(count[i]);
        if (n < 2) continue;
        for (int c = 0; c < 3; ++c) {
            const double m = sumAt(i, c) / n;
            const double var = (fromFixed(sumSq[i * 3 + c]) - n * m * m) / (n - 1.0);
            out[i * 3 + c] = static_cast<float>(var > 0.0 ? var / n : 0.0);
        }
    }
    return out;
}

}  // namespace strata
