// Motion blur from glTF animations (--shutter, --animation; host/scene/
// gltf_motion, lib/motion.glsl, lib/camera.glsl) against known answers on
// tests/data/motion (tests/data/make_motion.py): unlit white shapes on black,
// so a pixel's value is the fraction of the shutter (and of its footprint)
// that the shape covers it.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

#include "cli_util.h"
#include "image/image_io.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

namespace {

struct Shot {
    int width = 0, height = 0;
    std::vector<float> mean;  // rgb per pixel
    double g(int x, int y) const { return mean[(std::size_t(y) * width + x) * 3 + 1]; }
};

Shot render(const std::string& file, int width, int height, std::uint32_t spp, bool shutter, double open,
            double close, const std::string& animation = "") {
    LoadOptions load;
    load.motion = {shutter, animation, open, close};
    const Scene scene = loadGltf(sourcePath("tests/data/motion/" + file), load);
    RenderSettings s;
    s.width = width;
    s.height = height;
    s.spp = spp;
    s.shutter = shutter;
    s.shutterOpen = open;
    s.shutterClose = close;
    s.animation = animation;
    const RenderResult r = renderScene(scene, s);
    return {width, height, r.film.mean()};
}

// quad.gltf's 64x16 image spans x in [-1, 1] at the quad's depth: column i
// covers [-1 + i/32, -1 + (i+1)/32]. The mean over a column's footprint of
// `coverage` (a function of x), by the midpoint rule on 4096 steps.
double columnMean(int i, const std::function<double(double)>& coverage) {
    constexpr int kSteps = 4096;
    double sum = 0.0;
    for (int k = 0; k < kSteps; ++k) sum += coverage(-1.0 + (i + (k + 0.5) / kSteps) / 32.0);
    return sum / kSteps;
}

// The quad (half width 0.25) sliding from x = -0.5 to 0.5 over the whole
// shutter covers x for the fraction of it when |x - c| < 0.25: a trapezoid.
double slideCoverage(double x) { return std::max(0.0, std::min(1.0, x + 0.75) - std::max(0.0, x + 0.25)); }

// Each column's mean over its 16 rows against `expected`, within 5 standard
// errors of a Bernoulli mean of spp x 16 samples (plus 1e-4 for the
// quadrature).
void checkColumns(const Shot& shot, std::uint32_t spp, const std::function<double(int)>& expected) {
    for (int i = 0; i < shot.width; ++i) {
        double m = 0.0;
        for (int y = 0; y < shot.height; ++y) m += shot.g(i, y);
        m /= shot.height;
        const double e = expected(i);
        const double sigma = std::sqrt(std::max(e * (1.0 - e), 1e-4) / (double(spp) * shot.height));
        CAPTURE(i);
        CAPTURE(m);
        CAPTURE(e);
        CHECK(std::abs(m - e) <= 5.0 * sigma + 1e-4);
    }
}

// Every pixel is 0 or 1: the quad is sharp, and covers exactly [lo, hi).
void checkSharp(const Shot& shot, double lo, double hi) {
    for (int i = 0; i < shot.width; ++i) {
        const double x = -1.0 + (i + 0.5) / 32.0;
        const double e = x > lo && x < hi ? 1.0 : 0.0;
        for (int y = 0; y < shot.height; ++y) {
            CAPTURE(i);
            CHECK(shot.g(i, y) == doctest::Approx(e).epsilon(1e-6));
        }
    }
}

}  // namespace

TEST_SUITE_BEGIN("render");

TEST_CASE("motion: a quad translating at constant speed gives the exact time-averaged trapezoid, the camera panning "
          "the other way the same" * doctest::test_suite("slow")) {
    constexpr std::uint32_t kSpp = 256;
    const Shot slide = render("quad.gltf", 64, 16, kSpp, true, 0.0, 1.0, "slide");
    checkColumns(slide, kSpp, [](int i) { return columnMean(i, slideCoverage); });
    const Shot pan = render("quad.gltf", 64, 16, kSpp, true, 0.0, 1.0, "pan");
    checkColumns(pan, kSpp, [](int i) { return columnMean(i, slideCoverage); });
    // Half the shutter: the quad moves from x = -0.5 to 0 (centre), a narrower trapezoid.
    const Shot half = render("quad.gltf", 64, 16, kSpp, true, 0.0, 0.5, "slide");
    checkColumns(half, kSpp, [](int i) {
        return columnMean(i, [](double x) {
            return 2.0 * std::max(0.0, std::min(0.5, x + 0.75) - std::max(0.0, x + 0.25));
        });
    });
}

TEST_CASE("motion: an emitting quad sliding at constant speed gives the same exact trapezoid" *
          doctest::test_suite("slow")) {
    constexpr std::uint32_t kSpp = 256;
    const Shot slide = render("glow.gltf", 64, 16, kSpp, true, 0.0, 1.0, "slide");
    checkColumns(slide, kSpp, [](int i) { return columnMean(i, slideCoverage); });
}

namespace {

// Lambert's formula: the irradiance at p (normal n) from a uniform
// polygon of radiance 1 seen from its emitting side, 1/2 sum over its edges
// of the angle the edge subtends times the cosine of its plane with n.
double polygonIrradiance(const glm::dvec3& p, const glm::dvec3& n, const std::vector<glm::dvec3>& polygon) {
    double sum = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec3 a = glm::normalize(polygon[i] - p), b = glm::normalize(polygon[(i + 1) % polygon.size()] - p);
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
    }
    return 0.5 * std::abs(sum);
}

}  // namespace

// lamp-plane.gltf at max depth 1 (next-event estimation and the BSDF's hits
// on the lamp, weighed by MIS): the plane's radiance is 0.5 / pi times the
// lamp's irradiance averaged over the shutter, the lamp (x in [c - 0.5,
// c + 0.5], z in [-0.5, 0.5] at y = 0.5) sliding c from -1 to 1: 256 times,
// midpoint rule, and 4 x 4 points of each pixel. Pixels whose view passes
// near the lamp's sweep (it hides the plane) are left out. Tolerances as
// the lights' known answers (checkPixels); both light samplers.
TEST_CASE("motion: a sliding lamp lights a plane with its irradiance averaged over the shutter (NEE and MIS at the "
          "path's time)" * doctest::test_suite("slow")) {
    LoadOptions load;
    load.motion = {true, "slide", 0.0, 1.0};
    const Scene scene = loadGltf(sourcePath("tests/data/motion/lamp-plane.gltf"), load);
    constexpr int kSize = 32, kSub = 4, kTimes = 256;
    const CameraRays rays(scene.cameras.at(0), kSize, kSize);
    auto onPlane = [&](double sx, double sy) {
        const glm::dvec3 d = rays.dir(sx, sy);
        return rays.origin + (-rays.origin.y / d.y) * d;
    };
    std::vector<double> expected(kSize * kSize), atOpen(kSize * kSize);
    std::vector<char> mask(kSize * kSize, 0);
    auto lampAt = [](double c) {
        return std::vector<glm::dvec3>{{c - 0.5, 0.5, -0.5}, {c + 0.5, 0.5, -0.5}, {c + 0.5, 0.5, 0.5},
                                       {c - 0.5, 0.5, 0.5}};
    };
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const std::size_t i = std::size_t(py) * kSize + px;
            double sum = 0.0, open = 0.0, zLo = 1e30, zHi = -1e30;
            for (int j = 0; j < kSub; ++j)
                for (int k = 0; k < kSub; ++k) {
                    const glm::dvec3 p = onPlane(px + (k + 0.5) / kSub, py + (j + 0.5) / kSub);
                    for (int t = 0; t < kTimes; ++t)
                        sum += polygonIrradiance(p, {0, 1, 0}, lampAt(-1.0 + 2.0 * (t + 0.5) / kTimes));
                    open += polygonIrradiance(p, {0, 1, 0}, lampAt(-1.0));
                }
            for (int c = 0; c < 4; ++c) {  // the view of the pixel's corners at the lamp's height, y = 0.5
                const double z = 0.9 * onPlane(px + (c & 1), py + (c >> 1)).z;
                zLo = std::min(zLo, z), zHi = std::max(zHi, z);
            }
            expected[i] = 0.5 / M_PI * sum / (kSub * kSub * kTimes);
            atOpen[i] = 0.5 / M_PI * open / (kSub * kSub);
            mask[i] = zLo > 0.55 || zHi < -0.55;
        }
    std::size_t pixels = 0;
    for (char m : mask) pixels += m;
    REQUIRE(pixels >= 500);
    for (LightSampler sampler : {LightSampler::Power, LightSampler::Tree}) {
        RenderSettings s;
        s.width = s.height = kSize;
        s.spp = 256;
        s.maxDepth = 1;
        s.shutter = true;
        s.shutterOpen = 0.0;
        s.shutterClose = 1.0;
        s.animation = "slide";
        s.lightSampler = sampler;
        const Rendered rendered = renderFile("tests/data/motion/lamp-plane.gltf", s);
        const RenderResult& r = rendered.result;
        CHECK((rendered.gpu.features.bits & gpu::kFeatureInstancedEmitters) != 0u);
        CHECK(((rendered.gpu.features.bits & gpu::kFeatureLightTree) != 0u) == (sampler == LightSampler::Tree));
        CAPTURE(int(sampler));
        report("the plane under the sliding lamp", checkPixels(r, expected, mask));
        // The test can fail: the lamp held at the open is far off.
        CHECK_FALSE(checkPixels(r, atOpen, mask).mean.passed);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("motion: the rest pose and the pose at T render sharp and in place, a zero-length shutter with no NaN") {
    checkSharp(render("quad.gltf", 64, 16, 16, false, 0.0, 0.0), -0.25, 0.25);  // the node's static translation
    checkSharp(render("quad.gltf", 64, 16, 16, true, 0.25, 0.25, "slide"), -0.5, 0.0);
    checkSharp(render("quad.gltf", 64, 16, 16, true, 1.5, 1.5, "slide"), 0.25, 0.75);  // after the last key: held
    checkSharp(render("quad.gltf", 64, 16, 16, true, 0.5, 0.5, "pan"), -0.25, 0.25);
}

TEST_CASE("motion: a STEP sampler renders two sharp copies weighted by their time") {
    // At x = -0.5 for t < 0.25, at 0.5 after: 1/4 and 3/4 of the shutter.
    const Shot step = render("quad.gltf", 64, 16, 64, true, 0.0, 1.0, "step");
    for (int i = 0; i < 64; ++i) {
        const double x = -1.0 + (i + 0.5) / 32.0;
        const double e = std::abs(x + 0.5) < 0.25 ? 0.25 : std::abs(x - 0.5) < 0.25 ? 0.75 : 0.0;
        double m = 0.0, lo = 1.0, hi = 0.0;
        for (int y = 0; y < 16; ++y) m += step.g(i, y), lo = std::min(lo, step.g(i, y)), hi = std::max(hi, step.g(i, y));
        m /= 16.0;
        CAPTURE(i);
        CHECK(std::abs(m - e) <= 5.0 * std::sqrt(std::max(e * (1 - e), 1e-4) / (64.0 * 16)) + 1e-4);
        if (e == 0.0) CHECK(hi == 0.0);  // nothing between or beside the copies
    }
}

TEST_CASE("motion: a bar rotating about its centre gives the exact time-averaged angular coverage" * doctest::test_suite("slow")) {
    constexpr int kSize = 32;
    constexpr std::uint32_t kSpp = 256;
    const Shot spin = render("bar.gltf", kSize, kSize, kSpp, true, 0.0, 1.0, "spin");
    // The expected value of each pixel: the bar (|x'| < 0.8, |y'| < 0.05 in
    // its own frame, turned by 90 degrees x t) averaged over 16x16 points of
    // the pixel and 256 times, midpoint rule.
    double sumImage = 0.0, worst = 0.0;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            double e = 0.0;
            constexpr int kSub = 16, kTimes = 256;
            for (int k = 0; k < kTimes; ++k) {
                const double a = 0.5 * M_PI * (k + 0.5) / kTimes, c = std::cos(a), s = std::sin(a);
                for (int j = 0; j < kSub * kSub; ++j) {
                    const double x = -1.0 + 2.0 * (px + (j % kSub + 0.5) / kSub) / kSize;
                    const double y = 1.0 - 2.0 * (py + (j / kSub + 0.5) / kSub) / kSize;
                    e += (std::abs(c * x + s * y) < 0.8 && std::abs(-s * x + c * y) < 0.05) ? 1.0 : 0.0;
                }
            }
            e /= kTimes * kSub * kSub;
            const double g = spin.g(px, py);
            sumImage += g;
            const double sigma = std::sqrt(std::max(e * (1.0 - e), 1e-3) / kSpp);
            worst = std::max(worst, std::abs(g - e) / (5.0 * sigma + 0.01));
        }
    CAPTURE(worst);
    CHECK(worst <= 1.0);
    // The bar's area (1.6 x 0.1) in pixels, whatever its motion.
    CHECK(sumImage == doctest::Approx(1.6 * 0.1 / (2.0 / kSize * 2.0 / kSize)).epsilon(0.01));
}

TEST_CASE("motion: --frames renders one numbered file per frame, each the image --shutter gives for its time, moving "
          "placements, cameras and emitters alike") {
    TempDir out;
    const std::string scene = sourcePath("tests/data/motion/quad.gltf");
    const std::string common = " --animation slide --spp 4 --width 64 --height 16 --quiet";
    // Frames 0, 2, 4 at 8 fps with a half-frame shutter: [f/8, f/8 + 1/16].
    Run r = run("render " + scene + common + " --frames 0:4:2 --fps 8 --shutter-angle 180 -o " + out / "q_##.exr");
    REQUIRE(r.status == 0);
    for (const char* f : {"q_00.exr", "q_02.exr", "q_04.exr"}) CHECK(std::filesystem::exists(out / f));
    CHECK(!std::filesystem::exists(out / "q_01.exr"));
    r = run("render " + scene + common + " --shutter 0.25,0.3125 -o " + out / "t.exr");
    REQUIRE(r.status == 0);
    CHECK(readRgb(out / "q_02.exr").rgb == readRgb(out / "t.exr").rgb);
    CHECK(readRgb(out / "q_02.exr").rgb != readRgb(out / "q_04.exr").rgb);
    // The camera posed again for a later frame (no blur): as loaded at that time.
    const std::string pan = " --animation pan --spp 4 --width 64 --height 16 --quiet";
    REQUIRE(run("render " + scene + pan + " --frames 0:4:4 --fps 8 -o " + out / "p_#.exr").status == 0);
    REQUIRE(run("render " + scene + pan + " --shutter 0.5,0.5 -o " + out / "p.exr").status == 0);
    CHECK(readRgb(out / "p_4.exr").rgb == readRgb(out / "p.exr").rgb);
    CHECK(readRgb(out / "p_0.exr").rgb != readRgb(out / "p.exr").rgb);
    // A moving emitter: each frame is loaded anew (its lights are placed when packed).
    const std::string lamp = " --animation lamp --spp 4 --width 64 --height 16 --quiet";
    REQUIRE(run("render " + scene + lamp + " --frames 0:8:8 --fps 8 -o " + out / "l_#.exr").status == 0);
    REQUIRE(run("render " + scene + lamp + " --shutter 1,1 -o " + out / "l.exr").status == 0);
    CHECK(readRgb(out / "l_8.exr").rgb == readRgb(out / "l.exr").rgb);
    CHECK(readRgb(out / "l_0.exr").rgb != readRgb(out / "l.exr").rgb);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("unit");

TEST_CASE("motion: a moving lamp's triangles are lights of its own copy, stored by its placement's record") {
    LoadOptions load;
    load.motion = {true, "slide", 0.0, 1.0};
    const Scene scene = loadGltf(sourcePath("tests/data/motion/lamp-plane.gltf"), load);
    REQUIRE(scene.instances.size() == 1);
    REQUIRE(scene.sharedMeshes.size() == 1);
    CHECK(scene.sharedMeshes[0].lights);
    const GpuScene gpu = buildAndPack(scene);
    CHECK((gpu.features.bits & gpu::kFeatureInstancedEmitters) != 0u);
    REQUIRE(gpu.emitters.size() == 2);
    for (const gpu::Emitter& e : gpu.emitters) {
        CHECK((e.flags & gpu::kEmitterInstanced) != 0u);
        // The record of the lamp's placement: the one with motion keys (open, close).
        const std::uint32_t record = std::bit_cast<std::uint32_t>(e.v0.x);
        REQUIRE(record + gpu::kInstanceTexels <= gpu.instances.size());
        CHECK(gpu.instances[record + gpu::kInstanceWordMotionCount / gpu::kTexelWords]
                           [gpu::kInstanceWordMotionCount % gpu::kTexelWords] == 2u);
        CHECK(e.area == 0.0f);
        CHECK(gpu.shading.at(e.triangle).light != gpu::kNoLight);
    }
    // Weighed by its area at the open (0.5 each), as a still lamp.
    CHECK(gpu.totalPower == doctest::Approx(1.0 * M_PI));
    // Without a shutter it stays a still, flattened lamp as before.
    const GpuScene still = buildAndPack(loadGltf(sourcePath("tests/data/motion/lamp-plane.gltf")));
    CHECK((still.features.bits & gpu::kFeatureInstancedEmitters) == 0u);
    for (const gpu::Emitter& e : still.emitters) CHECK((e.flags & gpu::kEmitterInstanced) == 0u);
}

TEST_CASE("motion: a moving placement is instanced with keys at the shutter's ends, a static one is not") {
    LoadOptions load;
    load.motion = {true, "slide", 0.0, 1.0};
    const Scene slide = loadGltf(sourcePath("tests/data/motion/quad.gltf"), load);
    REQUIRE(slide.instances.size() == 1);
    REQUIRE(slide.instances[0].motion.size() == 2);
    CHECK(slide.instances[0].motion[0].translation.x == -0.5f);
    CHECK(slide.instances[0].motion[1].translation.x == 0.5f);
    CHECK(slide.instances[0].motion[1].time == 1.0f);
    CHECK(slide.cameras.at(0).motion.empty());
    load.motion = {true, "step", 0.0, 1.0};
    const Scene step = loadGltf(sourcePath("tests/data/motion/quad.gltf"), load);
    REQUIRE(step.instances.size() == 1);
    // open, the pose before the jump at 0.25, the pose after it, close.
    REQUIRE(step.instances[0].motion.size() == 4);
    CHECK(step.instances[0].motion[1].time == 0.25f);
    CHECK(step.instances[0].motion[1].translation.x == -0.5f);
    CHECK(step.instances[0].motion[2].translation.x == 0.5f);
    load.motion = {true, "pan", 0.0, 1.0};
    const Scene pan = loadGltf(sourcePath("tests/data/motion/quad.gltf"), load);
    CHECK(pan.instances.empty());
    CHECK(pan.cameras.at(0).motion.size() == 2);
    load.motion = {true, "slide", 0.25, 0.25};  // a pose, no motion
    CHECK(loadGltf(sourcePath("tests/data/motion/quad.gltf"), load).instances.empty());
}

TEST_CASE("motion: a shutter with CLOSE before OPEN, --animation without --shutter, an unknown animation, the "
          "wavefront integrator, --frames with --shutter or an output without '#', --fps or --shutter-angle "
          "without --frames, an angle past 360 or LAST before FIRST is one error line, exit 2, no output") {
    const std::string scene = sourcePath("tests/data/motion/quad.gltf");
    const std::pair<const char*, std::string> cases[] = {
        {"--shutter 1,0", "strata: error: --shutter: CLOSE must not precede OPEN"},
        {"--shutter 1", "strata: error: --shutter takes OPEN,CLOSE"},
        {"--animation slide", "strata: error: --animation needs --shutter"},
        {"--shutter 0,1 --animation walk", scene + ": error: "},
        {"--shutter 0,1 --animation 7", scene + ": error: "},
        {"--shutter 0,1 --integrator wavefront",
         "strata: error: --lens-radius and a --shutter interval need the megakernel integrator"},
        {"--frames 0:2 --shutter 0,1", "strata: error: --frames sets each frame's shutter"},
        {"--frames 0:2", "strata: error: with --frames each output names its frame"},
        {"--fps 24", "strata: error: --fps needs --frames"},
        {"--shutter-angle 90", "strata: error: --shutter-angle needs --frames"},
        {"--frames 0:2 --shutter-angle 400", "strata: error: --shutter-angle must be in"},
        {"--frames 5:2", "strata: error: --frames: LAST must not precede FIRST"},
    };
    for (const auto& [flags, prefix] : cases) expectError("render " + scene + " " + flags, prefix);
}

TEST_CASE("motion: an animation channel targeting a missing node, key times not increasing or a rotation key of "
          "zero length is one error line naming the file, exit 2, no output") {
    for (const auto& [file, what] : {std::pair<std::string, std::string>{"bad-target", "target node 99 does not exist"},
                                     {"bad-times", "is not greater than key 1"},
                                     {"bad-quaternion", "rotation key 1 has length 0"}}) {
        const std::string scene = sourcePath("tests/data/motion/" + file + ".gltf");
        expectError("render " + scene + " --shutter 0,1", scene + ": error: ");
        TempDir out;
        const Run r = run("render " + scene + " --shutter 0,1 --quiet -o " + out / "a.exr");
        CAPTURE(r.output);
        CHECK(r.output.find(what) != std::string::npos);
    }
}

TEST_SUITE_END();
