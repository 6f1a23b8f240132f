#include "denoise/denoise.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <span>
#include <string>

#include "spirv/cache.h"

#include "../../shaders/shared/denoise.h"
#include "util/error.h"
#include "vk/buffer.h"
#include "vk/kernel.h"
#include "vk/timer.h"

namespace strata {
namespace {

using Clock = std::chrono::steady_clock;
using Spirv = std::span<const std::uint32_t>;
Spirv denoiseModule(spirv::KernelId id) { return spirv::moduleFor({id, 0}); }

// Below this albedo a channel is not demodulated (its factor is 1).
constexpr float kDarkAlbedo = 0.01f;
// NFOR: the regression window's radius, the two NL-means bandwidths k, the
// ridge on the feature terms (relative to the weight sum) and the radius of
// the box over which the selection averages each candidate's error.
constexpr int kNforRadius = 4;
constexpr float kNforK1 = 0.5f, kNforK2 = 1.0f;
constexpr float kNforRidge = 1e-3f;
constexpr int kSelectRadius = 1;
// The feature prefilter's window radius and 1 / k^2.
constexpr int kFeatureRadius = 3;
constexpr float kFeatureInvK2 = 1.0f;
// Fast: a-trous iterations (steps 1, 2, 4, ...) and the luminance edge-stop scale.
constexpr int kAtrousIterations = 5;
constexpr float kAtrousSigmaLum = 4.0f;

using Rgba = std::vector<float>;  // 4 floats per pixel

void checkLayer(const std::vector<float>& v, const char* name, const DenoiseInput& in, int channels, bool optional) {
    if (optional && v.empty()) return;
    const std::size_t want = std::size_t(in.width) * std::size_t(in.height) * std::size_t(channels);
    if (v.size() != want)
        throw Error("strata: error: denoise: layer '" + std::string(name) + "' has " + std::to_string(v.size()) +
                    " floats, expected " + std::to_string(want) + " (" + std::to_string(channels) + " per pixel, " +
                    std::to_string(in.width) + "x" + std::to_string(in.height) + ")");
}

void checkInput(const DenoiseInput& in) {
    if (in.width <= 0 || in.height <= 0)
        throw Error("strata: error: denoise: image size " + std::to_string(in.width) + "x" +
                    std::to_string(in.height) + " is empty");
    checkLayer(in.color, "color", in, 3, false);
    checkLayer(in.halfA, "halfA", in, 3, false);
    checkLayer(in.halfB, "halfB", in, 3, false);
    checkLayer(in.variance, "variance", in, 3, false);
    checkLayer(in.albedo, "albedo", in, 3, false);
    checkLayer(in.normal, "normal", in, 3, false);
    checkLayer(in.depth, "depth", in, 1, false);
    checkLayer(in.emitter, "emitter", in, 1, false);
    checkLayer(in.albedoVariance, "albedoVariance", in, 3, true);
    checkLayer(in.normalVariance, "normalVariance", in, 3, true);
    checkLayer(in.depthVariance, "depthVariance", in, 1, true);
}

float finiteOr(float v, float fallback) { return std::isfinite(v) ? v : fallback; }

// The weighted mean of each pixel's 3x3 neighbourhood (inside the image),
// all four channels; a pixel whose neighbourhood weighs nothing keeps its value.
Rgba box3(const Rgba& img, const std::vector<float>& weight, int w, int h) {
    Rgba out(img.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            float sum[4] = {0, 0, 0, 0}, sumW = 0.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    if (x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
                    const std::size_t q = std::size_t(y + dy) * w + (x + dx);
                    for (int c = 0; c < 4; ++c) sum[c] += weight[q] * img[4 * q + c];
                    sumW += weight[q];
                }
            for (int c = 0; c < 4; ++c) out[4 * i + c] = sumW > 0.0f ? sum[c] / sumW : img[4 * i + c];
        }
    return out;
}

// The host's share: per-pixel demodulation factors and the packed RGBA
// layers the kernels read.
struct Prepared {
    std::vector<float> factor;  // 3/pixel: the albedo, or 1 where it is dark
    // 1/pixel: 1 where the pixel may be a neighbour in a filter: no sample saw
    // an emitter or the background directly, every colour value is finite.
    std::vector<float> neighbour;
    Rgba features;              // normal xyz, depth / the largest depth
    Rgba featureVar;            // their variances (empty: no prefilter)
};

Prepared prepare(const DenoiseInput& in) {
    const std::size_t n = std::size_t(in.width) * in.height;
    Prepared p;
    p.factor.resize(3 * n);
    for (std::size_t i = 0; i < 3 * n; ++i) {
        const float a = finiteOr(in.albedo[i], 0.0f);
        p.factor[i] = a >= kDarkAlbedo ? a : 1.0f;
    }
    p.neighbour.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        bool ok = in.emitter[i] == 0.0f;
        for (int c = 0; c < 3; ++c)
            ok = ok && std::isfinite(in.color[3 * i + c]) && std::isfinite(in.halfA[3 * i + c]) &&
                 std::isfinite(in.halfB[3 * i + c]) && std::isfinite(in.variance[3 * i + c]);
        p.neighbour[i] = ok ? 1.0f : 0.0f;
    }
    float maxDepth = 0.0f;
    for (float d : in.depth) maxDepth = std::max(maxDepth, finiteOr(d, 0.0f));
    const float depthScale = maxDepth > 0.0f ? 1.0f / maxDepth : 1.0f;
    p.features.resize(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) p.features[4 * i + c] = finiteOr(in.normal[3 * i + c], 0.0f);
        p.features[4 * i + 3] = finiteOr(in.depth[i], 0.0f) * depthScale;
    }
    if (!in.normalVariance.empty() && !in.depthVariance.empty()) {
        p.featureVar.resize(4 * n);
        for (std::size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) p.featureVar[4 * i + c] = std::max(finiteOr(in.normalVariance[3 * i + c], 0.0f), 0.0f);
            p.featureVar[4 * i + 3] = std::max(finiteOr(in.depthVariance[i], 0.0f), 0.0f) * depthScale * depthScale;
        }
    }
    return p;
}

// A device image of RGBA32F texels: read through its texel view, written as vec4[].
struct Image {
    vk::Buffer buffer;
    vk::TexelView view;
};

constexpr VkBufferUsageFlags kImageUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                           VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT;

Image upload(const vk::Context& ctx, const Rgba& rgba) {
    Image img;
    img.buffer = vk::uploadBuffer(ctx, std::as_bytes(std::span<const float>(rgba)), kImageUsage);
    img.view = vk::TexelView(ctx, img.buffer, VK_FORMAT_R32G32B32A32_SFLOAT, rgba.size() * sizeof(float));
    return img;
}

Image blank(const vk::Context& ctx, std::size_t pixels) {
    Image img;
    img.buffer = vk::Buffer(ctx, pixels * 16, kImageUsage, vk::MemoryUse::Device);
    img.view = vk::TexelView(ctx, img.buffer, VK_FORMAT_R32G32B32A32_SFLOAT, pixels * 16);
    return img;
}

// The kernels of one denoise() call, each with its own descriptor set; the
// compiled programs are shared between calls (Kernel reuse).
class Passes {
public:
    Passes(const vk::Context& ctx, const DenoiseInput& in) : ctx_(ctx), w_(in.width), h_(in.height) {}

    // A kernel reading `inputs` through texel views and writing `outputs`.
    vk::Kernel& add(Spirv spirv, std::initializer_list<const Image*> inputs,
                    std::initializer_list<const Image*> outputs) {
        const auto t0 = Clock::now();
        std::vector<vk::BindingDesc> bindings;
        for (std::uint32_t i = 0; i < inputs.size(); ++i)
            bindings.push_back({gpu::DN_IN0 + i, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER});
        for (std::uint32_t i = 0; i < outputs.size(); ++i)
            bindings.push_back({gpu::DN_OUT0 + i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
        kernels_.push_back(std::make_unique<vk::Kernel>(ctx_, spirv, bindings, sizeof(gpu::DenoiseParams),
                                                        std::vector<std::uint32_t>{}, true));
        vk::Kernel& k = *kernels_.back();
        std::uint32_t i = 0;
        for (const Image* img : inputs) k.bind(gpu::DN_IN0 + i++, img->view);
        i = 0;
        for (const Image* img : outputs) k.bind(gpu::DN_OUT0 + i++, img->buffer);
        if (!k.reusedProgram()) {
            // lavapipe compiles a kernel's machine code at its first
            // dispatch: one of no pixels here counts that as pipeline time.
            gpu::DenoiseParams none{};
            vk::OneShot shot(ctx_);
            k.dispatch(shot.begin(), &none, 1, 1);
            shot.submitAndWait();
        }
        const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        pipelineMs_ += k.reusedProgram() ? 0.0 : 1e3 * seconds;
        setupSeconds_ += seconds;
        return k;
    }

    gpu::DenoiseParams params() const {
        gpu::DenoiseParams p{};
        p.width = std::uint32_t(w_);
        p.height = std::uint32_t(h_);
        return p;
    }

    void dispatch(VkCommandBuffer cmd, const vk::Kernel& k, const gpu::DenoiseParams& p) const {
        const std::uint32_t g = gpu::kDenoiseGroup;
        k.dispatch(cmd, &p, (std::uint32_t(w_) + g - 1) / g, (std::uint32_t(h_) + g - 1) / g);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    }

    double pipelineMs() const { return pipelineMs_; }
    double setupSeconds() const { return setupSeconds_; }

private:
    const vk::Context& ctx_;
    int w_, h_;
    std::vector<std::unique_ptr<vk::Kernel>> kernels_;
    double pipelineMs_ = 0.0;
    double setupSeconds_ = 0.0;
};

// Runs the recorded passes and reads `result` back as 4 floats per pixel.
struct Run {
    Rgba rgba;
    double deviceSeconds = 0.0;
};

template <class Record>
Run submit(const vk::Context& ctx, const Image& result, std::size_t pixels, Record&& record) {
    vk::Buffer back(ctx, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    vk::OneShot shot(ctx);
    vk::DeviceTimer timer(ctx);
    VkCommandBuffer cmd = shot.begin();
    timer.begin(cmd);
    record(cmd);
    timer.end(cmd);
    vk::recordReadback(cmd, result.buffer, back, pixels * 16);
    shot.submitAndWait();
    back.invalidate();
    Run run;
    run.rgba.resize(pixels * 4);
    std::memcpy(run.rgba.data(), back.mapped(), pixels * 16);
    run.deviceSeconds = timer.supported() ? timer.seconds() : -1.0;
    return run;
}

struct Denoised {
    Rgba demodulated;  // rgb of the denoised demodulated colour, 4 floats per pixel
    double deviceSeconds = 0.0;
};

// Both halves demodulated, as the selection (denoise_select) and the
// filters read them: a's .a the pixel's weight as a neighbour, b's .a the
// variance of a half's mean (twice the mean's, channels averaged), as a 3x3
// mean over the neighbour pixels.
struct Halves {
    Rgba a, b;
};

Halves demodulatedHalves(const DenoiseInput& in, const Prepared& prep) {
    const std::size_t n = std::size_t(in.width) * in.height;
    Halves h{Rgba(4 * n), Rgba(4 * n)};
    Rgba varHalf(4 * n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        float v = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float f = prep.factor[3 * i + c];
            h.a[4 * i + c] = finiteOr(in.halfA[3 * i + c], 0.0f) / f;
            h.b[4 * i + c] = finiteOr(in.halfB[3 * i + c], 0.0f) / f;
            v += 2.0f * std::max(finiteOr(in.variance[3 * i + c], 0.0f), 0.0f) / (f * f);
        }
        varHalf[4 * i] = v * (1.0f / 3.0f);
        h.a[4 * i + 3] = prep.neighbour[i];
    }
    const Rgba varSmooth = box3(varHalf, prep.neighbour, in.width, in.height);
    for (std::size_t i = 0; i < n; ++i) h.b[4 * i + 3] = varSmooth[4 * i];
    return h;
}

Denoised runNfor(const vk::Context& ctx, Passes& passes, const DenoiseInput& in, const Prepared& prep) {
    const std::size_t n = std::size_t(in.width) * in.height;
    const Halves h = demodulatedHalves(in, prep);
    // The guides: 3x3 means over the pixels that may be neighbours, .a the variance of that mean.
    Rgba guideA = box3(h.a, prep.neighbour, in.width, in.height), guideB = box3(h.b, prep.neighbour, in.width, in.height);
    for (std::size_t i = 0; i < n; ++i) guideA[4 * i + 3] = guideB[4 * i + 3] = h.b[4 * i + 3] * (1.0f / 9.0f);
    const Image gA = upload(ctx, guideA), gB = upload(ctx, guideB), cA = upload(ctx, h.a), cB = upload(ctx, h.b);
    const Image feat = upload(ctx, prep.features);
    Image featVar, featOut;
    const bool prefilter = !prep.featureVar.empty();
    if (prefilter) {
        featVar = upload(ctx, prep.featureVar);
        featOut = blank(ctx, n);
    }
    const Image& features = prefilter ? featOut : feat;
    Image fA1 = blank(ctx, n), fB1 = blank(ctx, n), fA2 = blank(ctx, n), fB2 = blank(ctx, n), out = blank(ctx, n);

    vk::Kernel* pre = prefilter ? &passes.add(denoiseModule(spirv::KernelId::DenoiseFeatures), {&feat, &featVar}, {&featOut})
                                : nullptr;
    vk::Kernel& nfor = passes.add(denoiseModule(spirv::KernelId::DenoiseNfor), {&gA, &gB, &cA, &cB, &features},
                                  {&fA1, &fB1, &fA2, &fB2});
    vk::Kernel& select = passes.add(denoiseModule(spirv::KernelId::DenoiseSelect), {&fA1, &fB1, &fA2, &fB2, &cA, &cB}, {&out});
    const Run run = submit(ctx, out, n, [&](VkCommandBuffer cmd) {
        if (pre) {
            gpu::DenoiseParams p = passes.params();
            p.radius = kFeatureRadius;
            p.sigma = kFeatureInvK2;
            passes.dispatch(cmd, *pre, p);
        }
        gpu::DenoiseParams p = passes.params();
        p.radius = kNforRadius;
        p.invK1 = 1.0f / (kNforK1 * kNforK1);
        p.invK2 = 1.0f / (kNforK2 * kNforK2);
        p.ridge = kNforRidge;
        passes.dispatch(cmd, nfor, p);
        p.radius = kSelectRadius;
        passes.dispatch(cmd, select, p);
    });
    return {run.rgba, run.deviceSeconds};
}

// Fast: the a-trous filter run on each half apart, and NFOR's selection
// (denoise_select) between the filtered halves' average and the unfiltered
// mean by the error the cross-half differences estimate, so that where the
// filter's bias exceeds the noise it removes (fine gradients at high spp)
// the pixel keeps its own colour.
Denoised runFast(const vk::Context& ctx, Passes& passes, const DenoiseInput& in, const Prepared& prep) {
    const std::size_t n = std::size_t(in.width) * in.height;
    constexpr float kLum[3] = {0.2126f, 0.7152f, 0.0722f};
    const Halves h = demodulatedHalves(in, prep);
    // The filters' input: each half, .a the variance of its luminance (twice the mean's).
    Rgba half[2] = {h.a, h.b};
    for (std::size_t i = 0; i < n; ++i) {
        float lum = 0.0f;
        for (int k = 0; k < 3; ++k) {
            const float f = prep.factor[3 * i + k];
            lum += kLum[k] * kLum[k] * (2.0f * std::max(finiteOr(in.variance[3 * i + k], 0.0f), 0.0f) / (f * f));
        }
        half[0][4 * i + 3] = half[1][4 * i + 3] = lum;
    }
    Rgba aux(4 * n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) aux[4 * i] = prep.neighbour[i];
    const Image feat = upload(ctx, prep.features), neighbour = upload(ctx, aux);
    const Image cA = upload(ctx, h.a), cB = upload(ctx, h.b);
    Image ping[2] = {upload(ctx, half[0]), upload(ctx, half[1])}, pong[2] = {blank(ctx, n), blank(ctx, n)};
    std::vector<vk::Kernel*> steps[2];
    for (int h = 0; h < 2; ++h)
        for (int it = 0; it < kAtrousIterations; ++it) {
            const Image& src = it % 2 == 0 ? ping[h] : pong[h];
            const Image& dst = it % 2 == 0 ? pong[h] : ping[h];
            steps[h].push_back(&passes.add(denoiseModule(spirv::KernelId::DenoiseAtrous), {&src, &feat, &neighbour}, {&dst}));
        }
    const Image& fA = kAtrousIterations % 2 == 1 ? pong[0] : ping[0];
    const Image& fB = kAtrousIterations % 2 == 1 ? pong[1] : ping[1];
    const Image out = blank(ctx, n);
    vk::Kernel& select = passes.add(denoiseModule(spirv::KernelId::DenoiseSelect), {&fA, &fB, &fA, &fB, &cA, &cB}, {&out});
    const Run run = submit(ctx, out, n, [&](VkCommandBuffer cmd) {
        for (int h = 0; h < 2; ++h)
            for (int it = 0; it < kAtrousIterations; ++it) {
                gpu::DenoiseParams p = passes.params();
                p.step = 1u << it;
                p.sigma = kAtrousSigmaLum;
                passes.dispatch(cmd, *steps[h][std::size_t(it)], p);
            }
        gpu::DenoiseParams p = passes.params();
        p.radius = kSelectRadius;
        passes.dispatch(cmd, select, p);
    });
    return {run.rgba, run.deviceSeconds};
}

}  // namespace

DenoiseResult denoise(const vk::Context& ctx, const DenoiseInput& in, DenoiseMethod method) {
    checkInput(in);
    const auto t0 = Clock::now();
    const std::size_t n = std::size_t(in.width) * in.height;
    const Prepared prep = prepare(in);
    Passes passes(ctx, in);
    const Denoised d = method == DenoiseMethod::Nfor ? runNfor(ctx, passes, in, prep) : runFast(ctx, passes, in, prep);
    DenoiseResult r;
    r.rgb.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        // A pixel where some sample saw an emitter or the background is not
        // filtered: its denoised value is its colour, so out = e * color +
        // (1 - e) * denoised = color. (Its colour is e Le + (1 - e) S with Le
        // that radiance; the filter estimates S alone, from the neighbours,
        // and e * color + (1 - e) * S would lose (1 - e) e Le.)
        const float e = finiteOr(in.emitter[i], 1.0f);
        for (int c = 0; c < 3; ++c) {
            const float color = in.color[3 * i + c];
            const float den = d.demodulated[4 * i + c] * prep.factor[3 * i + c];
            r.rgb[3 * i + c] = e > 0.0f ? color : den;
        }
    }
    r.pipelineMs = passes.pipelineMs();
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count() - passes.setupSeconds();
    r.deviceSeconds = d.deviceSeconds >= 0.0 ? d.deviceSeconds : r.seconds;
    return r;
}

}  // namespace strata
