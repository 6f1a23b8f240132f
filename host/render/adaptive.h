// Adaptive sampling (--noise-threshold, --min-spp): the image's 8x8 blocks
// stop taking samples once every pixel's estimated error is within the
// threshold; --spp is the cap. The decisions are made on the host between
// batches, at the folds (multiples of kAdaptiveStep samples), from the film's
// exact sums alone: so a render is the same bits for a seed however its
// submissions were cut, and a resumed state finds the same blocks retired
// again from its film (render/renderer.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "image/film.h"

namespace strata {

// Samples between two decisions (the fold interval of an adaptive render).
inline constexpr std::uint32_t kAdaptiveStep = 16;

// Pixel i's estimated error: the standard error of its mean (from the sums
// of samples and of their squares, averaged over r, g, b) relative to
// sqrt(I^2 + 0.01), I its mean: the square root of its term of the relMSE
// `strata compare` reports (eps 0.01). Infinite below 2 finite samples.
double pixelError(const Film& film, std::size_t i);

// The active 8x8 blocks (1 sampled, 0 retired), row-major, ceil(w/8) x
// ceil(h/8): what BINDING_ACTIVE_BLOCKS holds.
struct ActiveBlocks {
    int columns = 0, rows = 0;
    std::vector<std::uint32_t> active;
    ActiveBlocks() = default;
    ActiveBlocks(int width, int height);
    std::size_t activeCount() const;
    // Pixels of the active blocks within a width x height image.
    std::uint64_t activePixels(int width, int height) const;
};

// Retires every active block whose every pixel has pixelError <= threshold.
void retireConverged(const Film& film, double threshold, ActiveBlocks& blocks);

}  // namespace strata
