// The camera a render looks through (scene/view.h): the default view of a
// file without a camera frames all of its geometry; --look-from/--look-at,
// --up and --fov; and the default light of a file without one.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "cli_util.h"
#include "scene/view.h"
#include "test_util.h"
#include "util/error.h"

using namespace strata;
using namespace strata::test;

namespace {

// Where vertex v lands on the image of a camera with the given aspect:
// (x, y) in [-1, 1]^2 is inside the image; depth > 0 is in front.
struct Projected {
    double x, y, depth;
};

Projected project(const Camera& cam, float aspect, glm::vec3 v) {
    const glm::dvec3 f(cam.forward), u(cam.up), r = glm::normalize(glm::cross(f, u));
    const glm::dvec3 d = glm::dvec3(v) - glm::dvec3(cam.position);
    const double depth = glm::dot(d, f), t = std::tan(0.5 * double(cam.yfov));
    return {glm::dot(d, r) / (depth * t * double(aspect)), glm::dot(d, u) / (depth * t), depth};
}

// A cloud of triangles: `n` random points in a box of the given centre and
// half-extent, three to a triangle.
Scene cloud(std::mt19937& rng, glm::vec3 centre, glm::vec3 half, int n) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Scene s;
    s.path = "cloud.gltf";
    for (int i = 0; i < n; ++i) {
        Triangle t;
        for (glm::vec3& v : t.v) v = centre + half * glm::vec3(u(rng), u(rng), u(rng));
        s.triangles.push_back(t);
    }
    return s;
}

float radians(float degrees) { return degrees * std::numbers::pi_v<float> / 180.0f; }

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("view: the default view keeps every vertex inside the image at any aspect and field of view") {
    std::mt19937 rng(7);
    const glm::vec3 centres[] = {{0, 0, 0}, {100, -50, 3}, {0.001f, 0.002f, 0.0f}};
    const glm::vec3 halves[] = {{1, 1, 1}, {10, 0.1f, 3}, {0.001f, 0.001f, 0.002f}};
    for (const glm::vec3& c : centres)
        for (const glm::vec3& h : halves)
            for (const float aspect : {1.0f, 16.0f / 9.0f, 9.0f / 16.0f, 4.0f})
                for (const float fov : {10.0f, 40.0f, 120.0f}) {
                    const Scene s = cloud(rng, c, h, 200);
                    const Camera cam = frameScene(s, aspect, radians(fov));
                    CAPTURE(aspect);
                    CAPTURE(fov);
                    const double halfY = 0.5 * double(radians(fov));
                    const double halfMin = std::min(halfY, std::atan(double(aspect) * std::tan(halfY)));
                    double widest = 0.0;  // the largest angle between a vertex and the view axis
                    for (const Triangle& t : s.triangles)
                        for (const glm::vec3& v : t.v) {
                            const Projected p = project(cam, aspect, v);
                            REQUIRE(p.depth > 0.0);
                            CHECK(std::abs(p.x) < 1.0);
                            CHECK(std::abs(p.y) < 1.0);
                            const glm::dvec3 d = glm::normalize(glm::dvec3(v) - glm::dvec3(cam.position));
                            widest = std::max(widest, std::acos(std::min(1.0, glm::dot(d, glm::dvec3(cam.forward)))));
                        }
                    // Framed, not lost in the middle: some vertex is more than
                    // half-way to the frustum's inscribed cone.
                    CHECK(widest > 0.5 * halfMin);
                }
}

TEST_CASE("view: the default view of an instanced scene keeps every placed vertex inside the image") {
    // Two clouds, one in world space and one stored once and placed three
    // times (turned, scaled, moved far off), framed without flattening.
    std::mt19937 rng(11);
    Scene s = cloud(rng, {0, 0, 0}, {1, 1, 1}, 50);
    const Scene shared = cloud(rng, {0.5f, 0, 0}, {0.5f, 2, 0.5f}, 50);
    s.sharedMeshes.push_back({s.triangles.size(), shared.triangles.size(), "mesh 1"});
    s.triangles.insert(s.triangles.end(), shared.triangles.begin(), shared.triangles.end());
    const glm::mat4 placements[] = {
        glm::mat4(1.0f),
        glm::mat4(glm::vec4(0, 0, -2, 0), glm::vec4(0, 2, 0, 0), glm::vec4(2, 0, 0, 0), glm::vec4(20, 1, -5, 1)),
        glm::mat4(glm::vec4(0.5f, 0, 0, 0), glm::vec4(0, 0.5f, 0, 0), glm::vec4(0, 0, 0.5f, 0), glm::vec4(-30, 4, 8, 1))};
    for (const glm::mat4& m : placements) s.instances.push_back({0, m});
    const float aspect = 1.5f;
    const Camera cam = frameScene(s, aspect, radians(kFrameYfovDegrees));
    double farthest = 0.0;
    auto inside = [&](glm::vec3 v) {
        const Projected p = project(cam, aspect, v);
        REQUIRE(p.depth > 0.0);
        CHECK(std::abs(p.x) < 1.0);
        CHECK(std::abs(p.y) < 1.0);
        farthest = std::max(farthest, std::abs(p.x));
    };
    for (std::size_t i = 0; i < s.worldTriangles(); ++i)
        for (const glm::vec3& v : s.triangles[i].v) inside(v);
    for (const MeshInstance& inst : s.instances)
        for (const Triangle& t : shared.triangles)
            for (const glm::vec3& v : t.v) inside(glm::vec3(inst.toWorld * glm::vec4(v, 1.0f)));
    CHECK(farthest > 0.5);  // the placements far off widen the view: framed, not only the world cloud
}

TEST_CASE("view: the default view looks at the bounds' centre from the front and 20 degrees above") {
    std::mt19937 rng(3);
    const Scene s = cloud(rng, glm::vec3(1, 2, -3), glm::vec3(2, 1, 0.5f), 50);
    glm::dvec3 lo(1e30), hi(-1e30);
    for (const Triangle& t : s.triangles)
        for (const glm::vec3& v : t.v) lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
    const glm::dvec3 centre = (lo + hi) * 0.5;
    const Camera cam = frameScene(s, 1.5f, radians(kFrameYfovDegrees));
    const glm::dvec3 back = glm::normalize(glm::dvec3(cam.position) - centre);
    CHECK(glm::length(glm::dvec3(cam.forward) + back) < 1e-5);  // looks at the centre
    CHECK(back.x == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(std::asin(back.y) * 180.0 / std::numbers::pi == doctest::Approx(kFrameElevationDegrees).epsilon(1e-5));
    CHECK(back.z > 0.0);  // in front: glTF assets face +Z
    CHECK(glm::dot(glm::dvec3(cam.up), glm::dvec3(cam.forward)) == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(cam.up.y > 0.0f);
    CHECK(cam.yfov == radians(kFrameYfovDegrees));
}

TEST_CASE("view: --look-from and --look-at override the scene's camera, --fov its field of view") {
    Scene s;
    s.path = "box.gltf";
    Camera gltf;
    gltf.position = glm::vec3(0, 1, 4);
    gltf.yfov = 0.5f;
    s.cameras = {gltf, gltf};
    s.cameras[1].position = glm::vec3(7, 7, 7);

    ViewOptions v;
    CHECK(chooseCamera(s, v, 64, 32).position == gltf.position);
    v.camera = 1;
    CHECK(chooseCamera(s, v, 64, 32).position == glm::vec3(7, 7, 7));
    v.fovDegrees = 90.0f;
    CHECK(chooseCamera(s, v, 64, 32).yfov == doctest::Approx(std::numbers::pi / 2));

    ViewOptions look;
    look.lookFrom = glm::vec3(3, 0, 0);
    look.lookAt = glm::vec3(0, 0, 0);
    const Camera a = chooseCamera(s, look, 64, 32);
    CHECK(a.position == glm::vec3(3, 0, 0));
    CHECK(a.forward == glm::vec3(-1, 0, 0));
    CHECK(a.up == glm::vec3(0, 1, 0));
    CHECK(a.yfov == 0.5f);  // the scene camera's
    look.up = glm::vec3(0, 1, 1);  // not orthogonal: made so
    const Camera b = chooseCamera(s, look, 64, 32);
    CHECK(glm::length(b.up - glm::normalize(glm::vec3(0, 1, 1))) < 1e-6f);
    s.cameras.clear();
    look.up.reset();
    CHECK(chooseCamera(s, look, 64, 32).yfov == radians(kFrameYfovDegrees));  // no scene camera: 40 degrees
}

TEST_CASE("view: bad views are one-line errors naming the file") {
    Scene s;
    s.path = "box.gltf";
    ViewOptions v;
    v.lookFrom = glm::vec3(1, 2, 3);
    v.lookAt = glm::vec3(1, 2, 3);
    CHECK_THROWS_WITH_AS(chooseCamera(s, v, 8, 8),
                         "box.gltf: error: --look-from and --look-at are the same point (1, 2, 3)", Error);
    v.lookAt = glm::vec3(1, 5, 3);
    CHECK_THROWS_WITH_AS(chooseCamera(s, v, 8, 8),
                         "box.gltf: error: --up (0, 1, 0) is parallel to the view direction from --look-from to "
                         "--look-at",
                         Error);
    ViewOptions c;
    c.camera = 2;
    CHECK_THROWS_WITH_AS(chooseCamera(s, c, 8, 8),
                         "box.gltf: error: --camera 2 does not exist (the scene has no camera)", Error);
    s.cameras.resize(2);
    CHECK_THROWS_WITH_AS(chooseCamera(s, c, 8, 8),
                         "box.gltf: error: --camera 2 does not exist (the scene has 2 camera(s))", Error);
}

TEST_CASE("view: flags are checked together, one line each, exit 2") {
    const std::string box = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    const std::pair<std::string, std::string> cases[] = {
        {"--look-from 0,1,4", "strata: error: --look-from needs --look-at"},
        {"--look-at 0,1,4", "strata: error: --look-at needs --look-from"},
        {"--up 0,0,1", "strata: error: --up needs --look-from and --look-at"},
        {"--look-from 0,1 --look-at 0,0,0", "strata: error: --look-from expects X,Y,Z, three finite numbers, got '0,1'"},
        {"--look-from 0,1,nan --look-at 0,0,0", "strata: error: --look-from expects X,Y,Z"},
        {"--look-from 0,1,4 --look-at 0,1,4", box + ": error: --look-from and --look-at are the same point"},
        {"--fov 180", "strata: error: --fov expects degrees in (0, 179], got '180'"},
        {"--fov 0", "strata: error: --fov expects degrees in (0, 179]"},
    };
    for (const auto& [flags, prefix] : cases) expectError("render " + box + " " + flags, prefix);
}

TEST_SUITE_END();

TEST_SUITE_BEGIN("render");

// bare-sphere.gltf: a convex icosphere of albedo 0.8, no camera, no light.
// Its default light must be exactly --env-color 1,1,1 (the same bits), and
// its default view must hold the whole sphere: for a sphere on the view axis
// at distance d = r / sin(h) the silhouette is the circle inscribed in the
// (square) image, so the covered fraction c lies between that circle's pi/4
// and the disc of the icosphere's inscribed sphere (radius hMin); c is read
// from the image mean, 0.8 c + (1 - c), the sphere's pixels being 0.8 in
// expectation and the background exactly 1.
TEST_CASE("view: a file without a camera or a light renders framed, lit as by --env-color 1,1,1") {
    const Scene scene = loadGltf(sourcePath("tests/data/lights/bare-sphere.gltf"));
    REQUIRE(scene.cameras.empty());
    REQUIRE(scene.environment.enabled);
    constexpr int kSize = 32;
    const Camera cam = chooseCamera(scene, {}, kSize, kSize);
    RenderSettings s;
    s.width = s.height = kSize;
    s.spp = 64;
    s.maxDepth = 8;
    s.seed = 5;
    const GpuScene gpu = buildAndPack(scene);
    const RenderResult r = uploadAndRender(gpu, cam, s);
    CHECK(r.nonFinite == 0);

    EnvironmentOptions white;
    white.hasColor = true;
    white.color = glm::vec3(1.0f);
    const Scene lit = loadSceneWithEnvironment(sourcePath("tests/data/lights/bare-sphere.gltf"), white);
    CHECK(sameImage(r.film, uploadAndRender(buildAndPack(lit), cam, s).film));

    const auto mean = r.film.mean();
    for (const int corner : {0, kSize - 1, kSize * (kSize - 1), kSize * kSize - 1})
        for (int k = 0; k < 3; ++k) CHECK(mean[static_cast<std::size_t>(corner) * 3 + k] == 1.0f);

    glm::dvec3 centre(0.0);
    double hMin = 1e30, rMax = 0.0;
    for (const Triangle& t : scene.triangles)
        for (const glm::vec3& v : t.v) centre += glm::dvec3(v) / (3.0 * double(scene.triangles.size()));
    for (const Triangle& t : scene.triangles) {
        const glm::dvec3 a(t.v[0]), b(t.v[1]), c(t.v[2]);
        hMin = std::min(hMin, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a - centre)));
        for (const glm::vec3& v : t.v) rMax = std::max(rMax, glm::length(glm::dvec3(v) - centre));
    }
    const double h = 0.5 * double(cam.yfov);
    const double d = glm::length(glm::dvec3(cam.position) - centre);
    const double inner = std::numbers::pi / 4 * std::pow(std::tan(std::asin(hMin / d)) / std::tan(h), 2.0);
    const ImageMean m = imageMean(r.film);
    const double covered = (1.0 - m.mean) / 0.2, sigma = m.stdError / 0.2;
    MESSAGE("covered " << covered << " +- " << sigma << ", bounds [" << inner << ", " << std::numbers::pi / 4
                       << "], rMax " << rMax << ", hMin " << hMin);
    CHECK(covered > inner - 4.0 * sigma);
    CHECK(covered < std::numbers::pi / 4 + 4.0 * sigma);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("view: the CLI warns once for the default view and once for the default light, and renders") {
    TempDir out;
    const std::string file = sourcePath("tests/data/lights/bare-sphere.gltf");
    const Run r = run("render " + file + " -o " + (out.path / "a.exr").string() + " --spp 1 --width 8 --height 8 --quiet");
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(lines(r.output) == 2);
    CHECK(r.output.find(file + ": warning: no light: lighting the scene with a uniform white environment") !=
          std::string::npos);
    CHECK(r.output.find(file + ": warning: no camera: viewing the whole scene from the front and 20 degrees above") !=
          std::string::npos);
    CHECK(std::filesystem::exists(out.path / "a.exr"));
}

TEST_CASE("view: --look-from and --look-at at the Cornell box's camera give its image bit for bit") {
    TempDir out;
    const std::string box = sourcePath("scenes/cornell-box.gltf");
    const std::string common = " --spp 2 --width 16 --height 16 --quiet -o ";
    const std::string a = (out.path / "a.exr").string(), b = (out.path / "b.exr").string(),
                      c = (out.path / "c.exr").string();
    REQUIRE(run("render " + box + common + a).status == 0);
    REQUIRE(run("render " + box + " --look-from 0,1,3.8 --look-at 0,1,0" + common + b).status == 0);
    REQUIRE(run("render " + box + " --look-from 0,1,3.8 --look-at 0,1,0 --fov 60" + common + c).status == 0);
    const Run same = run("compare " + b + " " + a);
    CAPTURE(same.output);
    CHECK(same.output.find("max |x - r|   0.000000e+00") != std::string::npos);
    const Run wider = run("compare " + c + " " + a);
    CHECK(wider.output.find("max |x - r|   0.000000e+00") == std::string::npos);
}

TEST_SUITE_END();
