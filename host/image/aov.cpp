#include "image/aov.h"

#include <cmath>

#include "image/image_io.h"
#include "util/error.h"

namespace strata {
namespace {

// Offsets of Film::aovSum's fields (Film::kAovSums per pixel).
enum : int { kHalfA = 0, kCountA = 3, kAlbedo = 4, kDepth = 7, kNormal = 8, kEmitter = 11,
             kAlbedoSq = 12, kDepthSq = 15, kNormalSq = 16 };

// The variance of a mean of n samples from their sum and sum of squares.
float varianceOfMean(double sum, double sumSq, double n) {
    if (n < 2) return 0.0f;
    const double m = sum / n, var = (sumSq - n * m * m) / (n - 1.0);
    return static_cast<float>(var > 0.0 ? var / n : 0.0);
}

}  // namespace

AovImages aovImages(const Film& film) {
    if (!film.aov) throw Error("strata: error: internal: the film has no AOV sums");
    const std::size_t n = film.pixels();
    AovImages a;
    a.width = film.width;
    a.height = film.height;
    a.color = film.mean();
    a.variance = film.varianceOfMean();
    for (auto* v : {&a.halfA, &a.halfB, &a.albedo, &a.normal, &a.albedoVariance, &a.normalVariance})
        v->assign(n * 3, 0.0f);
    for (auto* v : {&a.depth, &a.emitter, &a.depthVariance}) v->assign(n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        if (film.count[i] == 0) continue;
        double s[Film::kAovSums];
        for (int k = 0; k < Film::kAovSums; ++k) s[k] = film.aovAt(i, k);
        const double count = static_cast<double>(film.count[i]), countA = s[kCountA], countB = count - countA;
        for (int c = 0; c < 3; ++c) {
            if (countA > 0) a.halfA[i * 3 + c] = static_cast<float>(s[kHalfA + c] / countA);
            if (countB > 0)  // the fixed-point difference is exact
                a.halfB[i * 3 + c] = static_cast<float>(
                    fromFixed(film.sum[i * 3 + c] - film.aovSum[i * Film::kAovSums + kHalfA + c]) / countB);
            a.albedo[i * 3 + c] = static_cast<float>(s[kAlbedo + c] / count);
            a.normal[i * 3 + c] = static_cast<float>(s[kNormal + c] / count);
            a.albedoVariance[i * 3 + c] = varianceOfMean(s[kAlbedo + c], s[kAlbedoSq + c], count);
            a.normalVariance[i * 3 + c] = varianceOfMean(s[kNormal + c], s[kNormalSq + c], count);
        }
        a.depth[i] = static_cast<float>(s[kDepth] / count);
        a.emitter[i] = static_cast<float>(s[kEmitter] / count);
        a.depthVariance[i] = varianceOfMean(s[kDepth], s[kDepthSq], count);
    }
    return a;
}

ExtraChannels aovChannels(const AovImages& a) {
    ExtraChannels x;
    x.add("variance", "RGB", a.variance);
    x.add("halfA", "RGB", a.halfA);
    x.add("halfB", "RGB", a.halfB);
    x.add("albedo", "RGB", a.albedo);
    x.add("normal", "XYZ", a.normal);
    x.add("depth", "Z", a.depth);
    x.add("emitter", "A", a.emitter);
    if (!a.albedoVariance.empty()) x.add("albedoVariance", "RGB", a.albedoVariance);
    if (!a.normalVariance.empty()) x.add("normalVariance", "XYZ", a.normalVariance);
    if (!a.depthVariance.empty()) x.add("depthVariance", "Z", a.depthVariance);
    x.attributes = a.attributes;
    return x;
}

AovImages readAovImages(const std::string& path) {
    const Image img = readImage(path);
    const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
    // The layer's channels interleaved; empty when `optional` and absent.
    auto layer = [&](const std::string& name, const std::string& suffix, bool optional) {
        std::vector<int> cs;
        for (char s : suffix) {
            const std::string full = name.empty() ? std::string(1, s) : name + "." + s;
            const int c = img.channel(full);
            if (c < 0) {
                if (optional) return std::vector<float>{};
                throw Error(path + ": error: no " + (name.empty() ? "R, G, B" : name) + " layer (channel " + full +
                            " missing); strata denoise needs an EXR rendered with --aov");
            }
            cs.push_back(c);
        }
        std::vector<float> out(n * cs.size());
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t k = 0; k < cs.size(); ++k) {
                const float v = img.pixels[i * img.channels + cs[k]];
                if (!std::isfinite(v))
                    throw Error(path + ": error: channel " + img.channelNames[cs[k]] + " is " +
                                (std::isnan(v) ? "NaN" : "infinite") + " at pixel (" +
                                std::to_string(i % img.width) + ", " + std::to_string(i / img.width) + ")");
                out[i * cs.size() + k] = v;
            }
        return out;
    };
    AovImages a;
    a.width = img.width;
    a.height = img.height;
    a.attributes = img.attributes;
    // A denoised file (render --denoise) keeps the image as rendered in noisy.R/G/B.
    a.color = layer("noisy", "RGB", true);
    if (a.color.empty()) a.color = layer("", "RGB", false);
    a.variance = layer("variance", "RGB", false);
    a.halfA = layer("halfA", "RGB", false);
    a.halfB = layer("halfB", "RGB", false);
    a.albedo = layer("albedo", "RGB", false);
    a.normal = layer("normal", "XYZ", false);
    a.depth = layer("depth", "Z", false);
    a.emitter = layer("emitter", "A", false);
    a.albedoVariance = layer("albedoVariance", "RGB", true);
    a.normalVariance = layer("normalVariance", "XYZ", true);
    a.depthVariance = layer("depthVariance", "Z", true);
    return a;
}

}  // namespace strata
