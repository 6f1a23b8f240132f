// The denoiser (host/denoise) on a synthetic image with a known answer:
// two regions of different albedo, normal, depth and irradiance, a smooth
// irradiance gradient, Gaussian noise of known variance in two independent
// halves, one emitter pixel.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "denoise/denoise.h"
#include "test_util.h"
#include "util/error.h"
#include "vk/context.h"

using namespace strata;

namespace {

constexpr int kSize = 64;
constexpr int kEdge = 32;      // columns [0, kEdge) are the left region
constexpr float kSigma = 0.12f;  // standard deviation of the full mean, per channel
constexpr int kSamples = 16;   // the variance layer is estimated from this many samples

struct Synthetic {
    DenoiseInput in;
    std::vector<float> clean;  // 3/pixel
};

bool leftRegion(int x) { return x < kEdge; }

Synthetic synthetic(bool featureVariance = false) {
    Synthetic s;
    DenoiseInput& in = s.in;
    in.width = in.height = kSize;
    const std::size_t n = std::size_t(kSize) * kSize;
    for (auto* v : {&in.color, &in.halfA, &in.halfB, &in.variance, &in.albedo, &in.normal, &s.clean})
        v->resize(3 * n);
    in.depth.resize(n);
    in.emitter.assign(n, 0.0f);
    std::mt19937 rng(12345);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    std::chi_squared_distribution<float> chi(float(kSamples - 1));
    const float halfSigma = kSigma * std::sqrt(2.0f);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = std::size_t(y) * kSize + x;
            const bool left = leftRegion(x);
            const float irradiance = (left ? 1.0f : 0.6f) * (0.5f + 1.5f * float(x + y) / float(2 * kSize));
            const float albedo[3] = {left ? 0.8f : 0.2f, left ? 0.2f : 0.6f, left ? 0.2f : 0.8f};
            const float normal[3] = {left ? 0.0f : 0.6f, 0.0f, 0.8f};
            in.depth[i] = left ? 5.0f : 6.0f + 0.01f * float(y);
            for (int c = 0; c < 3; ++c) {
                const float v = albedo[c] * irradiance;
                s.clean[3 * i + c] = v;
                in.albedo[3 * i + c] = albedo[c];
                in.normal[3 * i + c] = normal[c];
                in.halfA[3 * i + c] = v + halfSigma * gauss(rng);
                in.halfB[3 * i + c] = v + halfSigma * gauss(rng);
                in.color[3 * i + c] = 0.5f * (in.halfA[3 * i + c] + in.halfB[3 * i + c]);
                in.variance[3 * i + c] = kSigma * kSigma * chi(rng) / float(kSamples - 1);
            }
        }
    if (featureVariance) {
        in.albedoVariance.assign(3 * n, 1e-6f);
        in.normalVariance.assign(3 * n, 1e-6f);
        in.depthVariance.assign(n, 1e-6f);
    }
    return s;
}

double mse(const std::vector<float>& a, const std::vector<float>& b) {
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += double(a[i] - b[i]) * double(a[i] - b[i]);
    return s / double(a.size());
}

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("denoise: both methods reduce the error of a noisy synthetic image, and keep its albedo edge") {
    // The least each method divides the mean squared error by, and the
    // largest mean error of a column beside the edge (the a-trous filter
    // fits a constant, so the irradiance gradient biases it where its
    // window is one-sided; a blurred edge would be off by about 0.3). NFOR
    // measured 0.031 with its 9x9 window (under 0.02 with 15x15, which did worse
    // on the rendered scenes at 1024 spp: docs/experiments/denoiser.md).
    struct Case {
        DenoiseMethod method;
        bool featureVariance;
        double factor;
        double edgeBias;
    };
    for (const Case& c : {Case{DenoiseMethod::Nfor, false, 20.0, 0.05}, Case{DenoiseMethod::Nfor, true, 20.0, 0.05},
                          Case{DenoiseMethod::Fast, false, 1.5, 0.1}}) {
        CAPTURE(int(c.method));
        CAPTURE(c.featureVariance);
        const Synthetic s = synthetic(c.featureVariance);
        const DenoiseResult r = denoise(test::context(), s.in, c.method);
        REQUIRE(r.rgb.size() == s.clean.size());
        const double before = mse(s.in.color, s.clean), after = mse(r.rgb, s.clean);
        MESSAGE("mse " << before << " -> " << after << " (" << before / after << "x), device " << r.deviceSeconds << " s");
        CHECK(after * c.factor < before);
        // The two columns beside the edge: no bias towards the other region.
        for (int x : {kEdge - 1, kEdge}) {
            double bias[3] = {0, 0, 0};
            for (int y = 0; y < kSize; ++y)
                for (int ch = 0; ch < 3; ++ch) {
                    const std::size_t i = 3 * (std::size_t(y) * kSize + x) + ch;
                    bias[ch] += (r.rgb[i] - s.clean[i]) / kSize;
                }
            CAPTURE(x);
            for (double b : bias) CHECK(std::abs(b) < c.edgeBias);
        }
        CHECK(r.seconds > 0.0);
        CHECK(r.deviceSeconds > 0.0);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("denoise: emitter pixels keep their colour, and the output is the same bits each run") {
    Synthetic s = synthetic();
    // p saw only an emitter; its neighbour p2 a quarter of the time.
    const std::size_t p = std::size_t(20) * kSize + 10, p2 = p - 1;
    s.in.emitter[p] = 1.0f;
    s.in.emitter[p2] = 0.25f;
    for (int c = 0; c < 3; ++c) {
        s.in.color[3 * p + c] = s.in.halfA[3 * p + c] = s.in.halfB[3 * p + c] = 40.0f + float(c);
        s.in.variance[3 * p + c] = 0.0f;
        s.in.color[3 * p2 + c] = s.in.halfA[3 * p2 + c] = s.in.halfB[3 * p2 + c] = 10.0f + float(c);
        s.in.variance[3 * p2 + c] = 20.0f;
    }
    for (DenoiseMethod method : {DenoiseMethod::Nfor, DenoiseMethod::Fast}) {
        CAPTURE(int(method));
        const DenoiseResult a = denoise(test::context(), s.in, method);
        const DenoiseResult b = denoise(test::context(), s.in, method);
        REQUIRE(a.rgb.size() == b.rgb.size());
        CHECK(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0);
        for (int c = 0; c < 3; ++c) {
            CHECK(a.rgb[3 * p + c] == s.in.color[3 * p + c]);
            CHECK(a.rgb[3 * p2 + c] == s.in.color[3 * p2 + c]);
        }
        // The pixels beside them do not take in their light.
        const std::size_t q = p + 1;
        CHECK(std::abs(a.rgb[3 * q] - s.clean[3 * q]) < 0.2f);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("denoise: a layer of the wrong size is an error that names it") {
    const Synthetic s = synthetic();
    const auto expectError = [](const DenoiseInput& in, const std::string& layer) {
        try {
            denoise(test::context(), in, DenoiseMethod::Nfor);
            FAIL("no error for " << layer);
        } catch (const Error& e) {
            const std::string what = e.what();
            CAPTURE(what);
            CHECK(what.rfind("strata: error: ", 0) == 0);
            CHECK(what.find("'" + layer + "'") != std::string::npos);
            CHECK(what.find('\n') == std::string::npos);
        }
    };
    DenoiseInput in = s.in;
    in.halfB.pop_back();
    expectError(in, "halfB");
    in = s.in;
    in.depth.push_back(1.0f);
    expectError(in, "depth");
    in = s.in;
    in.normalVariance.assign(5, 0.0f);
    expectError(in, "normalVariance");
    in = s.in;
    in.width = 0;
    CHECK_THROWS_AS(denoise(test::context(), in, DenoiseMethod::Fast), Error);
}

TEST_SUITE_END();
