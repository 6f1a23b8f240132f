// The thin lens (--lens-radius, --focus-distance, --aperture-blades;
// lib/film.glsl, cameraSample) against its known answer on
// tests/data/lens/square.gltf (tests/data/make_lens.py): a small emitter at
// distance d seen through a lens of radius R focused at f spreads into the
// aperture's shape scaled by R |1/f - 1/d| (tan units on the image), its
// energy unchanged; focused at d it stays sharp.
#include <doctest/doctest.h>

#include <cmath>

#include "cli_util.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

namespace {

constexpr int kSize = 64;
constexpr double kTanHalf = 0.25;                    // the camera's tan(yfov / 2)
constexpr double kPixel = 2.0 * kTanHalf / kSize;    // a pixel's side in tan units
constexpr double kSquare = 0.08 / 4.0;               // the emitter's side in tan units (0.08 at d = 4)
constexpr double kDistance = 4.0;

struct Image {
    std::vector<float> mean, var;  // rgb per pixel
    double sum = 0.0, sumVar = 0.0;  // of channel G over all pixels
};

Image renderSquare(float radius, float focus, std::uint32_t blades, std::uint32_t spp) {
    const Scene scene = loadGltf(sourcePath("tests/data/lens/square.gltf"));
    RenderSettings s;
    s.width = s.height = kSize;
    s.spp = spp;
    s.lensRadius = radius;
    s.focusDistance = focus;
    s.apertureBlades = blades;
    const RenderResult r = renderScene(scene, s);
    Image img{r.film.mean(), r.film.varianceOfMean()};
    for (int i = 0; i < kSize * kSize; ++i) img.sum += img.mean[i * 3 + 1], img.sumVar += img.var[i * 3 + 1];
    return img;
}

// Pixel (px, py)'s centre's distance from the image centre, in pixels.
double radiusOf(int px, int py) { return std::hypot(px + 0.5 - kSize / 2.0, py + 0.5 - kSize / 2.0); }

// The mean of channel G over the pixels within `inner` pixels of the centre,
// with its standard error from the render's variance; and the largest value
// beyond `outer`.
struct Rings {
    double mean = 0.0, stdError = 0.0, outside = 0.0;
    int count = 0;
};
Rings rings(const Image& img, double inner, double outer) {
    Rings r;
    double var = 0.0;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const std::size_t i = (std::size_t(py) * kSize + px) * 3 + 1;
            const double d = radiusOf(px, py);
            if (d < inner) r.mean += img.mean[i], var += img.var[i], ++r.count;
            if (d > outer) r.outside = std::max(r.outside, double(img.mean[i]));
        }
    r.mean /= r.count;
    r.stdError = std::sqrt(var) / r.count;
    return r;
}

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("lens: a small emitter out of focus spreads into a uniform disk of radius R |1/f - 1/d| with its energy "
          "unchanged, a pentagon with five blades, and stays sharp in focus" * doctest::test_suite("slow")) {
    const double energy = kSquare * kSquare / (kPixel * kPixel);  // the image's sum, in pixels x radiance 1
    const double margin = kSquare / kPixel / std::sqrt(2.0) * 2.0 + std::sqrt(0.5);  // the square's diagonal + half a pixel's

    const Image pinhole = renderSquare(0.0f, 1.0f, 0, 256);
    CHECK(std::abs(pinhole.sum - energy) < 4.0 * std::sqrt(pinhole.sumVar));

    // R = 0.5, f = 2, d = 4: a disk of radius 0.125 tan units, 16 pixels.
    const double radius = 0.5 * std::abs(1.0 / 2.0 - 1.0 / kDistance) / kPixel;
    const Image disk = renderSquare(0.5f, 2.0f, 0, 512);
    CAPTURE(disk.sum);
    CHECK(std::abs(disk.sum - energy) < 4.0 * std::sqrt(disk.sumVar));
    const double diskArea = M_PI * radius * radius;
    const Rings d = rings(disk, radius - margin, radius + margin);
    CAPTURE(d.mean);
    CAPTURE(d.stdError);
    CHECK(d.count > 400);
    CHECK(std::abs(d.mean - energy / diskArea) < 4.0 * d.stdError);
    CHECK(d.stdError < 0.03 * energy / diskArea);
    CHECK(d.outside == 0.0);

    // Five blades: a regular pentagon inscribed in that circle (area 5/2 r^2 sin 72 degrees).
    const Image penta = renderSquare(0.5f, 2.0f, 5, 512);
    CHECK(std::abs(penta.sum - energy) < 4.0 * std::sqrt(penta.sumVar));
    const double apothem = radius * std::cos(M_PI / 5.0);
    const Rings p = rings(penta, apothem - margin, radius + margin);
    CAPTURE(p.mean);
    CHECK(std::abs(p.mean - energy / (2.5 * radius * radius * std::sin(2.0 * M_PI / 5.0))) < 4.0 * p.stdError);
    CHECK(p.outside == 0.0);

    // Focused at the emitter: as sharp as the pinhole.
    const Image sharp = renderSquare(0.5f, float(kDistance), 0, 64);
    CHECK(std::abs(sharp.sum - energy) < 4.0 * std::sqrt(sharp.sumVar) + 0.01 * energy);
    const Rings s = rings(sharp, 0.0, kSquare / kPixel / std::sqrt(2.0) + 1.5);
    CHECK(s.outside == 0.0);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

TEST_CASE("lens: a negative radius or an aperture of one or two blades is one error line, exit 2, no output") {
    const std::string scene = sourcePath("tests/data/lens/square.gltf");
    expectError("render " + scene + " --lens-radius -0.1", "strata: error: --lens-radius must be 0 or more");
    expectError("render " + scene + " --lens-radius 0.1 --aperture-blades 2",
                "strata: error: --aperture-blades must be 0 (round) or 3 or more");
    expectError("render " + scene + " --focus-distance 0", "strata: error: --focus-distance");
}

TEST_SUITE_END();
