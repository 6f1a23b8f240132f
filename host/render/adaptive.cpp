#include "render/adaptive.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata {

double pixelError(const Film& film, std::size_t i) {
    const double n = static_cast<double>(film.count[i]);
    if (n < 2.0) return std::numeric_limits<double>::infinity();
    double mean = 0.0, varianceOfMean = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double m = fromFixed(film.sum[i * 3 + c]) / n;
        const double sq = fromFixed(film.sumSq[i * 3 + c]);
        mean += m / 3.0;
        varianceOfMean += std::max(0.0, (sq - n * m * m) / (n - 1.0)) / n / 3.0;
    }
    const double e = std::sqrt(varianceOfMean / (mean * mean + 0.01));
    return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

ActiveBlocks::ActiveBlocks(int width, int height)
    : columns((width + 7) / 8), rows((height + 7) / 8),
      active(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), 1u) {}

std::size_t ActiveBlocks::activeCount() const {
    return static_cast<std::size_t>(std::count(active.begin(), active.end(), 1u));
}

std::uint64_t ActiveBlocks::activePixels(int width, int height) const {
    std::uint64_t pixels = 0;
    for (int by = 0; by < rows; ++by)
        for (int bx = 0; bx < columns; ++bx)
            if (active[static_cast<std::size_t>(by) * columns + bx] != 0u)
                pixels += static_cast<std::uint64_t>(std::min(8, width - 8 * bx)) * std::min(8, height - 8 * by);
    return pixels;
}

void retireConverged(const Film& film, double threshold, ActiveBlocks& blocks) {
    for (int by = 0; by < blocks.rows; ++by)
        for (int bx = 0; bx < blocks.columns; ++bx) {
            std::uint32_t& a = blocks.active[static_cast<std::size_t>(by) * blocks.columns + bx];
            if (a == 0u) continue;
            bool converged = true;
            for (int y = 8 * by; converged && y < std::min(film.height, 8 * by + 8); ++y)
                for (int x = 8 * bx; converged && x < std::min(film.width, 8 * bx + 8); ++x)
                    converged = pixelError(film, static_cast<std::size_t>(y) * film.width + x) <= threshold;
            if (converged) a = 0u;
        }
}

}  // namespace strata
