// The host-side accumulation of a render. The device accumulates float32
// sums for a bounded batch of samples; the host folds each batch in here as
// fixed-point integers, so the running sums do not drift however many
// samples are taken, and adding them is exact: any grouping of the same
// batches (a render in one go, resumed, or split into shards and merged)
// gives the same bits.
#pragma once
#include <cstdint>
#include <vector>

#include "../../shaders/shared/types.h"

namespace strata {

// A sum in units of 2^-kFixedFracBits, in a 128-bit integer: 2^-48 to
// 2^79 (6e23). A float32 of magnitude 2^-25 or more converts exactly;
// smaller parts are truncated toward zero. Magnitudes of 2^79 or more (and
// Inf, NaN) become +-kFixedInf, which adding keeps: they read back as
// infinite.
using FixedSum = __int128;
static_assert(sizeof(FixedSum) == 16, "FixedSum is the 128-bit integer the comment above states");
inline constexpr int kFixedFracBits = 48;
inline constexpr double kFixedLimit = 0x1p79;
inline constexpr FixedSum kFixedInf = ~(static_cast<FixedSum>(1) << 127);  // the largest value

FixedSum toFixed(float x);
double fromFixed(FixedSum v);
// Saturating: an infinite operand, or a result beyond the range, is +-kFixedInf.
FixedSum addFixed(FixedSum a, FixedSum b);

struct Film {
    int width = 0;
    int height = 0;
    std::vector<FixedSum> sum;        // rgb per pixel
    std::vector<FixedSum> sumSq;      // rgb per pixel: sum of squared samples
    std::vector<std::uint64_t> count; // finite samples per pixel
    // Samples of batches whose float32 sum overflowed (each sample finite,
    // their sum not): left out, like non-finite samples.
    std::uint64_t overflowed = 0;
    // With AOVs (RenderSettings::aov): kAovSums per pixel, the device's
    // kAovVec4PerPixel vec4 (shaders/shared/types.h) summed over the same
    // samples as `sum`: half A's rgb and count, albedo rgb, depth, normal
    // xyz, emitter mark, albedo squared, depth squared, normal squared, 0.
    bool aov = false;
    std::vector<FixedSum> aovSum;
    static constexpr int kAovSums = 20;
    static_assert(kAovSums == 4 * gpu::kAovVec4PerPixel, "kAovSums: the device's kAovVec4PerPixel vec4 a pixel");

    Film() = default;
    Film(int w, int h, bool withAov = false);
    std::size_t pixels() const { return static_cast<std::size_t>(width) * height; }
    // The floats of a device batch: gpu::kAccumVec4PerPixel vec4 a pixel, then
    // with AOVs kAovSums more.
    std::size_t batchFloats() const { return pixels() * (8 + (aov ? kAovSums : 0)); }
    static_assert(4 * gpu::kAccumVec4PerPixel == 8, "batchFloats and fold read two vec4 (8 floats) a pixel");

    // Adds a device batch: per pixel two vec4 (sum rgb + count, sumSq rgb + 0),
    // the layout of gpu::kAccumVec4PerPixel, then with AOVs the AOV sums. A
    // pixel whose batch sum is not finite, or kFixedLimit or more, keeps none
    // of that batch (counted in `overflowed`); a square sum beyond the range
    // is kept, so its variance reads as infinite.
    void fold(const float* batch);

    // Adds another film's sums (the same size and AOVs): exact.
    void add(const Film& other);

    // The sums as doubles: pixel i's channel c, AOV sum k.
    double sumAt(std::size_t i, int c) const { return fromFixed(sum[i * 3 + c]); }
    double aovAt(std::size_t i, int k) const { return fromFixed(aovSum[i * kAovSums + k]); }

    // Per-pixel mean rgb (float, row-major, row 0 at the top); 0 where a pixel
    // has no finite sample.
    std::vector<float> mean() const;

    // Per-pixel variance of the mean (sample variance / count), rgb.
    std::vector<float> varianceOfMean() const;
};

}  // namespace strata
