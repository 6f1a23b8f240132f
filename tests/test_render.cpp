// Render tests on the real shaders (lavapipe in CI), validation layers on.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "test_util.h"
#include "util/error.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

RenderSettings small(std::uint32_t spp, std::uint32_t maxDepth, std::uint32_t seed = 1) {
    RenderSettings s;
    s.width = 24;
    s.height = 24;
    s.spp = spp;
    s.maxDepth = maxDepth;
    s.seed = seed;
    return s;
}

}  // namespace

// Closed furnace (scenes/furnace.gltf): every surface has albedo a = 0.5 and
// emits Le = 0.5, so L = Le (1 - a^(D+1)) / (1 - a) for max depth D
// (the geometric series of D scattering events).
struct Furnace {
    const char* file;
    double albedo, le;
};

TEST_CASE("closed furnace matches Le (1 - a^(D+1)) / (1 - a) within 4 standard errors") {
  for (const Furnace f : {Furnace{"scenes/furnace.gltf", 0.5, 0.5},
                          Furnace{"scenes/furnace-a0.8-le0.1.gltf", 0.8, 0.1}}) {
    const double a = f.albedo, le = f.le;
    CAPTURE(f.file);
    for (std::uint32_t depth : {0u, 1u, 2u, 5u, 16u}) {
        CAPTURE(depth);
        Rendered r = renderFile(f.file, small(64, depth, 7 + depth));
        const double expected = le * (1.0 - std::pow(a, depth + 1.0)) / (1.0 - a);
        const ImageMean m = imageMean(r.result.film);
        CAPTURE(m.mean);
        CAPTURE(m.stdError);
        CHECK(r.result.spp == 64);
        CHECK(r.result.nonFinite == 0);
        if (depth == 0) {
            // Only the directly seen emission: no randomness at all.
            CHECK(m.mean == doctest::Approx(expected).epsilon(1e-6));
        } else {
            CHECK(m.stdError > 0.0);
            CHECK(std::abs(m.mean - expected) <= 4.0 * m.stdError);
            // The standard error is small enough for the test to mean something.
            CHECK(m.stdError < 0.01 * expected);
        }
    }
  }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("same seed and spp give a bit-identical image, and another seed differs") {
    const RenderSettings s = small(4, 16, 42);
    Rendered a = renderFile("scenes/cornell-box.gltf", s);
    Rendered b = renderFile("scenes/cornell-box.gltf", s);
    RenderSettings s2 = s;
    s2.seed = 43;
    Rendered c = renderFile("scenes/cornell-box.gltf", s2);
    const auto ma = a.result.film.mean(), mb = b.result.film.mean(), mc = c.result.film.mean();
    REQUIRE(ma.size() == mb.size());
    CHECK(std::memcmp(ma.data(), mb.data(), ma.size() * sizeof(float)) == 0);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < ma.size(); ++i) differing += ma[i] != mc[i];
    CHECK(differing > ma.size() / 2);
    CHECK(a.result.nonFinite == 0);
    CHECK(vk::validationMessageCount() == 0);
}

// On CPU devices the path tracer shades a tile's 8x8 blocks in a permuted
// order (SPEC_WORK_QUEUE); every pixel must still get exactly its own path.
// 90x70 pixels: partial blocks on both edges; 4 spp in 1x1 tiles of 64x64
// and the rest, so tiles of several shapes are permuted.
TEST_CASE("the permuted block order gives the image of the row order, bit for bit") {
    RenderSettings s = small(4, 16, 5);
    s.width = 90;
    s.height = 70;
    RenderTuning t;
    t.tileSize = 64;
    t.workQueue = WorkQueue::On;
    Rendered a = renderFile("scenes/cornell-box.gltf", s, t);
    t.workQueue = WorkQueue::Off;
    Rendered b = renderFile("scenes/cornell-box.gltf", s, t);
    const auto ma = a.result.film.mean(), mb = b.result.film.mean();
    REQUIRE(ma.size() == mb.size());
    CHECK(std::memcmp(ma.data(), mb.data(), ma.size() * sizeof(float)) == 0);
    CHECK(a.result.closestRays == b.result.closestRays);
    CHECK(a.result.nonFinite == 0);
    CHECK(vk::validationMessageCount() == 0);
}

// Submissions are sized by timing; the image must not depend on where they
// end, nor on how many samples the megakernel takes in one dispatch (each
// invocation runs them one after another).
TEST_CASE("the image does not depend on how samples are split into submissions and dispatches") {
    RenderSettings s = small(100, 16, 9);  // 100 = one full fold group of 64 and a partial one
    RenderTuning t;
    t.fixedBatch = 1;                      // one sample per submission
    Rendered a = renderFile("scenes/cornell-box.gltf", s, t);
    t.fixedBatch = 0;
    t.submitSeconds = 1e9;                 // as many as a fold group allows: batches of 8 (the
    Rendered b = renderFile("scenes/cornell-box.gltf", s, t);  // first, 576 pixels), 56, 36
    t.samplesPerDispatch = 3;              // batches of 3, 61, 36: dispatches of 1, 21 (20 x 3 + 1), 12 x 3
    Rendered c = renderFile("scenes/cornell-box.gltf", s, t);
    CHECK(a.result.submissions == 100);
    CHECK(a.result.dispatches == 100);
    CHECK(b.result.submissions == 3);
    // 64 samples a dispatch (8 on a CPU device: 8, 7 x 8, 4 x 8 + 4).
    CHECK(b.result.dispatches == (context().info.vkType == VK_PHYSICAL_DEVICE_TYPE_CPU ? 1 + 7 + 5 : 3));
    CHECK(c.result.dispatches == 1 + 21 + 12);
    const auto ma = a.result.film.mean(), mb = b.result.film.mean(), mc = c.result.film.mean();
    CHECK(std::memcmp(ma.data(), mb.data(), ma.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(ma.data(), mc.data(), ma.size() * sizeof(float)) == 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("the first submission takes up to 8 samples of a small image, one of a large one") {
    CHECK(firstSubmissionSamples(128 * 128, 8) == 8);
    CHECK(firstSubmissionSamples(256 * 256, 8) == 2);
    CHECK(firstSubmissionSamples(256 * 256, 64) == 2);
    CHECK(firstSubmissionSamples(362 * 362, 8) == 1);
    CHECK(firstSubmissionSamples(1920 * 1080, 64) == 1);
    CHECK(firstSubmissionSamples(16 * 16, 64) == 8);  // a GPU's 64 a dispatch: still 8
    CHECK(firstSubmissionSamples(16 * 16, 3) == 3);   // no more than a dispatch takes
    CHECK(firstSubmissionSamples(16 * 16, 1) == 1);
    CHECK(firstSubmissionSamples(0, 8) == 8);
    // In a render: 24x24 pixels take 8 samples first, one where a time
    // limit must not be passed by more than a sample.
    RenderSettings s = small(8, 2);
    RenderTuning t;
    t.submitSeconds = 1e9;
    CHECK(renderFile("scenes/cornell-box.gltf", s, t).result.submissions == 1);
    s.timeLimit = 1e6;
    CHECK(renderFile("scenes/cornell-box.gltf", s, t).result.submissions == 2);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("the four-wide BVH (register or memory stack) and the binary BVH render the same image") {
    RenderSettings s = small(2, 4, 5);
    s.bvhStack = BvhStack::Registers;
    Rendered four = renderFile("scenes/cornell-box.gltf", s);
    s.bvhStack = BvhStack::Memory;
    Rendered memory = renderFile("scenes/cornell-box.gltf", s);
    s.bvhWidth = 2;
    Rendered two = renderFile("scenes/cornell-box.gltf", s);
    CHECK(four.result.bvhWidth == 4);
    CHECK(std::string(four.result.bvhStack) == "registers");
    CHECK(memory.result.bvhWidth == 4);
    CHECK(std::string(memory.result.bvhStack) == "memory");
    CHECK(two.result.bvhWidth == 2);
    const auto ma = four.result.film.mean(), mb = two.result.film.mean(), mm = memory.result.film.mean();
    CHECK(std::memcmp(ma.data(), mb.data(), ma.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(ma.data(), mm.data(), ma.size() * sizeof(float)) == 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("texel and storage traversal render the same image") {
    RenderSettings s = small(2, 4, 5);
    s.reads = ReadMode::Texel;
    Rendered t = renderFile("scenes/cornell-box.gltf", s);
    s.reads = ReadMode::Storage;
    Rendered st = renderFile("scenes/cornell-box.gltf", s);
    CHECK(t.result.reads == gpu::kReadsTexelBvh);
    CHECK(st.result.reads == gpu::kReadsStorage);
    const auto mt = t.result.film.mean(), ms = st.result.film.mean();
    CHECK(std::memcmp(mt.data(), ms.data(), mt.size() * sizeof(float)) == 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("renders share a compiled pipeline when asked, with the same image") {
    const Scene scene = loadGltf(sourcePath("scenes/cornell-box.gltf"));
    const GpuScene gpu = buildAndPack(scene);
    RenderSettings s = small(4, 3, 77);
    s.width = 24;
    s.height = 16;
    RenderTuning t;
    t.reusePipeline = false;
    const RenderResult own = uploadAndRender(gpu, scene.cameras.at(0), s, t);
    CHECK_FALSE(own.pipelineReused);
    CHECK(own.pipelineMs > 0.0);
    t.reusePipeline = true;
    const RenderResult first = uploadAndRender(gpu, scene.cameras.at(0), s, t);
    const RenderResult second = uploadAndRender(gpu, scene.cameras.at(0), s, t);
    CHECK(second.pipelineReused);
    CHECK(second.pipelineMs == 0.0);
    // Without reuse a render compiles its own, though one is cached.
    t.reusePipeline = false;
    const RenderResult third = uploadAndRender(gpu, scene.cameras.at(0), s, t);
    CHECK_FALSE(third.pipelineReused);
    const auto a = own.film.mean(), b = first.film.mean(), c = second.film.mean(), d = third.film.mean();
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(a.data(), d.data(), a.size() * sizeof(float)) == 0);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("an image whose sample sums exceed the device's largest allocation is one error before any work") {
    // 24 x 16 pixels need 24 * 16 * 32 = 12288 bytes of sums; a device
    // allowing 12287 bytes per allocation (the limit lowered) cannot hold them.
    RenderSettings s = small(1, 0, 1);
    s.width = 24;
    s.height = 16;
    RenderTuning t;
    t.limits.allocation = 12287;
    CHECK_THROWS_WITH_AS(renderFile("scenes/furnace.gltf", s, t),
                         "strata: error: a 24x16 image needs 12288 bytes for its sample sums, more than the device's "
                         "maxMemoryAllocationSize (12287 bytes); render a smaller image",
                         strata::Error);
    t.limits.allocation = 12288;
    CHECK(renderFile("scenes/furnace.gltf", s, t).result.spp == 1);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("an image larger than one dispatch tile is covered in full") {
    RenderSettings s = small(1, 0, 3);
    s.width = 37;
    s.height = 29;
    RenderTuning t;
    t.tileSize = 16;  // 3 x 2 tiles, ragged edges
    Rendered r = renderFile("scenes/furnace.gltf", s, t);
    for (std::uint64_t n : r.result.film.count) CHECK(n == 1);
    const auto m = r.result.film.mean();
    for (float v : m) CHECK(v == doctest::Approx(0.5).epsilon(1e-6));
    CHECK(vk::validationMessageCount() == 0);
}

// 250,000 samples of a constant: the device sums float32 batches of at most
// 64 samples and the host folds them as fixed-point integers, so the mean
// does not drift. A float32 running sum of 250,000 x 0.1f ends 0.24% off
// (1% at 10^6), 240 times the tolerance, so this can fail.
TEST_CASE("accumulation of 250,000 samples of a constant does not drift" * doctest::test_suite("slow")) {
    RenderSettings s = small(250000, 0, 1);
    s.width = 8;
    s.height = 8;
    Rendered r = renderFile("scenes/furnace-a0.8-le0.1.gltf", s);
    REQUIRE(r.result.spp == 250000);
    const double le = static_cast<double>(0.1f);  // every sample is this float exactly
    for (std::size_t i = 0; i < r.result.film.pixels(); ++i) {
        CHECK(r.result.film.count[i] == 250000);
        const double mean = r.result.film.sumAt(i, 0) / r.result.film.count[i];
        CHECK(std::abs(mean - le) / le < 1e-5);
    }
    CHECK(vk::validationMessageCount() == 0);
}

namespace {

// Renders `scene` with the megakernel and with the wavefront integrator (in
// tiles of 16 pixels, so that an image spans several) and checks that the
// images are the same bits: the stages do pathtrace.comp's arithmetic in its
// order, and each pixel's sums are added in sample order either way. Both
// read textures at full resolution (the wavefront integrator has no
// texture LOD: its renders pack no mip chains).
// `required`: feature bits the packed scene must have (the code under test).
void checkWavefrontMatches(const Scene& scene, RenderSettings s, bool textureLod = false, std::uint32_t required = 0) {
    const GpuScene gpu = buildAndPack(scene, {}, 4, textureLod);
    CHECK((gpu.features.bits & required) == required);
    RenderTuning t;
    t.tileSize = 16;
    s.integrator = IntegratorKind::Megakernel;
    const RenderResult mega = uploadAndRender(gpu, scene.cameras.at(0), s, t);
    s.integrator = IntegratorKind::Wavefront;
    const RenderResult wave = uploadAndRender(gpu, scene.cameras.at(0), s, t);
    CHECK(wave.spp == s.spp);
    CHECK(wave.nonFinite == mega.nonFinite);
    CHECK(sameImage(mega.film, wave.film));
    // The same paths: the same closest rays. The megakernel also counts a
    // shadow ray whose light point coincides with its origin (not traced).
    CHECK(wave.closestRays == mega.closestRays);
    CHECK(wave.shadowRays <= mega.shadowRays);
    CHECK(static_cast<double>(wave.shadowRays) >= 0.999 * static_cast<double>(mega.shadowRays));
    CHECK(wave.closestRays > 0);
    CHECK(vk::validationMessageCount() == 0);
}

}  // namespace

TEST_CASE("the wavefront integrator renders the megakernel's image bit for bit" * doctest::test_suite("slow")) {
    RenderSettings s = small(3, 6, 5);
    s.width = 40;
    s.height = 28;
    SUBCASE("Cornell box (area lights, Lambert)") { checkWavefrontMatches(loadGltf(sourcePath("scenes/cornell-box.gltf")), s); }
    SUBCASE("Veach MIS (glossy, four lights)") { checkWavefrontMatches(loadGltf(sourcePath("scenes/veach-mis.gltf")), s); }
    SUBCASE("many lights by the light tree (its MIS probability from the last vertex kept between stages)") {
        checkWavefrontMatches(loadGltf(sourcePath("scenes/many-lights.gltf")), s, false, gpu::kFeatureLightTree);
    }
    SUBCASE("materials board (textures, normal maps, transmission)") {
        checkWavefrontMatches(loadGltf(sourcePath("scenes/materials-board.gltf")), s);
    }
    SUBCASE("material layers (clearcoat, sheen, specular colour)") {
        checkWavefrontMatches(loadGltf(sourcePath("tests/data/materials/layer-spheres.gltf")), s);
    }
    SUBCASE("alpha test") { checkWavefrontMatches(loadGltf(sourcePath("tests/data/textures/alpha-mask.gltf")), s); }
    SUBCASE("texture LOD: ray cones carried between the stages, through a mirror bounce") {
        checkWavefrontMatches(loadGltf(sourcePath("tests/data/textures/lod-mirror.gltf")), s, true, gpu::kFeatureTextureLod);
        checkWavefrontMatches(loadGltf(sourcePath("scenes/materials-board.gltf")), s, true, gpu::kFeatureTextureLod);
    }
    SUBCASE("diffuse transmission (a sun-lit sheet seen from behind) and anisotropy (a brushed plate)") {
        checkWavefrontMatches(loadGltf(sourcePath("tests/data/materials/translucent-backlit.gltf")), s);
        checkWavefrontMatches(loadGltf(sourcePath("tests/data/materials/anisotropy-90.gltf")), s);
    }
    SUBCASE("environment map and a directional light, light sampling only") {
        const Scene scene = envBoardWithSun();
        checkWavefrontMatches(scene, s);
        s.mis = gpu::kMisLight;
        checkWavefrontMatches(scene, s);
    }
}

TEST_SUITE_END();
