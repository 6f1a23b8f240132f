#include "pack/textures.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>

#include "sheen_albedo.h"

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

// Appends the image's words (layout in types.h, TextureRef) to `texels`.
void appendWords(const TextureImage& image, std::vector<std::uint32_t>& texels) {
    const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
    if (image.bits == 16) {
        const std::size_t first = texels.size();
        texels.resize(first + 2 * count);
        for (std::size_t i = 0; i < count; ++i) {
            std::uint16_t c[4];
            std::memcpy(c, image.data.data() + i * 8, sizeof c);
            texels[first + 2 * i] = c[0] | static_cast<std::uint32_t>(c[1]) << 16;
            texels[first + 2 * i + 1] = c[2] | static_cast<std::uint32_t>(c[3]) << 16;
        }
        return;
    }
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* c = image.data.data() + i * 4;
        texels.push_back(c[0] | static_cast<std::uint32_t>(c[1]) << 8 |
                         static_cast<std::uint32_t>(c[2]) << 16 |
                         static_cast<std::uint32_t>(c[3]) << 24);
    }
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

std::uint32_t wrapBits(Wrap w) {
    switch (w) {
        case Wrap::ClampToEdge: return gpu::kWrapClamp;
        case Wrap::MirroredRepeat: return gpu::kWrapMirror;
        case Wrap::Repeat: break;
    }
    return gpu::kWrapRepeat;
}

}  // namespace

TextureImage downsampledTexture(const TextureImage& image, std::uint32_t maxSize, TexelCoding coding, AlphaUse alpha) {
    Halver halver(image, coding, alpha, true);
    TextureImage out = halver.next(image);
    while (std::uint32_t(std::max(out.width, out.height)) > maxSize) out = halver.next(out);
    return out;
}

namespace {

// Bytes of an image of w x h texels (`bits` per channel) and, with `mips`, its chain.
std::uint64_t packedBytes(std::uint64_t w, std::uint64_t h, int bits, bool mips) {
    const std::uint64_t texel = bits == 16 ? 8 : 4;
    std::uint64_t bytes = w * h * texel;
    while (mips && (w > 1 || h > 1)) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        bytes += w * h * texel;
    }
    return bytes;
}

}  // namespace

std::vector<std::size_t> shrinkTextures(std::vector<std::uint32_t>& texels, std::vector<gpu::TextureRef>& refs,
                                        std::vector<PackedImage>& images, std::uint64_t maxBytes) {
    std::vector<std::size_t> halvedImages;
    if (images.empty() || texels.size() * sizeof(std::uint32_t) <= maxBytes) return halvedImages;
    // Each image's first level as an image (the words are the texels' bytes, little-endian).
    std::vector<TextureImage> unpacked(images.size());
    std::uint64_t first = texels.size();
    for (std::size_t i = 0; i < images.size(); ++i) {
        const PackedImage& p = images[i];
        TextureImage& im = unpacked[i];
        im.width = p.width;
        im.height = p.height;
        im.bits = p.bits;
        im.data.resize(packedBytes(std::uint64_t(p.width), std::uint64_t(p.height), p.bits, false));
        std::memcpy(im.data.data(), texels.data() + p.offset, im.data.size());
        first = std::min(first, p.offset);
    }
    std::uint64_t bytes = texels.size() * sizeof(std::uint32_t);
    std::vector<char> halvedOnce(images.size(), 0);
    while (bytes > maxBytes) {
        std::size_t largest = images.size();
        for (std::size_t i = 0; i < images.size(); ++i)
            if (unpacked[i].width * unpacked[i].height > 1 &&
                (largest == images.size() || unpacked[i].data.size() > unpacked[largest].data.size()))
                largest = i;
        if (largest == images.size()) break;  // every image 1x1
        TextureImage& im = unpacked[largest];
        const bool mips = images[largest].levels > 1;
        const std::uint64_t before = packedBytes(std::uint64_t(im.width), std::uint64_t(im.height), im.bits, mips);
        im = Halver(im, images[largest].coding, images[largest].alpha, true).next(im);
        bytes -= before - packedBytes(std::uint64_t(im.width), std::uint64_t(im.height), im.bits, mips);
        if (!halvedOnce[largest]) halvedOnce[largest] = 1, halvedImages.push_back(largest);
    }
    // The words again: what precedes the images (the sheen table), then each
    // image with its chain built again where it had one.
    std::vector<std::uint32_t> out(texels.begin(), texels.begin() + std::ptrdiff_t(first));
    std::vector<std::uint64_t> oldOffset(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        PackedImage& p = images[i];
        oldOffset[i] = p.offset;
        p.offset = out.size();
        p.width = unpacked[i].width;
        p.height = unpacked[i].height;
        appendWords(unpacked[i], out);
        if (p.levels > 1) {
            const std::vector<TextureImage> chain = textureMips(unpacked[i], p.coding, p.alpha);
            for (const TextureImage& level : chain) appendWords(level, out);
            p.levels = 1 + static_cast<int>(chain.size());
        }
        p.bytes = (out.size() - p.offset) * sizeof(std::uint32_t);
    }
    const std::uint32_t levelBits = ~std::uint32_t(0) << gpu::kTexLevelsShift;
    for (gpu::TextureRef& r : refs)
        for (std::size_t i = 0; i < images.size(); ++i)
            if (r.offset == oldOffset[i]) {
                r.offset = static_cast<std::uint32_t>(images[i].offset);
                r.width = static_cast<std::uint32_t>(images[i].width);
                r.height = static_cast<std::uint32_t>(images[i].height);
                r.flags &= ~levelBits;
                if (images[i].levels > 1) r.flags |= static_cast<std::uint32_t>(images[i].levels) << gpu::kTexLevelsShift;
                break;
            }
    texels = std::move(out);
    return halvedImages;
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

void transformRows(const TextureTransform& t, glm::vec4& row0, glm::vec4& row1) {
    // KHR_texture_transform: M = T(offset) R(rotation) S(scale), R with
    // columns (cos, -sin), (sin, cos) as the ratified extension writes it.
    const double c = std::cos(static_cast<double>(t.rotation));
    const double s = std::sin(static_cast<double>(t.rotation));
    row0 = glm::vec4(static_cast<float>(c * t.scale.x), static_cast<float>(s * t.scale.y), t.offset.x, 0.0f);
    row1 = glm::vec4(static_cast<float>(-s * t.scale.x), static_cast<float>(c * t.scale.y), t.offset.y, 0.0f);
}

std::vector<std::uint32_t> sheenAlbedoWords() {
    std::vector<std::uint32_t> words;
    for (const float e : kSheenAlbedo) words.push_back(std::bit_cast<std::uint32_t>(e));
    return words;
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

namespace {

// The words of one packed image: downsampled to `maxSize` (0: whole), then
// with its mip chain where `mips`.
std::vector<std::uint32_t> imageWords(const TextureImage& image, TexelCoding coding, std::uint32_t maxSize, bool mips,
                                      PackedImage& p) {
    std::vector<std::uint32_t> words;
    TextureImage small;
    const TextureImage* base = &image;
    if (maxSize > 0 && std::uint32_t(std::max(image.width, image.height)) > maxSize) {
        small = downsampledTexture(image, maxSize, coding, p.alpha);
        base = &small;
    }
    p.width = base->width;
    p.height = base->height;
    appendWords(*base, words);
    p.levels = 1;
    if (mips) {
        std::vector<TextureImage> chain = textureMips(*base, coding, p.alpha);
        for (const TextureImage& level : chain) appendWords(level, words);
        p.levels += static_cast<int>(chain.size());
    }
    return words;
}

// Runs job(i) for i in [0, n) on up to the machine's threads; the first
// exception a job throws (std::bad_alloc) is thrown again here.
template <class Job>
void parallelFor(std::size_t n, Job job) {
    const std::size_t threads = std::min<std::size_t>(n, std::max(1u, std::thread::hardware_concurrency()));
    if (threads <= 1) {
        for (std::size_t i = 0; i < n; ++i) job(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failed;
    std::mutex failedMutex;
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            try {
                for (std::size_t i = next++; i < n; i = next++) job(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(failedMutex);
                if (!failed) failed = std::current_exception();
                next = n;  // the others stop after their current job
            }
        });
    for (std::thread& t : pool) t.join();
    if (failed) std::rethrow_exception(failed);
}

}  // namespace

PackedTextures packTextures(const Scene& scene, const std::vector<bool>& used,
                            std::vector<gpu::Material>& materials, std::uint32_t maxSize, bool mips) {
    PackedTextures out;
    // KHR_materials_sheen's albedo table first (lib/sheen.glsl reads it there).
    bool sheen = false;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) sheen = sheen || (used[i] && scene.materials[i].sheened());
    if (sheen) out.texels = sheenAlbedoWords();
    // Each image once, in the order slots first read it, as that slot reads
    // it; the refs hold its index in out.images until the words are laid out.
    std::vector<std::int64_t> packedIndex(scene.images.size(), -1);  // into out.images
    std::vector<std::size_t> sourceImage;                           // out.images -> scene.images
    auto addRef = [&](const MaterialDesc& m, const TextureSlot& slot, TexelCoding coding) -> std::uint32_t {
        if (!slot.used()) return gpu::kNoTexture;
        const bool srgb = coding == TexelCoding::Srgb;
        const Texture& texture = scene.textures[static_cast<std::size_t>(slot.texture)];
        const TextureImage& image = scene.images[static_cast<std::size_t>(texture.image)];
        std::int64_t& index = packedIndex[static_cast<std::size_t>(texture.image)];
        if (index < 0) {
            index = static_cast<std::int64_t>(out.images.size());
            const std::string name = image.name.empty() ? "image " + std::to_string(texture.image) : image.name;
            out.images.push_back({name, image.width, image.height, image.width, image.height, 0, 0, image.bits, coding});
            sourceImage.push_back(static_cast<std::size_t>(texture.image));
        }
        gpu::TextureRef ref{};
        ref.offset = static_cast<std::uint32_t>(index);  // laid out below
        ref.flags = wrapBits(texture.wrapS) | wrapBits(texture.wrapT) << 2;
        if (texture.nearest) ref.flags |= gpu::kTexNearest;
        if (m.uvSlot(slot.texCoord) == 1) ref.flags |= gpu::kTexCoord1;
        if (image.bits == 16) ref.flags |= gpu::kTex16Bit;
        if (srgb) ref.flags |= gpu::kTexSrgb;
        transformRows(slot.transform, ref.row0, ref.row1);
        out.refs.push_back(ref);
        return static_cast<std::uint32_t>(out.refs.size() - 1);
    };
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const MaterialDesc& m = scene.materials[i];
        gpu::Material& g = materials[i];
        g.baseColorTex = addRef(m, m.baseColorTexture, TexelCoding::Srgb);
        g.metallicRoughnessTex = addRef(m, m.metallicRoughnessTexture, TexelCoding::Linear);
        g.normalTex = addRef(m, m.normalTexture, TexelCoding::Normal);
        g.emissiveTex = addRef(m, m.emissiveTexture, TexelCoding::Srgb);
        g.transmissionTex = addRef(m, m.transmissionTexture, TexelCoding::Linear);
        g.clearcoatTex = g.clearcoatRoughnessTex = g.clearcoatNormalTex = gpu::kNoTexture;
        if (m.coated()) {
            g.clearcoatTex = addRef(m, m.clearcoatTexture, TexelCoding::Linear);
            g.clearcoatRoughnessTex = addRef(m, m.clearcoatRoughnessTexture, TexelCoding::Linear);
            g.clearcoatNormalTex = addRef(m, m.clearcoatNormalTexture, TexelCoding::Normal);
        }
        g.specularTex = g.specularColorTex = gpu::kNoTexture;
        if (m.tinted()) {
            g.specularTex = addRef(m, m.specularTexture, TexelCoding::Linear);
            g.specularColorTex = addRef(m, m.specularColorTexture, TexelCoding::Srgb);
        }
        g.sheenColorTex = g.sheenRoughnessTex = gpu::kNoTexture;
        if (m.sheened()) {
            g.sheenColorTex = addRef(m, m.sheenColorTexture, TexelCoding::Srgb);
            g.sheenRoughnessTex = addRef(m, m.sheenRoughnessTexture, TexelCoding::Linear);
        }
        g.iridescenceTex = g.iridescenceThicknessTex = gpu::kNoTexture;
        if (m.iridescent()) {
            g.iridescenceTex = addRef(m, m.iridescenceTexture, TexelCoding::Linear);
            g.iridescenceThicknessTex = addRef(m, m.iridescenceThicknessTexture, TexelCoding::Linear);
        }
        g.diffuseTransmissionTex = g.diffuseTransmissionColorTex = gpu::kNoTexture;
        if (m.diffuselyTransmitting()) {
            g.diffuseTransmissionTex = addRef(m, m.diffuseTransmissionTexture, TexelCoding::Linear);
            g.diffuseTransmissionColorTex = addRef(m, m.diffuseTransmissionColorTexture, TexelCoding::Srgb);
        }
        g.anisotropyTex = m.anisotropic() ? addRef(m, m.anisotropyTexture, TexelCoding::Linear) : gpu::kNoTexture;
    }
    // How the used materials' alpha reads each image as base colour: one
    // MASK cutoff (with its factor) or BLEND; OPAQUE reads no alpha, and an
    // image read two other ways keeps plain means.
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const MaterialDesc& m = scene.materials[i];
        if (!used[i] || !m.baseColorTexture.used() || m.alphaMode == MaterialDesc::AlphaMode::Opaque) continue;
        const int image = scene.textures[static_cast<std::size_t>(m.baseColorTexture.texture)].image;
        PackedImage& p = out.images[static_cast<std::size_t>(packedIndex[static_cast<std::size_t>(image)])];
        AlphaUse use;
        use.mode = m.alphaMode == MaterialDesc::AlphaMode::Mask ? AlphaUse::Mode::Mask : AlphaUse::Mode::Blend;
        if (use.mode == AlphaUse::Mode::Mask) use.cutoff = m.alphaCutoff, use.factor = m.baseColor.a;
        if (!p.alphaSeen) p.alpha = use, p.alphaSeen = true;
        else if (p.alpha.mode != use.mode || p.alpha.cutoff != use.cutoff || p.alpha.factor != use.factor) p.alpha = {};
    }
    // The images' words, built in parallel, then laid out in order.
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::vector<std::uint32_t>> words(out.images.size());
    parallelFor(out.images.size(), [&](std::size_t i) {
        words[i] = imageWords(scene.images[sourceImage[i]], out.images[i].coding, maxSize, mips, out.images[i]);
    });
    std::size_t total = out.texels.size();
    for (const auto& w : words) total += w.size();
    out.texels.reserve(total);
    for (std::size_t i = 0; i < out.images.size(); ++i) {
        out.images[i].offset = out.texels.size();
        out.images[i].bytes = words[i].size() * sizeof(std::uint32_t);
        out.texels.insert(out.texels.end(), words[i].begin(), words[i].end());
        std::vector<std::uint32_t>().swap(words[i]);
    }
    for (gpu::TextureRef& r : out.refs) {
        const PackedImage& p = out.images[r.offset];
        r.offset = static_cast<std::uint32_t>(p.offset);
        r.width = static_cast<std::uint32_t>(p.width);
        r.height = static_cast<std::uint32_t>(p.height);
        if (p.levels > 1) r.flags |= static_cast<std::uint32_t>(p.levels) << gpu::kTexLevelsShift;
    }
    if (mips) out.mipMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace strata
