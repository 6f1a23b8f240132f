// The AOVs of --aov (image/aov.h, lib/film.glsl, lib/path.glsl): known values
// on tests/data/aov/walls.gltf (tests/data/make_aov.py), the half-buffers,
// the image left unchanged, and the EXR layers written and read back.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "cli_util.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "test_util.h"
#include "util/error.h"

using namespace strata;
using namespace strata::test;

namespace {

constexpr int kSize = 48;
const char* kWalls = "tests/data/aov/walls.gltf";

RenderResult renderWalls(bool aov, IntegratorKind integrator = IntegratorKind::Megakernel) {
    const Scene scene = loadWithWhiteEnvironment(sourcePath(kWalls));
    RenderSettings s;
    s.width = s.height = kSize;
    s.spp = 8;
    s.aov = aov;
    s.integrator = integrator;
    return renderScene(scene, s);
}

// Where a pixel's samples (box filter, radius 0.5: inside the pixel) meet
// the plane z = -3: the x range, from the camera's yfov 0.7 at aspect 1.
struct Span {
    double x0, x1;
};
Span spanAtWall(int px) {
    const double t = 3.0 * std::tan(0.35);
    return {t * (2.0 * px / kSize - 1.0), t * (2.0 * (px + 1) / kSize - 1.0)};
}

// The cosine between pixel (px, py)'s central ray and the view direction -Z.
double centralCosine(int px, int py) {
    const double t = std::tan(0.35);
    const double x = t * (2.0 * (px + 0.5) / kSize - 1.0), y = t * (1.0 - 2.0 * (py + 0.5) / kSize);
    return 1.0 / std::sqrt(1.0 + x * x + y * y);
}

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("aov: a diffuse wall's albedo, normal and depth, a mirror's tinted albedo of the wall it shows, the "
          "background marked") {
    const RenderResult r = renderWalls(true);
    const AovImages a = aovImages(r.film);
    const double front[3] = {0.2, 0.5, 0.8}, back[3] = {0.3, 0.7, 0.2}, mirror[3] = {0.9, 0.6, 0.3};
    int walls = 0, mirrors = 0, sky = 0;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const std::size_t i = static_cast<std::size_t>(py) * kSize + px;
            const Span s = spanAtWall(px);
            CAPTURE(px);
            CAPTURE(py);
            if (s.x1 < 0.0) {  // the diffuse wall z = -3 facing the camera
                ++walls;
                for (int c = 0; c < 3; ++c) CHECK(a.albedo[i * 3 + c] == doctest::Approx(front[c]).epsilon(1e-6));
                CHECK(std::abs(a.normal[i * 3 + 0]) < 1e-5);
                CHECK(std::abs(a.normal[i * 3 + 1]) < 1e-5);
                CHECK(a.normal[i * 3 + 2] == doctest::Approx(1.0).epsilon(1e-5));
                // The mean of 3 / cos over the pixel: within 1e-3 of the central ray's.
                CHECK(a.depth[i] == doctest::Approx(3.0 / centralCosine(px, py)).epsilon(1e-3));
                CHECK(a.emitter[i] == 0.0f);
                // The same albedo in every sample: no variance, but for float32 sums' rounding.
                for (int c = 0; c < 3; ++c) CHECK(a.albedoVariance[i * 3 + c] < 1e-8f);
            } else if (s.x0 > 0.0 && s.x1 < 0.6) {  // the mirror, showing the wall behind the camera
                ++mirrors;
                // A smooth metal's reflectance is its F0 at these angles (Schlick's term < 1e-6).
                for (int c = 0; c < 3; ++c)
                    CHECK(a.albedo[i * 3 + c] == doctest::Approx(mirror[c] * back[c]).epsilon(1e-3));
                CHECK(a.normal[i * 3 + 2] == doctest::Approx(-1.0).epsilon(1e-5));  // facing away from the camera
                CHECK(a.depth[i] == doctest::Approx(3.0 / centralCosine(px, py)).epsilon(1e-3));
                CHECK(a.emitter[i] == 0.0f);
            } else if (s.x0 > 0.6) {  // the background
                ++sky;
                for (int c = 0; c < 3; ++c) {
                    CHECK(a.albedo[i * 3 + c] == 1.0f);
                    CHECK(a.normal[i * 3 + c] == 0.0f);
                }
                CHECK(a.depth[i] == 0.0f);
                CHECK(a.emitter[i] == 1.0f);
            }
        }
    CHECK(walls > 400);
    CHECK(mirrors > 150);
    CHECK(sky > 150);
}

TEST_CASE("aov: the half-buffers are the two halves of the samples, and the image is the same bits with AOVs") {
    const RenderResult with = renderWalls(true), without = renderWalls(false);
    CHECK(sameImage(with.film, without.film));
    const AovImages a = aovImages(with.film);
    int differ = 0;
    for (std::size_t i = 0; i < a.color.size(); ++i) {
        // 8 samples: 4 in each half, so the mean is the halves' average.
        CHECK(0.5 * (a.halfA[i] + a.halfB[i]) == doctest::Approx(a.color[i]).epsilon(1e-5));
        differ += a.halfA[i] != a.halfB[i];
    }
    CHECK(differ > static_cast<int>(a.color.size()) / 2);  // independent halves of a noisy image
}

TEST_CASE("aov: the wavefront integrator refuses --aov with one clear error") {
    CHECK_THROWS_WITH_AS(renderWalls(true, IntegratorKind::Wavefront),
                         doctest::Contains("need the megakernel integrator"), Error);
}

TEST_CASE("aov: render --aov writes every layer, and they read back as rendered") {
    TempDir out;
    const Run r = run(std::string("render ") + sourcePath(kWalls) + " --env-color 1,1,1 --aov --spp 4 --width 16 "
                      "--height 12 --quiet -o " + out / "a.exr");
    REQUIRE(r.status == 0);
    const AovImages a = readAovImages(out / "a.exr");
    CHECK(a.width == 16);
    CHECK(a.height == 12);
    for (const auto* v : {&a.color, &a.variance, &a.halfA, &a.halfB, &a.albedo, &a.normal, &a.albedoVariance,
                          &a.normalVariance})
        CHECK(v->size() == 16u * 12u * 3u);
    for (const auto* v : {&a.depth, &a.emitter, &a.depthVariance}) CHECK(v->size() == 16u * 12u);
    const Image img = readImage(out / "a.exr");
    CHECK(img.channels == 3 + 3 * 5 + 2 + 3 + 3 + 1);
}

TEST_SUITE_END();
