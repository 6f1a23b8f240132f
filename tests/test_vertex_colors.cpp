// COLOR_0 vertex colours (glTF 2.0 3.7.2.1: they multiply baseColor, rgb and
// alpha): the loader's decoding of each storage, and known answers on the
// device: an unlit quad whose COLOR_0 is an affine function of the point
// shows baseColor times that function at every pixel centre, and under
// alphaMode MASK the colour's alpha cuts the hole. Data:
// tests/data/make_geometry.py (vertex_colors; QUAD_COLOR mirrored below).
#include <doctest/doctest.h>

#include <cmath>

#include "gltf_util.h"
#include "pack/gpu_scene.h"
#include "render/sampler_kind.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

namespace {

const LoadOptions kNoLights{false, false};

Scene loadGeometry(const std::string& name) { return loadGltf(dataPath("geometry/" + name), kNoLights); }

// make_geometry.py's quad_color: COLOR_0 at the point (x, y, 0) of the quad.
glm::dvec4 quadColor(double x, double y) {
    return {0.2 + 0.05 * (x + 4), 0.3 + 0.06 * (y + 3), 0.9 - 0.04 * (x + 4) - 0.03 * (y + 3), (x + 4) / 9};
}

// The point of the plane z = 0 that the camera ray through the centre of
// pixel (px, py) reaches (host/render/renderer.cpp's frame, lib/film.glsl's
// cameraRay), in double.
glm::dvec2 pixelOnPlane(const Camera& cam, int width, int height, int px, int py) {
    const glm::dvec3 forward(cam.forward), right = glm::normalize(glm::cross(forward, glm::dvec3(cam.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tanHalf = std::tan(0.5 * double(cam.yfov)), aspect = double(width) / height;
    const double nx = 2.0 * (px + 0.5) / width - 1.0, ny = 1.0 - 2.0 * (py + 0.5) / height;
    const glm::dvec3 dir = forward + nx * tanHalf * aspect * right + ny * tanHalf * up;
    const glm::dvec3 origin(cam.position);
    const glm::dvec3 p = origin - origin.z / dir.z * dir;
    return {p.x, p.y};
}

// One sample per pixel at its centre: the regular sampler's single cell,
// the box filter's middle.
RenderSettings centreSamples() {
    RenderSettings s;
    s.width = 24;
    s.height = 20;
    s.spp = 1;
    s.sampler = gpu::kSamplerRegular;
    s.maxDepth = 2;
    return s;
}

}  // namespace

TEST_CASE("vertex colours: COLOR_0 of every storage decodes to linear RGBA, white where a primitive has none" *
          doctest::test_suite("unit")) {
    const Scene scene = loadGeometry("colors.gltf");
    REQUIRE(scene.triangles.size() == 6);
    REQUIRE(scene.colors.size() == 6);
    // make_geometry.py's COLORS, by glTF's formulas: c / 255, c / 65535; VEC3
    // gets alpha 1.
    const glm::vec4 expected[6][3] = {
        {{0.25f, 0.5f, 1.0f, 1.0f}, {0.0f, 0.125f, 0.75f, 1.0f}, {1.0f, 1.0f, 0.5f, 1.0f}},
        {{0.25f, 0.5f, 1.0f, 0.5f}, {0.0f, 0.125f, 0.75f, 0.0f}, {1.0f, 1.0f, 0.5f, 1.0f}},
        {{0.0f, 128 / 255.0f, 1.0f, 1.0f}, {51 / 255.0f, 102 / 255.0f, 204 / 255.0f, 1.0f}, {1.0f, 0.0f, 1 / 255.0f, 1.0f}},
        {{0.0f, 128 / 255.0f, 1.0f, 64 / 255.0f}, {51 / 255.0f, 102 / 255.0f, 204 / 255.0f, 0.0f}, {1.0f, 0.0f, 1 / 255.0f, 1.0f}},
        {{0.0f, 32768 / 65535.0f, 1.0f, 16384 / 65535.0f},
         {13107 / 65535.0f, 26214 / 65535.0f, 52428 / 65535.0f, 0.0f},
         {1.0f, 0.0f, 1 / 65535.0f, 1.0f}},
        {glm::vec4(1.0f), glm::vec4(1.0f), glm::vec4(1.0f)},
    };
    for (std::size_t t = 0; t < 6; ++t) {
        CAPTURE(t);
        for (std::size_t k = 0; k < 3; ++k) CHECK(scene.colors[t][k] == expected[t][k]);
    }
    CHECK((buildAndPack(scene).features.bits & gpu::kFeatureVertexColor) != 0u);
    // A file without COLOR_0 keeps no colours and no feature bit.
    const Scene plain = loadGeometry("texcoord-0.gltf");
    CHECK(plain.colors.empty());
    CHECK((buildAndPack(plain).features.bits & gpu::kFeatureVertexColor) == 0u);
}

TEST_CASE("vertex colours: an unlit quad shows baseColor times the interpolated COLOR_0 at every pixel centre" *
          doctest::test_suite("render")) {
    const Scene scene = loadGeometry("colors-unlit.gltf");
    const GpuScene gpu = buildAndPack(scene);
    REQUIRE((gpu.features.bits & gpu::kFeatureVertexColor) != 0u);
    const RenderSettings s = centreSamples();
    const glm::dvec3 base(0.5, 1.0, 0.8);
    for (const IntegratorKind kind : {IntegratorKind::Megakernel, IntegratorKind::Wavefront}) {
        RenderSettings k = s;
        k.integrator = kind;
        const std::vector<float> mean = uploadAndRender(gpu, scene.cameras.at(0), k).film.mean();
        double worst = 0.0;
        for (int y = 0; y < s.height; ++y) {
            for (int x = 0; x < s.width; ++x) {
                const glm::dvec2 p = pixelOnPlane(scene.cameras[0], s.width, s.height, x, y);
                const glm::dvec3 expected = base * glm::dvec3(quadColor(p.x, p.y));
                for (int c = 0; c < 3; ++c) {
                    const double got = mean[static_cast<std::size_t>((y * s.width + x) * 3 + c)];
                    worst = std::max(worst, std::abs(got - expected[c]));
                }
            }
        }
        // float32 barycentrics and colours: about 1e-6 of the values.
        CHECK(worst < 2e-5);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("vertex colours: under alphaMode MASK the COLOR_0 alpha makes the hole" * doctest::test_suite("render")) {
    const Scene scene = loadGeometry("colors-mask.gltf");
    const RenderSettings s = centreSamples();
    const std::vector<float> mean = renderScene(scene, s).film.mean();
    const glm::dvec3 base(0.5, 1.0, 0.8);
    int holes = 0, shown = 0;
    for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
            const glm::dvec2 p = pixelOnPlane(scene.cameras[0], s.width, s.height, x, y);
            const glm::dvec4 color = quadColor(p.x, p.y);
            if (std::abs(color.a - 0.5) < 1e-3) continue;  // on the cutoff within float rounding
            const bool hole = color.a < 0.5;
            const glm::dvec3 expected = hole ? glm::dvec3(0.0) : base * glm::dvec3(color);
            holes += hole;
            shown += !hole;
            for (int c = 0; c < 3; ++c) {
                CAPTURE(x);
                CAPTURE(y);
                CHECK(mean[static_cast<std::size_t>((y * s.width + x) * 3 + c)] == doctest::Approx(expected[c]).epsilon(2e-5));
            }
        }
    }
    CHECK(holes > 50);
    CHECK(shown > 50);
    CHECK(vk::validationMessageCount() == 0);
}
