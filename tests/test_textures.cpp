// glTF textures: known answers rendered by the real shaders (lavapipe,
// validation on), plus CPU checks of texture-coordinate decoding and tangent
// generation. Scenes: tests/data/textures/, written by
// scripts/make_texture_scenes.py, whose constants are mirrored here.
//
// "Direct" scenes are seen at max depth 0 with a box filter of radius 1e-5
// pixels, so every sample sees the pixel centre's uv (within 1e-6) and a
// pixel is exactly emissiveFactor x the decoded texture there.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "pack/textures.h"
#include "render/report.h"
#include "measure/tracer.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

const std::string kDir = "tests/data/textures/";
constexpr glm::dvec3 kEmissive{1.0, 0.5, 0.25};
// 4 x 2 sRGB texels, rows top to bottom (checker.png).
constexpr int kChecker[2][4][3] = {{{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}},
                                   {{10, 20, 30}, {128, 64, 200}, {40, 200, 90}, {0, 0, 0}}};
// 3 x 2 16-bit texels (rgb; alpha 65535).
constexpr int kChecker16[2][3][3] = {{{65535, 0, 1000}, {300, 40000, 65535}, {12345, 54321, 7}},
                                     {{0, 0, 0}, {65535, 65535, 65535}, {32768, 16384, 49152}}};

enum class WrapMode { Repeat, Clamp, Mirror };

// OpenGL 4.6 sec. 8.14.2, written independently of the shader.
int wrapIndex(int i, int n, WrapMode mode) {
    if (mode == WrapMode::Clamp) return std::clamp(i, 0, n - 1);
    if (mode == WrapMode::Mirror) {
        const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
        return m < n ? m : 2 * n - 1 - m;
    }
    return ((i % n) + n) % n;
}

glm::dvec3 checkerTexel(int x, int y) {
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) c[k] = srgbToLinear(kChecker[y][x][k] / 255.0);
    return c;
}

// Nearest lookup of checker.png: the texel, and the distance (in texels) of
// uv from the nearest texel boundary.
glm::dvec3 checkerNearest(glm::dvec2 uv, WrapMode s, WrapMode t, double* boundary = nullptr) {
    const glm::dvec2 x = uv * glm::dvec2(4.0, 2.0);
    if (boundary) {
        const glm::dvec2 f = x - glm::floor(x);
        *boundary = std::min({f.x, 1.0 - f.x, f.y, 1.0 - f.y});
    }
    return checkerTexel(wrapIndex(static_cast<int>(std::floor(x.x)), 4, s),
                        wrapIndex(static_cast<int>(std::floor(x.y)), 2, t));
}

glm::dvec3 checkerBilinear(glm::dvec2 uv, WrapMode s, WrapMode t) {
    const glm::dvec2 c = uv * glm::dvec2(4.0, 2.0) - 0.5;
    const glm::dvec2 b = glm::floor(c), f = c - b;
    auto at = [&](int dx, int dy) {
        return checkerTexel(wrapIndex(static_cast<int>(b.x) + dx, 4, s),
                            wrapIndex(static_cast<int>(b.y) + dy, 2, t));
    };
    return glm::mix(glm::mix(at(0, 0), at(1, 0), f.x), glm::mix(at(0, 1), at(1, 1), f.x), f.y);
}

struct DirectCheck {
    double maxRelError = 0.0;
    std::size_t skipped = 0;  // pixels whose centre is within 1e-5 texel of a texel boundary
};

// Renders a direct scene and compares every pixel with `expected(s, t)`, the
// radiance at pixel centre (s, t) in [0, 1]^2; returns the largest relative
// error max |r - e| / max(e, 1e-3) over channels.
DirectCheck checkDirect(const std::string& file, int size,
                        const std::function<glm::dvec3(glm::dvec2, double*)>& expected) {
    const Rendered r = renderFile(kDir + file, centreSettings(size, 4, 0, 3));
    const auto mean = r.result.film.mean();
    DirectCheck out;
    for (int py = 0; py < size; ++py) {
        for (int px = 0; px < size; ++px) {
            double boundary = 1.0;
            const glm::dvec2 st((px + 0.5) / size, (py + 0.5) / size);
            const glm::dvec3 e = expected(st, &boundary);
            // Samples lie within 1e-5 px of the centre: < 5e-6 texel here.
            if (boundary < 1e-5) {
                ++out.skipped;
                continue;
            }
            for (int c = 0; c < 3; ++c) {
                const double v = mean[(static_cast<std::size_t>(py) * size + px) * 3 + c];
                out.maxRelError = std::max(out.maxRelError, std::abs(v - e[c]) / std::max(e[c], 1e-3));
            }
        }
    }
    return out;
}

// uv of the direct scenes' quad: UV0 + (s, t) * span.
glm::dvec2 quadUv(glm::dvec2 st, glm::dvec2 uv0, glm::dvec2 span) { return uv0 + st * span; }

}  // namespace

TEST_CASE("texture: an emissive checker seen directly is emissiveFactor x the sRGB-decoded texel") {
    const DirectCheck d = checkDirect("nearest.gltf", 24, [](glm::dvec2 st, double* b) {
        return kEmissive * checkerNearest(st, WrapMode::Repeat, WrapMode::Repeat, b);
    });
    CAPTURE(d.maxRelError);
    CHECK(d.skipped == 0);
    CHECK(d.maxRelError < 1e-5);  // float32 pow/unpack against the double curve

    const DirectCheck d16 = checkDirect("nearest-16bit.gltf", 24, [](glm::dvec2 st, double* b) {
        const glm::dvec2 x = st * glm::dvec2(3.0, 2.0);
        const glm::dvec2 f = x - glm::floor(x);
        *b = std::min({f.x, 1.0 - f.x, f.y, 1.0 - f.y});
        glm::dvec3 c;
        for (int k = 0; k < 3; ++k)
            c[k] = srgbToLinear(kChecker16[static_cast<int>(x.y)][static_cast<int>(x.x)][k] / 65535.0);
        return kEmissive * c;
    });
    CAPTURE(d16.maxRelError);
    CHECK(d16.skipped == 0);
    CHECK(d16.maxRelError < 1e-5);  // 16-bit PNG: decoded to 16 bits, not 8
    CHECK(vk::validationMessageCount() == 0);
}

// --texture-max-size 2 halves checker.png (4 x 2) to 2 x 1: each texel the
// mean of its 2 x 2 block in linear light, stored in sRGB again (8 bits).
TEST_CASE("texture: --texture-max-size halves a texture in linear light, the render reads the smaller one") {
    SceneRequest request = keptRequest(centreSettings(24, 4, 0, 3));
    request.file = sourcePath(kDir + "nearest.gltf");
    request.textureMaxSize = 2;
    HostScene host = prepareScene(request);
    REQUIRE(host.gpu.images.size() == 1);
    CHECK(host.gpu.images[0].width == 2);
    CHECK(host.gpu.images[0].height == 1);
    CHECK(host.gpu.images[0].fileWidth == 4);
    CHECK(host.gpu.images[0].levels == 2);       // and its 1x1 mip level (--texture-lod on)
    CHECK(host.gpu.images[0].bytes == (2 + 1) * 4);
    const RenderResult r = render(context(), uploadPrepared(context(), request, host.gpu), host.camera,
                                  centreSettings(24, 4, 0, 3));
    auto halfTexel = [](int x) {
        glm::dvec3 c(0.0);
        for (int y = 0; y < 2; ++y)
            for (int dx = 0; dx < 2; ++dx) c += 0.25 * checkerTexel(2 * x + dx, y);
        for (int k = 0; k < 3; ++k) {  // stored as 8-bit sRGB again
            const double v = c[k] <= 0.0031308 ? c[k] * 12.92 : 1.055 * std::pow(c[k], 1.0 / 2.4) - 0.055;
            c[k] = srgbToLinear(std::round(v * 255.0) / 255.0);
        }
        return c;
    };
    const auto mean = r.film.mean();
    double worst = 0.0;
    std::size_t compared = 0;
    for (int py = 0; py < 24; ++py)
        for (int px = 0; px < 24; ++px) {
            const glm::dvec2 st((px + 0.5) / 24, (py + 0.5) / 24);
            const double x = st.x * 2.0;  // the quad's uv spans [0, 1]: nearest texel of the 2 x 1 image
            if (std::abs(x - std::round(x)) < 1e-5) continue;
            const glm::dvec3 e = kEmissive * halfTexel(static_cast<int>(x) % 2);
            for (int c = 0; c < 3; ++c) {
                const double v = mean[(static_cast<std::size_t>(py) * 24 + px) * 3 + c];
                worst = std::max(worst, std::abs(v - e[c]) / std::max(e[c], 1e-3));
            }
            ++compared;
        }
    CAPTURE(worst);
    CHECK(compared > 500);
    CHECK(worst < 1e-5);
    CHECK(vk::validationMessageCount() == 0);
}

// The materials board's three 64x64 textures (48 KiB of words) on a device
// whose texel view holds 4096 texels (16 KiB): each is halved once, the
// largest first, and the render is --texture-max-size 32's, bit for bit.
TEST_CASE("texture: textures past a texel view's range are halved to fit, as --texture-max-size would") {
    RenderSettings s = centreSettings(24, 2, 2, 1);
    RenderTuning lowered;
    lowered.limits.texelElements = 4096;
    SceneRequest request = keptRequest(s, lowered);
    request.file = sourcePath("scenes/materials-board.gltf");
    HostScene host = prepareScene(request);
    REQUIRE(host.gpu.images.size() == 3);
    const RenderResult fitted = render(context(), uploadPrepared(context(), request, host.gpu), host.camera, s, lowered);
    for (const PackedImage& p : host.gpu.images) {
        CHECK(p.width == 32);
        CHECK(p.fileWidth == 64);
    }
    CHECK(host.gpu.texels.size() * 4 <= 4096 * 4);
    SceneRequest halved = keptRequest(s);
    halved.file = request.file;
    halved.textureMaxSize = 32;
    HostScene small = prepareScene(halved);
    const RenderResult expected = render(context(), uploadPrepared(context(), halved, small.gpu), small.camera, s);
    CHECK(sameImage(fitted.film, expected.film));
    // Without the lowered range nothing is halved.
    SceneRequest whole = keptRequest(s);
    whole.file = request.file;
    HostScene full = prepareScene(whole);
    (void)uploadPrepared(context(), whole, full.gpu);
    for (const PackedImage& p : full.gpu.images) CHECK(p.width == 64);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: wrap modes REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT per axis") {
    struct Case {
        const char* file;
        WrapMode s, t;
    };
    for (const Case c : {Case{"wrap-repeat.gltf", WrapMode::Repeat, WrapMode::Repeat},
                         Case{"wrap-clamp-mirror.gltf", WrapMode::Clamp, WrapMode::Mirror},
                         Case{"wrap-mirror-clamp.gltf", WrapMode::Mirror, WrapMode::Clamp}}) {
        CAPTURE(c.file);
        // uv spans [-1, 2]^2: three periods per axis.
        const DirectCheck d = checkDirect(c.file, 24, [&](glm::dvec2 st, double* b) {
            return kEmissive * checkerNearest(quadUv(st, {-1, -1}, {3, 3}), c.s, c.t, b);
        });
        CAPTURE(d.maxRelError);
        CHECK(d.skipped == 0);
        CHECK(d.maxRelError < 1e-5);
        // The test can tell the modes apart: the expected image of every
        // other mode pair differs in at least a sixth of the pixels.
        for (const WrapMode s : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
            for (const WrapMode t : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
                if (s == c.s && t == c.t) continue;
                int differ = 0;
                for (int i = 0; i < 24 * 24; ++i) {
                    const glm::dvec2 uv = quadUv({(i % 24 + 0.5) / 24, (i / 24 + 0.5) / 24}, {-1, -1}, {3, 3});
                    differ += checkerNearest(uv, s, t) != checkerNearest(uv, c.s, c.t);
                }
                CHECK(differ >= 24 * 24 / 6);
            }
        }
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: KHR_texture_transform offset, rotation, scale and texCoord override") {
    // offset (0.25, -0.5), rotation 0.6 rad, scale (1.5, -2), TEXCOORD_1;
    // uv' = offset + R (scale * uv), R columns (cos, -sin), (sin, cos).
    const double c = std::cos(0.6), s = std::sin(0.6);
    const DirectCheck d = checkDirect("transform.gltf", 24, [&](glm::dvec2 st, double* b) {
        const glm::dvec2 q = st * glm::dvec2(1.5, -2.0);
        const glm::dvec2 uv(0.25 + c * q.x + s * q.y, -0.5 - s * q.x + c * q.y);
        return kEmissive * checkerNearest(uv, WrapMode::Repeat, WrapMode::Repeat, b);
    });
    CAPTURE(d.maxRelError);
    CAPTURE(d.skipped);
    CHECK(d.skipped == 0);
    CHECK(d.maxRelError < 1e-5);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: bilinear filtering, and half-way between texel centres is their average") {
    // 23 x 23 pixels: pixel (11, 11) sees uv (0.5, 0.5), half-way between
    // the centres of texels (1..2, 0..1).
    const DirectCheck d = checkDirect("bilinear.gltf", 23, [](glm::dvec2 st, double*) {
        return kEmissive * checkerBilinear(st, WrapMode::Clamp, WrapMode::Repeat);
    });
    CAPTURE(d.maxRelError);
    CHECK(d.maxRelError < 1e-4);
    const Rendered r = renderFile(kDir + "bilinear.gltf", centreSettings(23, 1, 0, 5));
    const auto mean = r.result.film.mean();
    const glm::dvec3 average =
        0.25 * (checkerTexel(1, 0) + checkerTexel(2, 0) + checkerTexel(1, 1) + checkerTexel(2, 1));
    for (int k = 0; k < 3; ++k) {
        CAPTURE(k);
        CHECK(mean[(11 * 23 + 11) * 3 + k] == doctest::Approx(kEmissive[k] * average[k]).epsilon(1e-4));
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: alpha MASK holes (alpha 127/255 < cutoff 0.5 <= 128/255) show the emitter behind") {
    // 8 x 8 checker of alpha 127 (hole) and 128 (kept) over a white emitter.
    const Rendered r = renderFile(kDir + "alpha-mask.gltf", centreSettings(24, 4, 0, 9));
    const auto mean = r.result.film.mean();
    std::size_t wrong = 0, lit = 0;
    for (int py = 0; py < 24; ++py) {
        for (int px = 0; px < 24; ++px) {
            const bool hole = (px / 3 + py / 3) % 2 == 0;
            const float v = mean[(static_cast<std::size_t>(py) * 24 + px) * 3];
            wrong += v != (hole ? 1.0f : 0.0f);
            lit += v == 1.0f;
        }
    }
    CHECK(wrong == 0);
    CHECK(lit == 24 * 24 / 2);
    CHECK((r.gpu.features.bits & gpu::kFeatureAlphaTest) != 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: alpha BLEND 0.3 lets 70% of camera rays through, deterministically per seed") {
    RenderSettings s = centreSettings(32, 64, 0, 21);
    s.filter = PixelFilter{};  // box, radius 0.5: every sample is another ray
    const Rendered a = renderFile(kDir + "alpha-blend.gltf", s);
    const Rendered b = renderFile(kDir + "alpha-blend.gltf", s);
    const auto ma = a.result.film.mean(), mb = b.result.film.mean();
    CHECK(std::memcmp(ma.data(), mb.data(), ma.size() * sizeof(float)) == 0);
    // Each sample is 1 (through) or 0 (stopped): Bernoulli(0.7).
    const double n = 32.0 * 32.0 * 64.0;
    double through = 0.0, sq = 0.0;
    for (std::size_t i = 0; i < ma.size(); i += 3) {
        through += ma[i];
        sq += static_cast<double>(ma[i]) * ma[i];
    }
    const double pixels = 32.0 * 32.0;
    const double p = through / pixels;
    const double se = std::sqrt(0.7 * 0.3 / n);  // 0.0018
    CAPTURE(p);
    CHECK(std::abs(p - 0.7) <= 4.0 * se);
    // Per-pixel fractions spread as Binomial(64, 0.7) / 64 (variance
    // 0.00328) when the samples of a pixel are independent; the sample
    // variance over 1024 pixels has a relative standard deviation of 4.4%,
    // so +-20% is a 4.5-sigma bound.
    const double var = sq / pixels - p * p;
    CAPTURE(var);
    CHECK(var == doctest::Approx(0.7 * 0.3 / 64.0).epsilon(0.2));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texture: alpha holes are skipped by trace.comp's closest-hit and any-hit alike") {
    const Scene scene = loadGltf(sourcePath(kDir + "alpha-mask.gltf"));
    const GpuScene gpu = buildAndPack(scene);
    // Rays down -Z through the centres of the blocker's 8 x 8 cells (z = 0.5,
    // [-0.75, 0.75]^2); the emitter is at z = 0.
    std::vector<gpu::TraceRay> rays;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            rays.push_back({glm::vec3(-0.75f + (x + 0.5f) * 0.1875f, 0.75f - (y + 0.5f) * 0.1875f, 1.0f), 0.0f,
                            glm::vec3(0, 0, -1), 0.75f});
    const auto any = traceOnDevice(context(), gpu, rays, ReadMode::Auto, gpu::kTraceAny);
    for (auto& r : rays) r.tmax = 2.0f;
    const auto closest = traceOnDevice(context(), gpu, rays, ReadMode::Auto, gpu::kTraceClosest);
    for (int i = 0; i < 64; ++i) {
        const bool hole = (i % 8 + i / 8) % 2 == 0;
        CAPTURE(i);
        CHECK((any[i].t < 0.0f) == hole);                                // tmax 0.75 ends before the emitter
        CHECK(closest[i].t == doctest::Approx(hole ? 1.0 : 0.5));        // the emitter, else the blocker
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

namespace {

TextureImage image8(int width, int height, const std::vector<std::array<int, 4>>& texels) {
    TextureImage im;
    im.width = width;
    im.height = height;
    for (const auto& t : texels)
        for (int c : t) im.data.push_back(static_cast<std::uint8_t>(c));
    return im;
}

}  // namespace

TEST_CASE("texture: downsampling averages colour in linear light, renormalises normals, covers odd sizes") {
    // sRGB: red and three black texels: a quarter of red's light, 137 in sRGB (not 64, the mean of the codes).
    const TextureImage quad = image8(2, 2, {{255, 0, 0, 255}, {0, 0, 0, 255}, {0, 0, 0, 0}, {0, 0, 0, 0}});
    const TextureImage srgb = downsampledTexture(quad, 1, TexelCoding::Srgb);
    REQUIRE(srgb.width == 1);
    REQUIRE(srgb.height == 1);
    CHECK(int(srgb.data[0]) == 137);
    CHECK(int(srgb.data[3]) == 128);  // alpha averaged as it is: 127.5 rounded
    CHECK(int(downsampledTexture(quad, 1, TexelCoding::Linear).data[0]) == 64);
    // Normals +X and +Y (encoded 2n - 1): their mean renormalised, (0.707, 0.707, 0).
    const TextureImage normals = image8(2, 1, {{255, 128, 128, 255}, {128, 255, 128, 255}});
    const TextureImage n = downsampledTexture(normals, 1, TexelCoding::Normal);
    glm::dvec3 v;
    for (int c = 0; c < 3; ++c) v[c] = 2.0 * n.data[std::size_t(c)] / 255.0 - 1.0;
    CHECK(glm::length(v) == doctest::Approx(1.0).epsilon(0.01));
    CHECK(v.x == doctest::Approx(std::sqrt(0.5)).epsilon(0.01));
    // An odd side: 3 x 1 halves to 2 x 1, its last texel alone.
    const TextureImage odd = image8(3, 1, {{0, 0, 0, 0}, {0, 0, 0, 0}, {10, 20, 30, 40}});
    const TextureImage h = downsampledTexture(odd, 2, TexelCoding::Linear);
    REQUIRE(h.width == 2);
    CHECK(std::vector<int>(h.data.begin() + 4, h.data.end()) == std::vector<int>{10, 20, 30, 40});
    // Halved until neither side exceeds the size: 64 x 16 at most 10 is 8 x 2.
    TextureImage big = image8(64, 16, std::vector<std::array<int, 4>>(64 * 16, {200, 100, 50, 255}));
    const TextureImage small = downsampledTexture(big, 10, TexelCoding::Srgb);
    CHECK(small.width == 8);
    CHECK(small.height == 2);
    CHECK(int(small.data[0]) == 200);  // a uniform image stays itself
    // --stats: the largest four, how many downsampled, the file's size where it differs.
    nlohmann::json list = nlohmann::json::array();
    for (int k = 0; k < 5; ++k)
        list.push_back({{"name", "t" + std::to_string(k)}, {"width", 8}, {"height", 8}, {"file_width", k == 2 ? 16 : 8},
                        {"file_height", k == 2 ? 16 : 8}, {"bytes", 256 * (k + 1)}});
    CHECK(texturesText({{"images", 5}, {"bytes", 3840}, {"list", list}}) ==
          "5 image(s), 3840 bytes on the device, 1 downsampled: t4 8x8 (1280 bytes), t3 8x8 (1024 bytes), t2 8x8 "
          "(768 bytes, 16x16 in the file), t1 8x8 (512 bytes) and 1 more");
    // 16 bits stay 16 bits.
    big.bits = 16;
    big.data.assign(std::size_t(64) * 16 * 8, 0xff);
    const TextureImage wide = downsampledTexture(big, 32, TexelCoding::Linear);
    CHECK(wide.bits == 16);
    CHECK(wide.data.size() == std::size_t(32) * 8 * 8);
}

// The share of bilinear lookups (repeat wrap) of an 8-bit image whose
// alpha is at least 128 (cutoff 0.5), at 8 x 8 points a texel.
double bilinearCoverage(const TextureImage& im) {
    const int w = im.width, h = im.height;
    auto alpha = [&](int x, int y) { return double(im.data[(std::size_t((y + h) % h) * std::size_t(w) + std::size_t((x + w) % w)) * 4 + 3]); };
    std::size_t passed = 0, total = 0;
    for (int y = 0; y < h * 8; ++y)
        for (int x = 0; x < w * 8; ++x) {
            const double u = (x + 0.5) / 8.0 - 0.5, v = (y + 0.5) / 8.0 - 0.5;
            const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
            const double fx = u - x0, fy = v - y0;
            const double a = (1 - fx) * (1 - fy) * alpha(x0, y0) + fx * (1 - fy) * alpha(x0 + 1, y0) +
                             (1 - fx) * fy * alpha(x0, y0 + 1) + fx * fy * alpha(x0 + 1, y0 + 1);
            passed += a >= 127.5;
            ++total;
        }
    return double(passed) / double(total);
}

// A MASK texture downsampled keeps its coverage (the share of bilinear
// lookups at or above the cutoff) within 2% down to 8 x 8, where plain
// means lose it; its mip levels take colour over the leaves alone; BLEND
// weights colour by alpha.
TEST_CASE("texture: cut-outs downsampled keep MASK coverage, their levels take colour over what is seen") {
    // 64 x 64: green leaves (alpha 255) where a smooth pattern is high, about
    // 23% of the lookups, on red holes (alpha 0).
    std::vector<std::array<int, 4>> texels;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const bool leaf = std::sin(0.7 * x) * std::cos(0.45 * y) + 0.3 * std::sin(0.2 * (x + y)) > 0.4;
            texels.push_back(leaf ? std::array<int, 4>{0, 255, 0, 255} : std::array<int, 4>{255, 0, 0, 0});
        }
    const TextureImage base = image8(64, 64, texels);
    const double share = bilinearCoverage(base);
    REQUIRE(share > 0.2);
    REQUIRE(share < 0.4);
    AlphaUse mask;
    mask.mode = AlphaUse::Mode::Mask;
    mask.cutoff = 0.5f;
    double plainWorst = 0.0;
    for (std::uint32_t size = 32; size >= 8; size /= 2) {
        CAPTURE(size);
        const TextureImage small = downsampledTexture(base, size, TexelCoding::Srgb, mask);
        const TextureImage plain = downsampledTexture(base, size, TexelCoding::Srgb);
        const double kept = bilinearCoverage(small);
        MESSAGE(size << "x" << size << ": coverage " << kept << " (base " << share << ", plain means "
                     << bilinearCoverage(plain) << ")");
        CHECK(std::abs(kept - share) <= 0.02);
        plainWorst = std::max(plainWorst, std::abs(bilinearCoverage(plain) - share));
    }
    CHECK(plainWorst > 0.1);  // what the test guards against
    const std::vector<TextureImage> chain = textureMips(base, TexelCoding::Srgb, mask);
    REQUIRE(chain.size() == 6);
    for (const TextureImage& level : chain)
        for (std::size_t i = 0; i < std::size_t(level.width) * std::size_t(level.height); ++i)
            if (level.data[i * 4 + 3] > 0) CHECK(int(level.data[i * 4]) == 0);  // no red where any leaf is
    // BLEND: transparent red and opaque green are green at half alpha.
    AlphaUse blend;
    blend.mode = AlphaUse::Mode::Blend;
    const std::vector<TextureImage> b = textureMips(image8(2, 1, {{255, 0, 0, 0}, {0, 255, 0, 255}}), TexelCoding::Srgb, blend);
    REQUIRE(b.size() == 1);
    CHECK(std::vector<int>(b[0].data.begin(), b[0].data.end()) == std::vector<int>{0, 255, 0, 128});
}

TEST_SUITE_END();
