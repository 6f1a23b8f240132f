// Properties of the GLSL samplers, on samples drawn by the shader
// (measure/sample_dump.h) and on renders.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>

#include "../shaders/shared/types.h"
#include "measure/sample_dump.h"
#include "render/sampler_kind.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

// True when the points form a (0, m, 2)-net in base 2: for every k in 0..m,
// each elementary interval [i/2^k, (i+1)/2^k) x [j/2^(m-k), (j+1)/2^(m-k))
// holds exactly one point.
bool isZeroMTwoNet(const std::vector<glm::vec2>& pts, int m) {
    if (pts.size() != (std::size_t(1) << m)) return false;
    for (int k = 0; k <= m; ++k) {
        std::vector<int> count(pts.size(), 0);
        for (const auto& p : pts) {
            const auto ix = static_cast<std::size_t>(std::floor(p.x * double(1u << k)));
            const auto iy = static_cast<std::size_t>(std::floor(p.y * double(1u << (m - k))));
            if (ix >= (1u << k) || iy >= (1u << (m - k))) return false;
            if (++count[iy * (std::size_t(1) << k) + ix] > 1) return false;
        }
    }
    return true;
}

}  // namespace

TEST_CASE("Sobol and bluenoise: the first 2^m samples of the pixel pair and of the first light pair are (0,m,2)-nets") {
    for (std::uint32_t kind : {gpu::kSamplerSobol, gpu::kSamplerBlueNoise}) {
        for (int m : {2, 4, 6, 8}) {
            for (std::uint32_t px : {0u, 5u, 77u}) {
                const std::string name = samplerByKind(kind).name;
                CAPTURE(name);
                CAPTURE(m);
                CAPTURE(px);
                PixelSampleRequest req{kind, 1u << m, 9u, px, 3u, 128u, 128u};
                const auto s = drawPixelSamples(context(), req);
                std::vector<glm::vec2> pixel, light;
                for (const auto& v : s) pixel.emplace_back(v.x, v.y), light.emplace_back(v.z, v.w);
                CHECK(isZeroMTwoNet(pixel, m));
                CHECK(isZeroMTwoNet(light, m));
            }
        }
    }
    // The check can fail: independent samples are not nets.
    const auto s = drawPixelSamples(context(), {gpu::kSamplerIndependent, 64u, 9u, 0u, 0u, 128u, 128u});
    std::vector<glm::vec2> pts;
    for (const auto& v : s) pts.emplace_back(v.x, v.y);
    CHECK_FALSE(isZeroMTwoNet(pts, 6));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("a block of pixels drawn in one dispatch holds each pixel's own samples, and a block off the image is refused") {
    // strata edges draws whole rows of its block at once; each pixel's
    // samples must be the ones a draw of that pixel alone gives.
    for (std::uint32_t kind : {gpu::kSamplerIndependent, gpu::kSamplerStratified, gpu::kSamplerSobol,
                               gpu::kSamplerBlueNoise}) {
        CAPTURE(samplerByKind(kind).name);
        const std::uint32_t spp = 16;
        PixelSampleRequest block{kind, spp, 5u, 3u, 60u, 64u, 64u};
        block.blockWidth = 3;
        block.blockHeight = 2;
        const auto all = drawPixelSamples(context(), block);
        REQUIRE(all.size() == std::size_t(6) * spp);
        for (std::uint32_t y = 0; y < 2; ++y)
            for (std::uint32_t x = 0; x < 3; ++x) {
                const auto one = drawPixelSamples(context(), {kind, spp, 5u, 3u + x, 60u + y, 64u, 64u});
                CHECK(std::memcmp(one.data(), all.data() + (y * 3 + x) * spp, spp * sizeof(glm::vec4)) == 0);
            }
        // Neighbouring pixels differ (a block that repeated one pixel would not).
        CHECK(std::memcmp(all.data(), all.data() + spp, spp * sizeof(glm::vec4)) != 0);
    }
    PixelSampleRequest off{gpu::kSamplerIndependent, 4u, 1u, 62u, 0u, 64u, 64u};
    off.blockWidth = 3;  // columns 62..64 of a 64-wide image
    CHECK_THROWS_AS(drawPixelSamples(context(), off), std::invalid_argument);
    off.blockWidth = 0;
    CHECK_THROWS_AS(drawPixelSamples(context(), off), std::invalid_argument);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("grid samplers: regular is the n x n grid, rotated has a row and column of its own, stratified one per stratum") {
    const std::uint32_t n = 8, spp = n * n;
    auto draw = [&](std::uint32_t kind) {
        return drawPixelSamples(context(), {kind, spp, 4u, 2u, 7u, 64u, 64u});
    };
    std::set<std::pair<int, int>> cells, rows, cols;
    for (const auto& v : draw(gpu::kSamplerRegular)) {
        const double gx = v.x * n - 0.5, gy = v.y * n - 0.5;  // cell centres
        CHECK(std::abs(gx - std::round(gx)) < 1e-5);
        CHECK(std::abs(gy - std::round(gy)) < 1e-5);
        cells.emplace(static_cast<int>(std::round(gx)), static_cast<int>(std::round(gy)));
    }
    CHECK(cells.size() == spp);
    std::set<int> r, c;
    for (const auto& v : draw(gpu::kSamplerRotated)) {
        c.insert(static_cast<int>(std::floor(v.x * spp)));
        r.insert(static_cast<int>(std::floor(v.y * spp)));
    }
    CHECK(c.size() == spp);  // n-rooks on the n^2 x n^2 subgrid
    CHECK(r.size() == spp);
    cells.clear();
    for (const auto& v : draw(gpu::kSamplerStratified))
        cells.emplace(static_cast<int>(std::floor(v.x * n)), static_cast<int>(std::floor(v.y * n)));
    CHECK(cells.size() == spp);
    CHECK(vk::validationMessageCount() == 0);
}

// Same seed: bit-identical images. Different seeds: independent estimates, so
// the errors of two renders of the closed furnace (exact answer 0.75 at max
// depth 1) are uncorrelated: |Pearson r| below 4 / sqrt(pixels).
TEST_CASE("every sampler is deterministic per seed, and renders at different seeds are uncorrelated" * doctest::test_suite("slow")) {
    for (const auto& info : samplers()) {
        const std::string name = info.name;
        CAPTURE(name);
        RenderSettings s;
        s.width = 32;
        s.height = 32;
        s.spp = 16;
        s.maxDepth = 1;
        s.sampler = info.kind;
        s.seed = 3;
        const auto a = renderFile("scenes/furnace.gltf", s).result.film.mean();
        const auto b = renderFile("scenes/furnace.gltf", s).result.film.mean();
        CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
        s.seed = 4;
        const auto c = renderFile("scenes/furnace.gltf", s).result.film.mean();
        double sab = 0.0, saa = 0.0, sbb = 0.0;
        for (std::size_t i = 0; i < a.size(); i += 3) {  // grey: one channel per pixel
            const double ea = a[i] - 0.75, ec = c[i] - 0.75;
            sab += ea * ec, saa += ea * ea, sbb += ec * ec;
        }
        const double r = sab / std::sqrt(saa * sbb);
        CAPTURE(r);
        CHECK(saa > 0.0);
        CHECK(std::abs(r) < 4.0 / std::sqrt(a.size() / 3.0));
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
