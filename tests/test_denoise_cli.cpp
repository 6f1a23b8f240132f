// The denoiser on renders (render --denoise, strata denoise, the AOVs it
// reads): its error against stored references (tests/data/denoise/, made by
// tests/data/denoise/README.md's commands), the same bits from a file as
// from a render, and bad input.
#include <doctest/doctest.h>

#include <cmath>

#include "cli_util.h"
#include "denoise/command.h"
#include "image/aov.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

namespace {

struct Errors {
    double raw = 0.0, nfor = 0.0, fast = 0.0;
};

// Renders `scene` at the reference's size with AOVs and compares the raw
// and both denoised images with the reference (relMSE, eps 0.01).
Errors denoisedErrors(const std::string& scene, const std::string& reference, std::uint32_t spp) {
    const RgbImage ref = readReference(sourcePath(reference));
    RenderSettings s;
    s.width = ref.width;
    s.height = ref.height;
    s.spp = spp;
    s.aov = true;
    const Rendered r = renderFile(scene, s);
    const AovImages aov = aovImages(r.result.film);
    const DenoiseResult nfor = denoise(context(), denoiseInput(aov), DenoiseMethod::Nfor);
    const DenoiseResult fast = denoise(context(), denoiseInput(aov), DenoiseMethod::Fast);
    const std::size_t n = aov.color.size();
    MESSAGE(scene << " relMSE raw " << compareImages(aov.color.data(), ref.rgb.data(), n).relMse << ", nfor "
                  << compareImages(nfor.rgb.data(), ref.rgb.data(), n).relMse << ", fast "
                  << compareImages(fast.rgb.data(), ref.rgb.data(), n).relMse);
    return {compareImages(aov.color.data(), ref.rgb.data(), n).relMse,
            compareImages(nfor.rgb.data(), ref.rgb.data(), n).relMse,
            compareImages(fast.rgb.data(), ref.rgb.data(), n).relMse};
}

}  // namespace

TEST_SUITE_BEGIN("render");

// At 64x64 a window holds a larger share of the box's edges than at the
// 256x256 of the benchmarks (12.6x and 6.6x there): measured 4.4x and 1.9x.
TEST_CASE("denoise: on the Cornell box at 64x64 and 16 spp the regression cuts relMSE against a stored reference "
          "by 3x or more, the a-trous filter by 1.4x or more") {
    const Errors e = denoisedErrors("scenes/cornell-box.gltf", "tests/data/denoise/cornell-64.exr", 16);
    CAPTURE(e.raw);
    CAPTURE(e.nfor);
    CAPTURE(e.fast);
    CHECK(e.nfor * 3.0 < e.raw);
    CHECK(e.fast * 1.4 < e.raw);
}

TEST_CASE("denoise: on the textured materials board at 16 spp neither method is worse than the raw image") {
    const Errors e = denoisedErrors("scenes/materials-board.gltf", "tests/data/denoise/board-64.exr", 16);
    CAPTURE(e.raw);
    CAPTURE(e.nfor);
    CAPTURE(e.fast);
    CHECK(e.nfor < e.raw);
    CHECK(e.fast < e.raw);
}

TEST_CASE("denoise: 'strata denoise' on a stored --aov EXR gives the bits of 'render --denoise', every time" * doctest::test_suite("slow")) {
    TempDir out;
    const std::string scene = sourcePath("scenes/cornell-box.gltf");
    const std::string common = " --spp 4 --width 24 --height 16 --quiet";
    for (const char* method : {"nfor", "fast"}) {
        CAPTURE(method);
        REQUIRE(run("render " + scene + common + " --aov -o " + out / "aov.exr").status == 0);
        REQUIRE(run("render " + scene + common + " --denoise " + method + " -o " + out / "render.exr").status == 0);
        REQUIRE(run("denoise " + out / "aov.exr" + " --method " + method + " --quiet -o " + out / "d1.exr -o " +
                    out / "d1.png").status == 0);
        REQUIRE(run("denoise " + out / "d1.exr" + " --method " + method + " --quiet -o " + out / "d2.exr").status ==
                0);
        const RgbImage fromRender = readRgb(out / "render.exr"), fromFile = readRgb(out / "d1.exr"),
                       again = readRgb(out / "d2.exr"), noisy = readRgb(out / "aov.exr");
        CHECK(fromFile.rgb == fromRender.rgb);
        CHECK(again.rgb == fromFile.rgb);  // d1.exr's noisy.R/G/B is what it denoises
        CHECK(fromFile.rgb != noisy.rgb);
        // The render's noisy layer is the image as rendered.
        const AovImages kept = readAovImages(out / "render.exr");
        CHECK(kept.color == noisy.rgb);
    }
}

TEST_CASE("denoise: an EXR without the AOV layers, an image that is not one, or a NaN in a layer is one error "
          "line, exit 2, no file") {
    TempDir out;
    const std::string scene = sourcePath("scenes/cornell-box.gltf");
    REQUIRE(run("render " + scene + " --spp 1 --width 8 --height 8 --quiet -o " + out / "plain.exr -o " +
                out / "plain.png").status == 0);
    auto refused = [&](const std::string& input, const std::string& message) {
        TempDir dst;
        const Run r = run("denoise " + input + " -o " + dst / "d.exr -o " + dst / "d.png");
        CAPTURE(r.output);
        CHECK(r.status == 2);
        CHECK(lines(r.output) == 1);
        CHECK(r.output.rfind(input + ": error: ", 0) == 0);
        CHECK(r.output.find(message) != std::string::npos);
        CHECK(dst.empty());
    };
    refused(out / "plain.exr", "no variance layer");
    refused(out / "plain.png", "no variance layer");
    refused(out / "missing.exr", "error");
    // A layer with a NaN.
    REQUIRE(run("render " + scene + " --spp 2 --width 8 --height 8 --aov --quiet -o " + out / "aov.exr").status == 0);
    AovImages a = readAovImages(out / "aov.exr");
    a.depth[5] = std::nanf("");
    writeImages({out / "nan.exr"}, a.width, a.height, a.color, aovChannels(a));
    refused(out / "nan.exr", "channel depth.Z is NaN at pixel (5, 0)");
    // --denoise needs the megakernel (refused while parsing).
    expectError("render " + scene + " --denoise --integrator wavefront",
                "strata: error: --denoise needs the megakernel integrator");
}

TEST_SUITE_END();
