// The host-side accumulation of a render, in double precision. The device
// accumulates float32 sums for a bounded batch of samples; the host folds
// each batch in here, so the running sums do not drift however many samples
// are taken.
#pragma once
#include <cstdint>
#include <vector>

namespace strata {

struct Film {
    int width = 0;
    int height = 0;
    std::vector<double> sum;          // rgb per pixel
    std::vector<double> sumSq;        // rgb per pixel: sum of squared samples
    std::vector<std::uint64_t> count; // finite samples per pixel
    // Samples of batches whose float32 sum overflowed (each sample finite,
    // their sum not): left out, like non-finite samples.
    std::uint64_t overflowed = 0;
    // With AOVs (RenderSettings::aov): kAovSums per pixel, the device's
    // kAovVec4PerPixel vec4 (shaders/shared/types.h) summed over the same
    // samples as `sum`: half A's rgb and count, albedo rgb, depth, normal
    // xyz, emitter mark, albedo squared, depth squared, normal squared, 0.
    bool aov = false;
    std::vector<double> aovSum;
    static constexpr int kAovSums = 20;

    Film() = default;
    Film(int w, int h, bool withAov = false);
    std::size_t pixels() const { return static_cast<std::size_t>(width) * height; }

    // Adds a device batch: per pixel two vec4 (sum rgb + count, sumSq rgb + 0),
    // the layout of gpu::kAccumVec4PerPixel, then with AOVs the AOV sums. A pixel whose batch sum is not
    // finite keeps none of that batch (counted in `overflowed`); a square sum
    // beyond float is kept, so its variance reads as infinite.
    void fold(const float* batch);

    // Per-pixel mean rgb (float, row-major, row 0 at the top); 0 where a pixel
    // has no finite sample.
    std::vector<float> mean() const;

    // Per-pixel variance of the mean (sample variance / count), rgb.
    std::vector<float> varianceOfMean() const;
};

}  // namespace strata
