// KHR_materials_dispersion: paths that reach a dispersive dielectric carry a
// wavelength (shaders/lib/spectrum.glsl, the dispersion axis). The GLSL
// wavelength sampling runs by sample_test.comp (chi-square against its pdf,
// the throughput's weight unbiased per channel, the matching functions
// against the host's copy of the fit); a glass wedge spreads a white strip
// into a spectrum whose every channel lands where Snell's law with the
// extension's index puts it, the same bits in both integrators (scenes from
// scripts/make_dispersion_tests.py: tests/data/dispersion/); and the loader.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <string>

#include "cli_util.h"
#include "gltf_util.h"
#include "test_util.h"
#include "measure/sample_dump.h"
#include "pack/gpu_scene.h"
#include "stats/stats.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

constexpr double kPi = 3.14159265358979323846;

// The host's copy of lib/spectrum.glsl: the CIE 1931 fit of Wyman, Sloan
// and Shirley 2013, in linear Rec. 709, white-balanced over 360-830 nm.
double cieLobe(double l, double mu, double below, double above) {
    const double t = (l - mu) / (l < mu ? below : above);
    return std::exp(-0.5 * t * t);
}

glm::dvec3 wavelengthRgb(double l) {
    const double x = 1.056 * cieLobe(l, 599.8, 37.9, 31.0) + 0.362 * cieLobe(l, 442.0, 16.0, 26.7) -
                     0.065 * cieLobe(l, 501.1, 20.4, 26.2);
    const double y = 0.821 * cieLobe(l, 568.8, 46.9, 40.5) + 0.286 * cieLobe(l, 530.9, 16.3, 31.1);
    const double z = 1.217 * cieLobe(l, 437.0, 11.8, 36.0) + 0.681 * cieLobe(l, 459.0, 26.0, 13.8);
    const glm::dvec3 rgb(3.2404542 * x - 1.5371385 * y - 0.4985314 * z, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
                         0.0556434 * x - 0.2040259 * y + 1.0572252 * z);
    return rgb / glm::dvec3(128.33516, 101.54379, 97.11689);
}

double visiblePdf(double l) {
    if (l < 360.0 || l > 830.0) return 0.0;
    const double c = std::cosh(0.0072 * (l - 538.0));
    return 0.0039398042 / (c * c);
}

// The extension's index at lambda (nm) for n_d = ior and 20 / V_d = dispersion.
double dispersiveIor(double ior, double dispersion, double l) {
    return std::max(ior + (ior - 1.0) * dispersion / 20.0 * (523655.0 / (l * l) - 1.5168), 1.0);
}

std::vector<glm::vec4> drawWavelengths(std::uint32_t routine, std::uint32_t count, std::uint32_t seed, float first = 0.0f,
                                       float step = 0.0f) {
    gpu::SampleTestParams p{};
    p.count = count;
    p.routine = routine;
    p.seed = seed;
    p.bsdf4 = glm::vec4(first, step, 0.0f, 0.0f);
    return runSampleKernel(context(), p, 0, {}, {}, nullptr, gpu::kFeatureDispersion);
}

// scripts/make_dispersion_tests.py's wedge, traced on the host in the plane
// y = 0: the camera at z = kCameraZ looking down -Z, the front face z =
// kFrontZ, the back face z = -tan(kApex) x, the strip's centre at z = kStripZ.
constexpr double kCameraZ = 10.0, kFrontZ = 2.0, kStripZ = -30.0, kIor = 1.5, kDispersion = 1.0;
constexpr std::uint32_t kWidth = 128, kHeight = 16;
const double kApex = 20.0 * kPi / 180.0, kHfov = 2.4 * kPi / 180.0;

// d refracted at a surface of normal n (against d), eta = n_in / n_out;
// false at total internal reflection. t: the unpolarised Fresnel transmittance.
bool refract(glm::dvec3& d, glm::dvec3 n, double eta, double& t) {
    const double ci = -glm::dot(d, n);
    const double k = 1.0 - eta * eta * (1.0 - ci * ci);
    if (k <= 0.0) return false;
    const double ct = std::sqrt(k);
    const double rs = (eta * ci - ct) / (eta * ci + ct), rp = (ci - eta * ct) / (ci + eta * ct);
    t *= 1.0 - 0.5 * (rs * rs + rp * rp);
    d = glm::normalize(eta * d + (eta * ci - ct) * n);
    return true;
}

// Where the camera ray through image column position px (pixels from the
// left edge, on the centre row) reaches z = kStripZ at index n, and its
// transmittance through both faces.
double stripHit(double px, double n, double& t) {
    const double tanHalf = std::tan(0.5 * kHfov);
    glm::dvec3 o(0.0, 0.0, kCameraZ), d = glm::normalize(glm::dvec3((2.0 * px / kWidth - 1.0) * tanHalf, 0.0, -1.0));
    t = 1.0;
    o += d * ((kFrontZ - o.z) / d.z);
    if (!refract(d, glm::dvec3(0.0, 0.0, 1.0), 1.0 / n, t)) return NAN;
    const double tb = std::tan(kApex);
    o += d * (-(o.z + tb * o.x) / (d.z + tb * d.x));
    if (!refract(d, glm::dvec3(std::sin(kApex), 0.0, std::cos(kApex)), n, t)) return NAN;
    return o.x + d.x * (kStripZ - o.z) / d.z;
}

// The image column position whose ray reaches the strip's centre at index
// n, and the strip's weight there: transmittance over the magnification
// (columns per unit of strip).
double stripColumn(double n, double& weight) {
    double t = 0.0;
    const double centre = stripHit(0.5 * kWidth, kIor, t);  // the strip sits where the axis lands at n_d
    double lo = -double(kWidth), hi = 2.0 * kWidth;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (stripHit(mid, n, t) < centre ? lo : hi) = mid;
    }
    const double px = 0.5 * (lo + hi);
    double t1 = 0.0;
    const double slope = (stripHit(px + 1e-3, n, t1) - stripHit(px - 1e-3, n, t1)) / 2e-3;
    stripHit(px, n, t);
    weight = t / std::abs(slope);
    return px;
}

// Each channel's centroid (column position) and its standard error over
// the whole image, and the channel's total.
struct Centroids {
    glm::dvec3 at{0.0}, se{0.0}, total{0.0};
};

Centroids centroids(const RenderResult& r) {
    const auto m = r.film.mean();
    const auto v = r.film.varianceOfMean();
    Centroids c;
    std::vector<glm::dvec3> col(kWidth, glm::dvec3(0.0)), colVar(kWidth, glm::dvec3(0.0));
    for (std::uint32_t y = 0; y < kHeight; ++y)
        for (std::uint32_t x = 0; x < kWidth; ++x)
            for (int k = 0; k < 3; ++k) {
                const std::size_t p = (std::size_t(y) * kWidth + x) * 3 + std::size_t(k);
                col[x][k] += m[p], colVar[x][k] += v[p];
            }
    glm::dvec3 s0(0.0), s1(0.0);
    for (std::uint32_t x = 0; x < kWidth; ++x) s0 += col[x], s1 += (x + 0.5) * col[x];
    c.at = s1 / s0;
    c.total = s0;
    // The ratio's error to first order: sum over columns of ((x - C) / S0)^2 var.
    for (std::uint32_t x = 0; x < kWidth; ++x)
        for (int k = 0; k < 3; ++k) {
            const double d = (x + 0.5 - c.at[k]) / s0[k];
            c.se[k] += d * d * colVar[x][k];
        }
    c.se = glm::sqrt(c.se);
    return c;
}

RenderResult renderWedge(const std::string& file, std::uint32_t spp, IntegratorKind kind = IntegratorKind::Megakernel) {
    const Scene scene = loadGltf(sourcePath("tests/data/dispersion/" + file));
    const GpuScene gpu = buildAndPack(scene);
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.spp = spp;
    s.maxDepth = 2;  // in through the front face, out through the back: the strip
    s.integrator = kind;
    RenderResult r = uploadAndRender(gpu, scene.cameras.at(0), s);
    CHECK(r.nonFinite == 0);
    return r;
}

}  // namespace

TEST_CASE("dispersion: wavelengths follow their pdf (chi-square), the throughput's weight is 1 in each channel on average, and the matching functions are the host's") {
    const std::uint32_t n = 400000;
    const auto s = drawWavelengths(gpu::kSampleWavelength, n, 51);
    const int bins = 47;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    glm::dvec3 sum(0.0), sq(0.0);
    double worst = 0.0;
    for (const auto& d : s) {
        const int b = std::clamp(int((d.x - 360.0f) / 10.0f), 0, bins - 1);
        observed[b] += 1.0;
        const glm::dvec3 w(d.y, d.z, d.w);
        sum += w, sq += w * w;
        const glm::dvec3 want = wavelengthRgb(d.x) / visiblePdf(d.x);
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(w[k] - want[k]));
    }
    for (int b = 0; b < bins; ++b) {
        // Simpson over the bin.
        const double a = 360.0 + 10.0 * b;
        expected[b] = n * 10.0 / 6.0 * (visiblePdf(a) + 4.0 * visiblePdf(a + 5.0) + visiblePdf(a + 10.0));
    }
    const auto r = stats::chiSquareTest(observed, expected, 0.01, 1);
    MESSAGE(r.detail << "; largest weight error against the host " << worst);
    CHECK(r.passed);
    CHECK(worst < 2e-4);
    for (int k = 0; k < 3; ++k) {
        const double mean = sum[k] / n, se = std::sqrt((sq[k] / n - mean * mean) / n);
        MESSAGE("channel " << k << ": mean weight " << mean << " +- " << se);
        CHECK(std::abs(mean - 1.0) < 4.0 * se);
    }
    // The matching functions' integral over 360-830 nm is 1 in each channel
    // (the white balance), on the shader's own values at 0.5 nm steps.
    const auto f = drawWavelengths(gpu::kWavelengthFunctions, 941, 0, 360.0f, 0.5f);
    glm::dvec3 integral(0.0);
    for (std::size_t i = 0; i < f.size(); ++i) {
        const double wgt = (i == 0 || i + 1 == f.size()) ? 0.25 : 0.5;  // trapezoids of 0.5 nm
        integral += wgt * glm::dvec3(f[i].y, f[i].z, f[i].w);
        CHECK(double(f[i].x) == doctest::Approx(visiblePdf(360.0 + 0.5 * double(i))).epsilon(1e-4));
    }
    for (int k = 0; k < 3; ++k) CHECK(integral[k] == doctest::Approx(1.0).epsilon(2e-4));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("dispersion: a glass wedge spreads a white strip into the spectrum Snell's law predicts with the extension's index: each channel's centroid, and one place for all without dispersion") {
    // The prediction: each wavelength's column (where its refracted ray
    // meets the strip), weighted by the channel's matching function, the
    // faces' transmittance and the strip's width in columns there.
    glm::dvec3 num(0.0), den(0.0);
    double blue = 0.0, red = 0.0, weight = 0.0;
    for (double l = 360.0; l <= 830.0; l += 0.25) {
        const double px = stripColumn(dispersiveIor(kIor, kDispersion, l), weight);
        const glm::dvec3 c = wavelengthRgb(l) * weight;
        num += c * px, den += c;
        if (std::abs(l - 450.0) < 0.1) blue = px;
        if (std::abs(l - 650.0) < 0.1) red = px;
    }
    const glm::dvec3 want = num / den;
    const double plain = stripColumn(kIor, weight);
    MESSAGE("Snell: 450 nm at column " << blue << ", 650 nm at " << red << "; without dispersion " << plain);
    MESSAGE("predicted centroids " << want.x << ", " << want.y << ", " << want.z);
    const Centroids d = centroids(renderWedge("wedge.gltf", 256));
    const Centroids p = centroids(renderWedge("wedge-plain.gltf", 64));
    for (int k = 0; k < 3; ++k) {
        MESSAGE("channel " << k << ": dispersive " << d.at[k] << " +- " << d.se[k] << " (want " << want[k]
                           << "), plain " << p.at[k] << " +- " << p.se[k] << " (want " << plain << ")");
        CHECK(d.total[k] > 0.0);
        CHECK(std::abs(d.at[k] - want[k]) < 4.0 * d.se[k] + 0.05);
        CHECK(std::abs(p.at[k] - plain) < 4.0 * p.se[k] + 0.05);
        CHECK(d.se[k] < 0.3);
    }
    // Blue and red apart on the side Snell's law gives, by far more than the
    // noise; without dispersion nothing separates.
    CHECK((d.at.z - d.at.x) * (blue - red) > 0.0);
    CHECK(std::abs(d.at.z - d.at.x) > 10.0 * (d.se.x + d.se.z));
    CHECK(std::abs(p.at.z - p.at.x) < 0.1);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("dispersion: white furnace: a dispersive glass sphere vanishes in a uniform environment, in every channel") {
    // As the clear sphere of test_materials.cpp: every path through a white
    // dielectric carries the environment's 1 unchanged in expectation; here
    // each path through it also draws a wavelength, its weight 1 per channel
    // on average, and the environment upsampled to that wavelength is 1.
    Scene scene = loadWithWhiteEnvironment(sourcePath("tests/data/materials/glass-sphere.gltf"));
    for (MaterialDesc& m : scene.materials) m.dispersion = 1.0f;
    const GpuScene gpu = buildAndPack(scene);
    REQUIRE((gpu.features.bits & gpu::kFeatureDispersion) != 0u);
    RenderSettings s;
    s.width = s.height = 32;
    s.spp = 256;
    s.maxDepth = 1000;
    const RenderResult r = uploadAndRender(gpu, scene.cameras.at(0), s);
    CHECK(r.nonFinite == 0);
    const FurnaceMean m = imageMeans(r.film);
    for (int c = 0; c < 3; ++c) {
        MESSAGE("channel " << c << ": " << m.mean[c] << " +- " << m.se[c]);
        CHECK(std::abs(m.mean[c] - 1.0) < 4.0 * m.se[c] + 1e-6);
        CHECK(m.se[c] < 0.01);  // 4 errors: a loss of 4% is seen
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("dispersion: the wavefront integrator renders the wedge as the megakernel does, bit for bit") {
    // Its paths keep their wavelength between stages (PathState.misc.w).
    const RenderResult mega = renderWedge("wedge.gltf", 8);
    CHECK(sameImage(renderWedge("wedge.gltf", 8, IntegratorKind::Wavefront).film, mega.film));
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("gltf materials: KHR_materials_dispersion is read, and packed only onto a refracting dielectric" * doctest::test_suite("unit")) {
    const Scene scene = loadGltf(sourcePath("tests/data/dispersion/wedge.gltf"));
    REQUIRE(scene.materials.size() == 2);
    CHECK(scene.materials[0].dispersion == doctest::Approx(kDispersion));
    const GpuScene gpu = buildAndPack(scene);
    CHECK((gpu.materials.at(0).flags & gpu::kMaterialDispersion) != 0u);
    CHECK(gpu.materials.at(0).dispersion == doctest::Approx(kDispersion));
    CHECK((gpu.features.bits & gpu::kFeatureDispersion) != 0u);
    // Without transmission nothing refracts: no flag, no feature (no axis).
    Scene opaque = scene;
    opaque.materials[0].transmission = 0.0f;
    const GpuScene o = buildAndPack(opaque);
    CHECK((o.materials.at(0).flags & gpu::kMaterialDispersion) == 0u);
    CHECK((o.features.bits & gpu::kFeatureDispersion) == 0u);
    const Scene plain = loadGltf(sourcePath("tests/data/dispersion/wedge-plain.gltf"));
    CHECK(plain.materials[0].dispersion == 0.0f);
    CHECK((buildAndPack(plain).features.bits & gpu::kFeatureDispersion) == 0u);
}

TEST_CASE("gltf materials: bad KHR_materials_dispersion values are refused in one line, and render writes nothing" * doctest::test_suite("unit")) {
    checkBrokenFolder("dispersion/broken",
                      {{"dispersion-negative.gltf",
                        "material 0 (\"Glass\"): KHR_materials_dispersion.dispersion -0.5 is not a finite number >= 0"},
                       {"dispersion-string.gltf",
                        "material 0 (\"Glass\"): KHR_materials_dispersion.dispersion is not a number"}});
}

TEST_SUITE_END();
