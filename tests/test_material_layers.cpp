// Render tests of the layers over the glTF BSDF against closed forms, pixel
// by pixel or over the image (scenes from scripts/make_material_tests.py):
// KHR_materials_clearcoat, KHR_materials_sheen and KHR_materials_specular's
// colour in a white furnace.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>

#include <glm/glm.hpp>

#include "pack/textures.h"
#include "sheen_albedo.h"
#include "stats/stats.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

double schlick(double f0, double mu) { return f0 + (1.0 - f0) * std::pow(1.0 - mu, 5.0); }

// Renders `file` (64 x 64, 16 independent samples per pixel, maxDepth 1)
// in a uniform environment of radiance 1 and checks every pixel of channel
// c against `expected(ray, c)`, the radiance along a camera ray. A pixel
// (box filter of radius 0.5) is the mean of 16 values of expected at
// uniform points of its square, whose mean A and standard deviation S the
// test takes from 8 x 8 points: the pixel must lie within z S / 4 of A,
// z the two-sided normal quantile at level 0.01 Sidak-corrected over the
// image's values (4.9), plus 2e-5 relative and 1e-6 (float rounding).
void checkFurnacePixels(const std::string& file, const std::function<double(const glm::dvec3&, int)>& expected,
                        std::uint32_t feature) {
    const Scene scene = loadWithWhiteEnvironment(sourcePath(file));
    const GpuScene gpu = buildAndPack(scene);
    CHECK((gpu.features.bits & feature) == feature);
    RenderSettings s;
    s.width = s.height = 64;
    s.spp = 16;
    s.maxDepth = 1;
    s.sampler = gpu::kSamplerIndependent;
    const RenderResult r = uploadAndRender(gpu, scene.cameras.at(0), s);
    CHECK(r.nonFinite == 0);
    const Camera& cam = scene.cameras.at(0);
    const auto mean = r.film.mean();
    const double z = -stats::normalQuantile(0.5 * stats::sidak(0.01, std::size_t(s.width) * s.height * 3));
    int wrong = 0;
    double worstZ = 0.0, worstRel = 0.0;
    for (int py = 0; py < s.height; ++py) {
        for (int px = 0; px < s.width; ++px) {
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0, sum2 = 0.0;
                for (int j = 0; j < 8; ++j)
                    for (int i = 0; i < 8; ++i) {
                        const double v = expected(cameraRay(cam, s.width, s.height, px + (i + 0.5) / 8.0,
                                                            py + (j + 0.5) / 8.0), c);
                        sum += v;
                        sum2 += v * v;
                    }
                const double a = sum / 64.0, sd = std::sqrt(std::max(0.0, sum2 / 64.0 - a * a));
                const double m = mean[(std::size_t(py) * s.width + px) * 3 + c];
                const double err = std::abs(m - a), tol = z * sd / 4.0 + 2e-5 * a + 1e-6;
                worstZ = std::max(worstZ, err / tol);
                worstRel = std::max(worstRel, err / std::max(a, 1e-30));
                if (err > tol && ++wrong <= 5)
                    MESSAGE("pixel " << px << "," << py << " channel " << c << ": " << m << ", expected " << a
                                     << " +- " << tol);
            }
        }
    }
    MESSAGE(file << ": " << wrong << " wrong values; largest |error| / tolerance " << worstZ
                 << ", largest relative error " << worstRel);
    CHECK(wrong == 0);
    CHECK(vk::validationMessageCount() == 0);
}

// The incidence cosine of a camera ray on the plate z = 0 facing +Z.
double plateCos(const glm::dvec3& d) { return -d.z; }

}  // namespace

TEST_CASE("clearcoat: a smooth coat over a black metal in a white furnace reflects Schlick F0 0.04 at N.V, and the metal the rest") {
    // A smooth black metal (baseColor 0, metallic 1, roughness 0) reflects
    // Schlick's (1 - mu)^5; a smooth coat of factor 1 over it reflects
    // Fc = 0.04 + 0.96 (1 - mu)^5 and passes 1 - Fc to the base. Every ray
    // escapes to the environment of radiance 1, so a pixel is
    // Fc + (1 - Fc) (1 - mu)^5. Below mu = 0.75 the strategy weights equal
    // the two reflectances and every sample is that value (above it the
    // base's choice probability has a floor and single samples scatter
    // about it), so the camera sees mu in [0.3, 0.7] only.
    checkFurnacePixels("tests/data/materials/coat-black-metal.gltf", [](const glm::dvec3& d, int) {
        const double mu = plateCos(d);
        REQUIRE(mu < 0.75);
        const double fc = schlick(0.04, mu);
        return fc + (1.0 - fc) * std::pow(1.0 - mu, 5.0);
    }, gpu::kFeatureClearcoat);
}

TEST_CASE("clearcoat: a smooth coat over a base that reflects nothing shows exactly Schlick F0 0.04 at N.V") {
    // A black dielectric of specular 0 reflects nothing: the coat is the
    // only strategy and every sample is Fc(mu), seen from mu 0.34 to 0.94.
    checkFurnacePixels("tests/data/materials/coat-black.gltf",
                       [](const glm::dvec3& d, int) { return schlick(0.04, plateCos(d)); }, gpu::kFeatureClearcoat);
}

TEST_CASE("clearcoat: clearcoatTexture R scales the factor and clearcoatRoughnessTexture G the roughness") {
    // Factor 1 x R = 128/255; roughness factor 1 x G = 0: a smooth coat of
    // weight 128/255 over a base that reflects nothing.
    checkFurnacePixels("tests/data/materials/coat-textured.gltf",
                       [](const glm::dvec3& d, int) { return 128.0 / 255.0 * schlick(0.04, plateCos(d)); },
                       gpu::kFeatureClearcoat | gpu::kFeatureTextures);
}

TEST_CASE("clearcoat: clearcoatNormalTexture tilts the coat's normal: Fc at the view against the mapped normal") {
    // The texel (191, 128, 221) with scale 0.8 in the plate's tangent frame
    // (the loader's generated tangents): a coat normal about 30 degrees off
    // the plate's, which the coat's Fresnel sees (the base reflects nothing).
    const Scene scene = loadGltf(sourcePath("tests/data/materials/coat-normal-map.gltf"));
    REQUIRE(!scene.tangents.empty());
    const glm::dvec4 t(scene.tangents[0][0]);
    const glm::dvec3 n(0.0, 0.0, 1.0), tangent(t);
    const glm::dvec3 bitangent = (t.w < 0.0 ? -1.0 : 1.0) * glm::cross(n, tangent);
    glm::dvec3 m = glm::dvec3(191.0, 128.0, 221.0) / 255.0 * 2.0 - 1.0;
    m.x *= 0.8;
    m.y *= 0.8;
    const glm::dvec3 coatN = glm::normalize(m.x * tangent + m.y * bitangent + m.z * n);
    MESSAGE("coat normal " << coatN.x << ", " << coatN.y << ", " << coatN.z);
    CHECK(coatN.z < 0.9);
    checkFurnacePixels("tests/data/materials/coat-normal-map.gltf",
                       [&](const glm::dvec3& d, int) { return schlick(0.04, glm::dot(-d, coatN)); },
                       gpu::kFeatureClearcoat | gpu::kFeatureNormalMap);
}

namespace {

// scripts/make_material_tests.py: coat-lamp.gltf's lamp is [-1, 1]^2 at
// z = -2, facing +Z, radiance 1; the camera is on its front side.
double coatLampRadiance(const glm::dvec3& o, const glm::dvec3& d) {
    if (d.z >= 0.0) return -1.0;
    const glm::dvec3 p = o + ((-2.0 - o.z) / d.z) * d;
    if (std::abs(p.x) >= 1.0 || std::abs(p.y) >= 1.0) return -1.0;  // off the lamp
    return 1.0 - schlick(0.04, -d.z);
}

}  // namespace

TEST_CASE("clearcoat: an emitter under a coat shows its emission x (1 - Fc) at the view, as the extension says") {
    // Camera rays only (max depth 0): a pixel whose footprint (9 x 9 rays)
    // lies on the lamp is within the range of 1 - Schlick(0.04, mu) there
    // (every sample is that value; 2e-5 relative for float rounding), one
    // off it is exactly 0.
    const Scene scene = loadGltf(sourcePath("tests/data/materials/coat-lamp.gltf"));
    RenderSettings s;
    s.width = s.height = 48;
    s.spp = 16;
    s.maxDepth = 0;
    const RenderResult r = uploadAndRender(buildAndPack(scene), scene.cameras.at(0), s);
    const Camera& cam = scene.cameras.at(0);
    const auto mean = r.film.mean();
    int lit = 0, dark = 0, wrong = 0;
    for (int py = 0; py < s.height; ++py) {
        for (int px = 0; px < s.width; ++px) {
            double lo = 1e30, hi = -1e30;
            int on = 0;
            for (int j = 0; j <= 8; ++j)
                for (int i = 0; i <= 8; ++i) {
                    const double v = coatLampRadiance(glm::dvec3(cam.position),
                                                      cameraRay(cam, s.width, s.height, px + i / 8.0, py + j / 8.0));
                    if (v < 0.0) continue;
                    ++on;
                    lo = std::min(lo, v), hi = std::max(hi, v);
                }
            const double m = mean[(std::size_t(py) * s.width + px) * 3];
            if (on == 81) {
                ++lit;
                wrong += m < lo * (1.0 - 2e-5) || m > hi * (1.0 + 2e-5);
            } else if (on == 0) {
                ++dark;
                wrong += m != 0.0;
            }
        }
    }
    MESSAGE(lit << " pixels on the lamp, " << dark << " off it, " << wrong << " wrong");
    CHECK(lit > 100);
    CHECK(dark > 100);
    CHECK(wrong == 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("clearcoat: next-event estimation and BSDF sampling light the floor with the same coated emitter") {
    // Direct light (max depth 1) on the floor under the coated lamp, by BSDF
    // sampling alone and by light sampling alone: the two image means agree
    // within 4 standard errors, so both darken the emission alike.
    const Scene scene = loadGltf(sourcePath("tests/data/materials/coat-lamp.gltf"));
    const GpuScene gpu = buildAndPack(scene);
    RenderSettings s;
    s.width = s.height = 32;
    s.spp = 512;
    s.maxDepth = 1;
    std::vector<ImageMean> means;
    for (std::uint32_t mis : {gpu::kMisBsdf, gpu::kMisLight}) {
        s.mis = mis;
        s.seed = 20 + mis;
        means.push_back(imageMean(uploadAndRender(gpu, scene.cameras.at(0), s).film));
    }
    const double se = std::hypot(means[0].stdError, means[1].stdError);
    MESSAGE("BSDF sampling " << means[0].mean << " +- " << means[0].stdError << ", light sampling " << means[1].mean
                             << " +- " << means[1].stdError);
    CHECK(std::abs(means[0].mean - means[1].mean) < 4.0 * se);
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// scripts/make_material_tests.py: the sheen plates' table node.
constexpr int kSheenMuNode = 24, kSheenRoughnessNode = 20;
const glm::dvec3 kSheenColor(0.9, 0.6, 0.3);

// Renders `file` (16 x 16, 256 spp, maxDepth 1) in a uniform environment of
// radiance 1 and checks each channel's image mean against expected[c]
// within 4 standard errors plus `tolerance` x expected[c].
void checkFurnaceMean(const std::string& file, const glm::dvec3& expected, double tolerance) {
    const FurnaceMean f = whiteFurnaceMean(file, gpu::kFeatureSheen);
    for (int c = 0; c < 3; ++c) {
        MESSAGE(file << " channel " << c << ": " << f.mean[c] << " +- " << f.se[c] << " (expected " << expected[c] << ")");
        CHECK(std::abs(f.mean[c] - expected[c]) < tolerance * expected[c] + 4.0 * f.se[c]);
    }
    CHECK(vk::validationMessageCount() == 0);
}

double sheenNodeAlbedo() { return kSheenAlbedo[kSheenRoughnessNode * kSheenAlbedoMuCount + kSheenMuNode]; }

}  // namespace

TEST_CASE("sheen: over a black base in a white furnace, the image is sheenColor x the lobe's albedo E(mu, roughness)") {
    // A plate at a node of the albedo table (mu 0.464, roughness 0.463)
    // through a 1-degree field of view: sheenColor x E, E within the
    // table's quadrature (1e-3 relative).
    const double e = sheenNodeAlbedo();
    CHECK(e < 1.0);
    checkFurnaceMean("tests/data/materials/sheen-black.gltf", kSheenColor * e, 1e-3);
}

TEST_CASE("sheen: sheenColorTexture (sRGB) and sheenRoughnessTexture (A) scale their factors") {
    // Colour factor 1 x the sRGB texel (188, 128, 64); roughness factor
    // r x 255/128 x A = 128/255: the black plate's node again.
    const glm::dvec3 color(srgbToLinear(188.0 / 255.0), srgbToLinear(128.0 / 255.0), srgbToLinear(64.0 / 255.0));
    checkFurnaceMean("tests/data/materials/sheen-textured.gltf", color * sheenNodeAlbedo(), 1e-3);
}

TEST_CASE("sheen: over white Lambert in a white furnace the albedo scaling keeps exactly the energy: 1") {
    // The base keeps 1 - max(sheenColor) E and the sheen reflects sheenColor E:
    // 1 - 0.9 E + (0.9, 0.6, 0.3) E per channel.
    const double e = sheenNodeAlbedo();
    checkFurnaceMean("tests/data/materials/sheen-white.gltf", glm::dvec3(1.0 - 0.9 * e) + kSheenColor * e, 1e-3);
}

namespace {

// KHR_materials_specular's dielectric Fresnel of ior 1.5 with the exact
// Fresnel's shape (lib/bsdf.glsl): specular x mix(min(F0 colour, 1), 1,
// (F(mu) - F0) / (1 - F0)), F0 = 0.04.
double tintedFresnel(double specular, double color, double mu) {
    const double f0 = 0.04, w = std::clamp((fresnelDielectric(mu, 1.5) - f0) / (1.0 - f0), 0.0, 1.0);
    const double f0c = std::min(f0 * color, 1.0);
    return specular * (f0c + (1.0 - f0c) * w);
}

// scripts/make_material_tests.py
const glm::dvec3 kSpecularColor(0.5, 2.0, 30.0);
constexpr double kSpecularFactor = 0.8;

}  // namespace

TEST_CASE("specular colour: a smooth dielectric of specularColor c reflects specular x min(F0 c, 1) at normal incidence") {
    // Head-on through a 2-degree field of view, a smooth black dielectric
    // (the only strategy its reflection: every sample is the value) reflects
    // 0.8 x min(0.04 x (0.5, 2, 30), 1) = (0.016, 0.064, 0.8) at the centre;
    // off the axis the exact Fresnel's shape (mu > 0.9998: within 2e-6).
    for (int c = 0; c < 3; ++c) {
        CHECK(tintedFresnel(kSpecularFactor, kSpecularColor[c], 1.0) ==
              doctest::Approx(kSpecularFactor * std::min(0.04 * kSpecularColor[c], 1.0)));
    }
    checkFurnacePixels("tests/data/materials/specular-color-0.gltf", [](const glm::dvec3& d, int c) {
        return tintedFresnel(kSpecularFactor, kSpecularColor[c], plateCos(d));
    }, gpu::kFeatureSpecularColor);
}

TEST_CASE("specular colour: at oblique views the tinted Fresnel rises from F0 c to 1 along the exact Fresnel's shape") {
    checkFurnacePixels("tests/data/materials/specular-color-60.gltf", [](const glm::dvec3& d, int c) {
        return tintedFresnel(kSpecularFactor, kSpecularColor[c], plateCos(d));
    }, gpu::kFeatureSpecularColor);
}

TEST_CASE("specular colour: specularColorTexture (sRGB RGB) scales the colour and specularTexture (A) the factor") {
    // Colour factor 20 x the sRGB texel (255, 128, 64); specular 1 x A = 128/255.
    const glm::dvec3 color = 20.0 * glm::dvec3(1.0, srgbToLinear(128.0 / 255.0), srgbToLinear(64.0 / 255.0));
    checkFurnacePixels("tests/data/materials/specular-textured.gltf", [&](const glm::dvec3& d, int c) {
        return tintedFresnel(128.0 / 255.0, color[c], plateCos(d));
    }, gpu::kFeatureSpecularColor | gpu::kFeatureTextures);
}

namespace {

// KHR_materials_iridescence's thin-film reflectance (lib/thin_film.glsl,
// thinFilmFresnel) in double: air | film of index n2 and thickness d nm |
// a base of normal-incidence reflectance f0, at cosine mu, channel c.
double filmSchlick(double f0, double mu) { return f0 + (1.0 - f0) * std::pow(1.0 - mu, 5.0); }

glm::dvec3 filmSpectral(double opd, glm::dvec3 shift) {
    const double pi = 3.14159265358979323846, phase = 2.0 * pi * opd * 1e-9;
    const glm::dvec3 amp(5.4856e-13, 4.4201e-13, 5.2481e-13), centre(1.6810e6, 1.7953e6, 2.2084e6),
        var(4.3278e9, 9.3046e9, 6.6121e9);
    glm::dvec3 xyz;
    for (int k = 0; k < 3; ++k)
        xyz[k] = amp[k] * std::sqrt(2.0 * pi * var[k]) * std::cos(centre[k] * phase + shift[k]) *
                 std::exp(-phase * phase * var[k]);
    xyz.x += 9.7470e-14 * std::sqrt(2.0 * pi * 4.5282e9) * std::cos(2.2399e6 * phase + shift.x) *
             std::exp(-4.5282e9 * phase * phase);
    xyz /= 1.0685e-7;
    return {3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
            -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
            0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z};
}

double thinFilm(double n2, double mu, double d, glm::dvec3 f0, int c) {
    const double pi = 3.14159265358979323846;
    const double cosT = std::sqrt(std::max(0.0, 1.0 - (1.0 - mu * mu) / (n2 * n2)));
    const double r12 = filmSchlick((n2 - 1.0) * (n2 - 1.0) / ((n2 + 1.0) * (n2 + 1.0)), mu), t121 = 1.0 - r12;
    glm::dvec3 r23, phi;
    for (int k = 0; k < 3; ++k) {
        const double s = std::sqrt(std::clamp(f0[k], 0.0, 0.9999)), n3 = (1.0 + s) / (1.0 - s);
        r23[k] = filmSchlick((n3 - n2) * (n3 - n2) / ((n3 + n2) * (n3 + n2)), cosT);
        phi[k] = pi + (n3 < n2 ? pi : 0.0);
    }
    const double opd = 2.0 * n2 * d * cosT;
    double result = 0.0;
    const double r123 = std::clamp(r12 * r23[c], 1e-5, 0.9999), rs = t121 * t121 * r23[c] / (1.0 - r123);
    result = r12 + rs;
    double cm = rs - t121;
    for (int m = 1; m <= 2; ++m) {
        cm *= std::sqrt(r123);
        result += cm * 2.0 * filmSpectral(m * opd, double(m) * phi)[c];
    }
    return std::max(result, 0.0);
}

// A film's exact head-on reflectance in linear Rec. 709, independent of
// the model: per wavelength the Airy sum of the two interfaces' exact
// amplitudes, |r12 + r23 e^(2i delta)|^2 / |1 + r12 r23 e^(2i delta)|^2 with
// delta = 2 pi n2 d / lambda, integrated over 380-780 nm against the CIE
// 1931 matching functions (the multi-lobe Gaussian fits of Wyman, Sloan &
// Shirley 2013), normalised by the integral of y-bar.
glm::dvec3 exactFilmRgb(double n2, double n3, double d) {
    auto lobe = [](double l, double mu, double s1, double s2) {
        const double s = l < mu ? s1 : s2;
        return std::exp(-(l - mu) * (l - mu) / (2.0 * s * s));
    };
    const double pi = 3.14159265358979323846, r12 = (1.0 - n2) / (1.0 + n2), r23 = (n2 - n3) / (n2 + n3);
    glm::dvec3 xyz(0.0);
    double norm = 0.0;
    for (int l = 380; l <= 780; ++l) {
        const double xbar = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
                            0.065 * lobe(l, 501.1, 20.4, 26.2);
        const double ybar = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
        const double zbar = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
        const std::complex<double> e = std::polar(1.0, 4.0 * pi * n2 * d / l);
        const double r = std::norm((r12 + r23 * e) / (1.0 + r12 * r23 * e));
        xyz += r * glm::dvec3(xbar, ybar, zbar);
        norm += ybar;
    }
    xyz /= norm;
    return {3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
            -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
            0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z};
}

// scripts/make_material_tests.py
constexpr double kFilmIor = 1.3, kFilmDielectricThickness = 400.0, kFilmMetalThickness = 250.0;
const glm::dvec3 kFilmMetalColor(0.9, 0.6, 0.3);

}  // namespace

TEST_CASE("iridescence: a smooth black dielectric under a film reflects the thin film's Fresnel, head-on and at 60 degrees") {
    // F0 of ior 1.5 under 400 nm of index 1.3. Without interference (the
    // orders' mean) head-on the film would reflect about 0.043; the
    // interference colours it: the channels differ.
    const glm::dvec3 f0(0.04);
    auto expected = [&](const glm::dvec3& d, int c) { return thinFilm(kFilmIor, plateCos(d), kFilmDielectricThickness, f0, c); };
    // The model against the exact film: its luminance within 3% at 100,
    // 250 and 400 nm (measured: 0.2%, 0.7%, 1.2%), and at 250 and 400 nm,
    // where the film is coloured, the same dominant channel. The channels
    // themselves differ by up to 0.005 (the two fits of the matching
    // functions; most at 100 nm, where the film reflects 0.4%).
    auto lum = [](const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
    auto largest = [](const glm::dvec3& c) { return c.x >= c.y && c.x >= c.z ? 0 : (c.y >= c.z ? 1 : 2); };
    for (const double d : {100.0, 250.0, 400.0}) {
        const glm::dvec3 exact = exactFilmRgb(kFilmIor, 1.5, d);
        const glm::dvec3 model(thinFilm(kFilmIor, 1.0, d, f0, 0), thinFilm(kFilmIor, 1.0, d, f0, 1),
                               thinFilm(kFilmIor, 1.0, d, f0, 2));
        CAPTURE(d);
        CHECK(lum(model) == doctest::Approx(lum(exact)).epsilon(0.03));
        if (d > 200.0) CHECK(largest(model) == largest(exact));
    }
    checkFurnacePixels("tests/data/materials/iridescence-0.gltf", expected, gpu::kFeatureIridescence);
    checkFurnacePixels("tests/data/materials/iridescence-60.gltf", expected, gpu::kFeatureIridescence);
}

TEST_CASE("iridescence: a smooth metal under a film reflects the film over its base colour") {
    checkFurnacePixels("tests/data/materials/iridescence-metal.gltf", [&](const glm::dvec3& d, int c) {
        return thinFilm(kFilmIor, plateCos(d), kFilmMetalThickness, kFilmMetalColor, c);
    }, gpu::kFeatureIridescence);
}

TEST_SUITE_END();
