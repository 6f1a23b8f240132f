// Texture levels: an image halved in the coding its texture reads it (the
// levels of a mip chain, downsampling to a size), and the texel decoding
// they and the emitters' mean colour share.
#include "pack/texture_levels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace strata {

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

namespace {

// Channel c (0-3) of texel i as a value in [0, 1].
double channel(const TextureImage& image, std::size_t i, int c) {
    if (image.bits == 16) {
        std::uint16_t v;
        std::memcpy(&v, image.data.data() + (i * 4 + static_cast<std::size_t>(c)) * 2, 2);
        return v / 65535.0;
    }
    return image.data[i * 4 + static_cast<std::size_t>(c)] / 255.0;
}

// The sRGB encoding curve, the inverse of srgbToLinear.
double linearToSrgb(double v) {
    return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

// The 256 8-bit sRGB codes decoded once: the same doubles as
// srgbToLinear(k / 255.0), without a pow per texel.
const std::array<double, 256>& decodedSrgb8() {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (int k = 0; k < 256; ++k) t[std::size_t(k)] = srgbToLinear(k / 255.0);
        return t;
    }();
    return table;
}

// One halving (each side to ceil(side / 2)): each texel the mean of the up
// to 2x2 it covers, its colour weighted by `weight` (one per texel of `in`;
// none: equal weights; where the weights sum to 0, equal weights too).
// `meanWeight`, when given, receives each new texel's mean weight.
TextureImage halved(const TextureImage& in, TexelCoding coding, const std::vector<double>* weight = nullptr,
                    std::vector<double>* meanWeight = nullptr) {
    TextureImage out;
    out.name = in.name;
    out.bits = in.bits;
    out.width = (in.width + 1) / 2;
    out.height = (in.height + 1) / 2;
    const std::size_t bytes = in.bits == 16 ? 2 : 1;
    const double scale = in.bits == 16 ? 65535.0 : 255.0;
    out.data.resize(std::size_t(out.width) * std::size_t(out.height) * 4 * bytes);
    if (meanWeight) meanWeight->assign(std::size_t(out.width) * std::size_t(out.height), 0.0);
    auto put = [&](std::size_t i, int c, double v) {
        const auto q = static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0, 1.0) * scale));
        if (bytes == 2) {
            const auto w = static_cast<std::uint16_t>(q);
            std::memcpy(out.data.data() + (i * 4 + std::size_t(c)) * 2, &w, 2);
        } else {
            out.data[i * 4 + std::size_t(c)] = static_cast<std::uint8_t>(q);
        }
    };
    const std::array<double, 256>& decoded8 = decodedSrgb8();
    const bool lookup = coding == TexelCoding::Srgb && in.bits != 16;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            double sum[4] = {0.0, 0.0, 0.0, 0.0}, weighted[3] = {0.0, 0.0, 0.0}, weights = 0.0;
            int n = 0;
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx) {
                    const int sx = 2 * x + dx, sy = 2 * y + dy;
                    if (sx >= in.width || sy >= in.height) continue;
                    const std::size_t i = std::size_t(sy) * std::size_t(in.width) + std::size_t(sx);
                    const double w = weight ? (*weight)[i] : 1.0;
                    for (int c = 0; c < 4; ++c) {
                        double v;
                        if (c < 3 && lookup) {
                            v = decoded8[in.data[i * 4 + std::size_t(c)]];
                        } else {
                            v = channel(in, i, c);
                            if (c < 3 && coding == TexelCoding::Srgb) v = srgbToLinear(v);
                            if (c < 3 && coding == TexelCoding::Normal) v = 2.0 * v - 1.0;
                        }
                        sum[c] += v;
                        if (c < 3) weighted[c] += w * v;
                    }
                    weights += w;
                    ++n;
                }
            const std::size_t o = std::size_t(y) * std::size_t(out.width) + std::size_t(x);
            glm::dvec3 rgb(sum[0] / n, sum[1] / n, sum[2] / n);
            if (weight && weights > 0.0) rgb = glm::dvec3(weighted[0], weighted[1], weighted[2]) / weights;
            if (meanWeight) (*meanWeight)[o] = weights / n;
            if (coding == TexelCoding::Normal) {
                const double len = glm::length(rgb);
                rgb = len > 0.0 ? 0.5 * (rgb / len) + 0.5 : glm::dvec3(0.5, 0.5, 1.0);
            } else if (coding == TexelCoding::Srgb) {
                rgb = {linearToSrgb(rgb.x), linearToSrgb(rgb.y), linearToSrgb(rgb.z)};
            }
            for (int c = 0; c < 3; ++c) put(o, c, rgb[c]);
            put(o, 3, sum[3] / n);
        }
    return out;
}

// Alpha channel of texel i as its code (0-255 or 0-65535).
std::uint32_t alphaCode(const TextureImage& image, std::size_t i) {
    if (image.bits == 16) {
        std::uint16_t v;
        std::memcpy(&v, image.data.data() + (i * 4 + 3) * 2, 2);
        return v;
    }
    return image.data[i * 4 + 3];
}

void setAlphaCode(TextureImage& image, std::size_t i, std::uint32_t code) {
    if (image.bits == 16) {
        const auto v = static_cast<std::uint16_t>(code);
        std::memcpy(image.data.data() + (i * 4 + 3) * 2, &v, 2);
    } else {
        image.data[i * 4 + 3] = static_cast<std::uint8_t>(code);
    }
}

// Lookup points a texel for forLookupPoints: 4 x 4 up to 2^16 texels (the
// small levels, where each texel's share is large), the 2 x 2 quarter
// points above.
int lookupSide(std::uint64_t texels) { return texels <= (std::uint64_t(1) << 16) ? 4 : 2; }

// How many points forLookupPoints visits.
std::uint64_t lookupPoints(int w, int h) {
    const std::uint64_t texels = std::uint64_t(w) * std::uint64_t(h);
    const auto n = std::uint64_t(lookupSide(texels));
    return texels * n * n;
}

// Calls use(v) for the bilinear lookups v of values[texel index] at n x n
// points spread evenly over every texel of a w x h image (repeat wrap; n =
// lookupSide).
template <class Use>
void forLookupPoints(int w, int h, const std::vector<double>& values, Use use) {
    const int n = lookupSide(std::uint64_t(w) * std::uint64_t(h));
    for (int y = 0; y < h; ++y)
        for (int j = 0; j < n; ++j) {
            // The points' offsets from the texel's centre, and the row and
            // column on their side.
            const double fy = std::abs((j + 0.5) / n - 0.5);
            const int y2 = 2 * j < n ? (y == 0 ? h - 1 : y - 1) : (y + 1 == h ? 0 : y + 1);
            const double* row = values.data() + std::size_t(y) * std::size_t(w);
            const double* row2 = values.data() + std::size_t(y2) * std::size_t(w);
            for (int x = 0; x < w; ++x)
                for (int i = 0; i < n; ++i) {
                    const double fx = std::abs((i + 0.5) / n - 0.5);
                    const int x2 = 2 * i < n ? (x == 0 ? w - 1 : x - 1) : (x + 1 == w ? 0 : x + 1);
                    use((1.0 - fy) * ((1.0 - fx) * row[x] + fx * row[x2]) + fy * ((1.0 - fx) * row2[x] + fx * row2[x2]));
                }
        }
}

// Successive halvings of one image (a mip chain, or downsampling) as its
// materials' alpha reads it (AlphaUse). MASK takes colour as the mean over
// the base texels that pass the cutoff; with `keepCoverage` (downsampling,
// whose result the alpha test reads) each level's alpha is also scaled so
// that its bilinear lookups pass as often as the base's (Castano 2010,
// coverage-preserving alpha); mip levels, which only shading reads, keep
// the plain mean. BLEND takes colour weighted by alpha (premultiplied).
class Halver {
public:
    Halver(const TextureImage& base, TexelCoding coding, AlphaUse alpha, bool keepCoverage)
        : coding_(coding), alpha_(alpha), keepCoverage_(keepCoverage) {
        if (alpha_.mode != AlphaUse::Mode::Mask) return;
        const std::uint32_t top = base.bits == 16 ? 65535u : 255u;
        // The first code that passes, with the shader's float arithmetic
        // (lib/material.glsl alphaHole: factor x texel < cutoff is a hole).
        passCode_ = top + 1;
        for (std::uint32_t c = 0; c <= top; ++c)
            if (!(alpha_.factor * (float(c) / float(top)) < alpha_.cutoff)) {
                passCode_ = c;
                break;
            }
        const std::size_t count = std::size_t(base.width) * std::size_t(base.height);
        coverage_.resize(count);
        for (std::size_t i = 0; i < count; ++i) coverage_[i] = alphaCode(base, i) >= passCode_ ? 1.0 : 0.0;
        if (!keepCoverage_) return;
        // The base's share: its bilinear lookups (forLookupPoints) that pass.
        const double cutoff = double(passCode_) / double(top);
        std::vector<double> values(count);
        for (std::size_t i = 0; i < count; ++i) values[i] = double(alphaCode(base, i)) / double(top);
        std::uint64_t passed = 0;
        forLookupPoints(base.width, base.height, values, [&](double v) { passed += v >= cutoff; });
        target_ = count ? double(passed) / double(lookupPoints(base.width, base.height)) : 0.0;
    }

    // The level after `previous` (the base first, then each level returned).
    TextureImage next(const TextureImage& previous) {
        if (alpha_.mode == AlphaUse::Mode::Blend) {
            std::vector<double> w(std::size_t(previous.width) * std::size_t(previous.height));
            for (std::size_t i = 0; i < w.size(); ++i) w[i] = channel(previous, i, 3);
            return halved(previous, coding_, &w);
        }
        if (alpha_.mode != AlphaUse::Mode::Mask || passCode_ > (previous.bits == 16 ? 65535u : 255u))
            return halved(previous, coding_);
        std::vector<double> coverage;
        TextureImage out = halved(previous, coding_, &coverage_, &coverage);
        coverage_ = std::move(coverage);
        if (!keepCoverage_) return out;
        // Alpha = coverage x s, quantised, s chosen so that the level's
        // bilinear lookups (forLookupPoints) pass as often as the base's.
        // Unclamped they are linear in s: s = cutoff / q, q their quantile
        // at the base's share (a histogram of 2^16 bins); alpha clamped at 1
        // passes less, so a few bisections above that start follow.
        const double top = previous.bits == 16 ? 65535.0 : 255.0;
        const double cutoff = double(passCode_) / top;
        const std::uint64_t points = lookupPoints(out.width, out.height);
        constexpr std::size_t kBins = 65536;
        std::vector<std::uint64_t> bins(kBins, 0);
        forLookupPoints(out.width, out.height, coverage_,
                        [&](double v) { ++bins[std::min(kBins - 1, static_cast<std::size_t>(v * double(kBins)))]; });
        const auto k = static_cast<std::uint64_t>(std::llround(target_ * double(points)));
        double q = 2.0;  // no lookup passes
        for (std::uint64_t above = 0, b = kBins; k > 0 && b-- > 0;)
            if ((above += bins[b]) >= k) {
                q = double(b) / double(kBins);
                break;
            }
        const auto code = [&](std::size_t i, double scale) {
            return static_cast<std::uint32_t>(std::lround(std::min(1.0, coverage_[i] * scale) * top));
        };
        double scale = q <= 0.0 ? 1.0e30 : cutoff / q;
        if (q > 0.0 && q <= 1.0) {
            std::vector<double> alpha(coverage_.size());
            const auto passing = [&](double sc) {
                for (std::size_t i = 0; i < alpha.size(); ++i) alpha[i] = double(code(i, sc)) / top;
                std::uint64_t n = 0;
                forLookupPoints(out.width, out.height, alpha, [&](double v) { n += v >= cutoff; });
                return n;
            };
            // Bisection until within a thousandth of the points (8 steps at most).
            double lo = scale, hi = 4.0 * scale, best = scale;
            std::uint64_t bestMiss = ~std::uint64_t(0);
            for (int step = 0; step < 8 && bestMiss > points / 1000; ++step) {
                const double mid = step == 0 ? lo : 0.5 * (lo + hi);
                const std::uint64_t n = passing(mid);
                const std::uint64_t miss = n > k ? n - k : k - n;
                if (miss < bestMiss) bestMiss = miss, best = mid;
                (n < k ? lo : hi) = mid;
            }
            scale = best;
        }
        for (std::size_t i = 0; i < coverage_.size(); ++i) setAlphaCode(out, i, code(i, scale));
        return out;
    }

private:
    TexelCoding coding_;
    AlphaUse alpha_;
    bool keepCoverage_;
    std::uint32_t passCode_ = 0;    // MASK: the first alpha code at or above the cutoff
    std::vector<double> coverage_;  // MASK: per texel of the last level, the share of base texels that pass
    double target_ = 0.0;           // MASK: the base's share
};

}  // namespace

TextureImage downsampledTexture(const TextureImage& image, std::uint32_t maxSize, TexelCoding coding, AlphaUse alpha) {
    Halver halver(image, coding, alpha, true);
    TextureImage out = halver.next(image);
    while (std::uint32_t(std::max(out.width, out.height)) > maxSize) out = halver.next(out);
    return out;
}

std::vector<TextureImage> textureMips(const TextureImage& image, TexelCoding coding, AlphaUse alpha) {
    std::vector<TextureImage> levels;
    Halver halver(image, coding, alpha, false);
    const TextureImage* last = &image;
    while (last->width > 1 || last->height > 1) {
        levels.push_back(halver.next(*last));
        last = &levels.back();
    }
    return levels;
}

glm::dvec3 meanColor(const TextureImage& image, bool srgb) {
    const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
    const std::array<double, 256>& decoded8 = decodedSrgb8();
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < count; ++i) {
        for (int c = 0; c < 3; ++c) {
            if (srgb && image.bits != 16) {
                sum[c] += decoded8[image.data[i * 4 + static_cast<std::size_t>(c)]];
                continue;
            }
            const double v = channel(image, i, c);
            sum[c] += srgb ? srgbToLinear(v) : v;
        }
    }
    return count ? sum / static_cast<double>(count) : sum;
}

}  // namespace strata
