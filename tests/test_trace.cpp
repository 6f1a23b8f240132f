// The shader's BVH traversal (shaders/trace.comp on the device) against the
// CPU reference traversal, through both texel and storage reads.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "bvh/bvh.h"
#include "measure/tracer.h"
#include "test_util.h"

using namespace strata;
using namespace strata::test;

TEST_SUITE_BEGIN("render");

namespace {

Scene randomSoup(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f), off(-1.0f, 1.0f);
    Scene s;
    s.materials.push_back(MaterialDesc{});
    for (std::size_t i = 0; i < count; ++i) {
        Triangle t;
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        for (int k = 0; k < 3; ++k) t.v[k] = c + glm::vec3(off(rng), off(rng), off(rng));
        const glm::vec3 n = glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
        t.n[0] = t.n[1] = t.n[2] = n;
        s.triangles.push_back(t);
    }
    return s;
}

std::vector<gpu::TraceRay> randomRays(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-12.0f, 12.0f), dir(-1.0f, 1.0f);
    std::vector<gpu::TraceRay> rays;
    for (std::size_t i = 0; i < count; ++i) {
        gpu::TraceRay r{};
        r.origin = glm::vec3(pos(rng), pos(rng), pos(rng));
        glm::vec3 d(dir(rng), dir(rng), dir(rng));
        if (i % 7 == 0) d.x = 0.0f;           // exact zero components
        if (i % 11 == 0) d.y = -0.0f;
        if (glm::length(d) == 0.0f) d = glm::vec3(0, 0, 1);
        r.dir = glm::normalize(d);
        r.tmin = 0.0f;
        r.tmax = 1e30f;
        rays.push_back(r);
    }
    return rays;
}

// `g` packed for `width` (buildAndPack's): the tree the shader traverses.
void compareWithCpu(const GpuScene& g, const std::vector<gpu::TraceRay>& rays, ReadMode mode, int width = 4,
                    BvhStack stack = BvhStack::Registers) {
    INFO("BVH" << width << (mode == ReadMode::Texel ? ", texel reads" : ", storage reads")
               << (stack == BvhStack::Memory ? ", memory stack" : ""));
    Bvh bvh;
    bvh.nodes = g.nodes;
    DeviceTracer tracer(context(), g, mode, stack);
    REQUIRE(tracer.bvhWidth() == width);
    CHECK(tracer.memoryStack() == (width == 4 && stack == BvhStack::Memory));
    const auto hits = tracer.trace(rays, gpu::kTraceClosest);
    const auto occluded = tracer.trace(rays, gpu::kTraceAny);
    std::size_t mismatches = 0, hitCount = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        Ray r{rays[i].origin, rays[i].dir, rays[i].tmin, rays[i].tmax};
        const Hit cpu = traceClosest(bvh, g.tris, r);
        const gpu::TraceHit& gh = hits[i];
        hitCount += cpu.hit();
        bool same = (cpu.triangle == gh.triangle);
        // Float evaluation order may differ between compilers (FMA); accept a
        // different triangle only at a numerically tied distance.
        if (!same && cpu.hit() && gh.triangle != gpu::kNoHit)
            same = std::abs(cpu.t - gh.t) <= 1e-5f * cpu.t;
        if (same && cpu.hit()) same = std::abs(cpu.t - gh.t) <= 1e-5f * cpu.t;
        mismatches += !same;
        // Any-hit agrees with closest-hit on whether something is hit.
        CHECK((occluded[i].t > 0.0f) == (gh.triangle != gpu::kNoHit));
    }
    CHECK(hitCount > rays.size() / 10);  // the ray set actually exercises hits
    CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("shader traversal matches the CPU BVH on random rays (BVH4 and BVH2, texel and storage reads)") {
    Scene soup = randomSoup(20000, 3);
    const GpuScene g = buildAndPack(soup), g2 = buildAndPack(soup, {}, 2);
    const auto rays = randomRays(50000, 9);
    for (int width : {4, 2}) {
        compareWithCpu(width == 4 ? g : g2, rays, ReadMode::Texel, width);
        compareWithCpu(width == 4 ? g : g2, rays, ReadMode::Storage, width);
    }
    // The four-wide traversal with its stack in an array (GPUs' default).
    compareWithCpu(g, rays, ReadMode::Texel, 4, BvhStack::Memory);
    compareWithCpu(g, rays, ReadMode::Storage, 4, BvhStack::Memory);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("shader traversal matches the CPU BVH on the Cornell box") {
    Scene box = loadGltf(sourcePath("scenes/cornell-box.gltf"));
    GpuScene g = buildAndPack(box);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& t : box.triangles)
        for (const auto& v : t.v) lo = glm::min(lo, v), hi = glm::max(hi, v);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), d(-1.0f, 1.0f);
    std::vector<gpu::TraceRay> rays;
    for (int i = 0; i < 20000; ++i) {
        gpu::TraceRay r{};
        r.origin = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
        r.dir = glm::normalize(glm::vec3(d(rng), d(rng), d(rng)) + glm::vec3(0, 0, 1e-3f));
        r.tmax = 1e30f;
        rays.push_back(r);
    }
    compareWithCpu(g, rays, ReadMode::Texel, 4);
    compareWithCpu(buildAndPack(box, {}, 2), rays, ReadMode::Texel, 2);
    CHECK(vk::validationMessageCount() == 0);
}

// A chain of triangles shrinking by 2.1x, one per leaf: a BVH about as deep
// as it gets, so the four-wide traversal needs more than 16 stack registers.
TEST_CASE("four-wide traversal of a deep tree (24 or 32 stack registers) matches the CPU BVH") {
    const Scene chain = triangleChain(60, 2.1f);
    BvhBuildOptions options;
    options.bins = 2;
    options.maxLeafSize = 1;
    GpuScene g = buildAndPack(chain, options);
    INFO("BVH2 depth " << g.bvh.maxDepth << ", wide depth " << g.wideDepth);
    REQUIRE(g.wideDepth > 16);
    REQUIRE(g.wideDepth <= 32);
    // Rays along the chain from its small end, through the boxes of every
    // level (the traversal descends to the deepest node first, holding an
    // entry per level); then rays at each triangle's centroid from random
    // directions, at distances on the triangle's own scale.
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> d(-1.0f, 1.0f);
    std::vector<gpu::TraceRay> rays;
    std::uniform_real_distribution<float> slope(0.0f, 0.3f);
    for (int k = 0; k < 3000; ++k) {
        gpu::TraceRay r{};
        r.origin = glm::vec3(0.0f);
        r.dir = glm::normalize(glm::vec3(1.0f, slope(rng), slope(rng)));
        r.tmax = 1e30f;
        rays.push_back(r);
    }
    for (const Triangle& t : chain.triangles) {
        const glm::vec3 c = (t.v[0] + t.v[1] + t.v[2]) / 3.0f;
        const float scale = glm::length(t.v[1] - t.v[0]);
        for (int k = 0; k < 50; ++k) {
            glm::vec3 dir = glm::normalize(glm::vec3(d(rng), d(rng), d(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
            gpu::TraceRay r{};
            r.origin = c - dir * (4.0f * scale);
            r.dir = dir;
            r.tmax = 1e30f;
            rays.push_back(r);
        }
    }
    DeviceTracer tracer(context(), g, ReadMode::Texel);
    CHECK(tracer.bvhRegs() == bvhRegsFor(g.wideDepth));
    CHECK(tracer.bvhRegs() > 16);
    compareWithCpu(g, rays, ReadMode::Texel, 4);
    compareWithCpu(g, rays, ReadMode::Storage, 4);
    compareWithCpu(g, rays, ReadMode::Storage, 4, BvhStack::Memory);
    CHECK(vk::validationMessageCount() == 0);
}

TEST_CASE("the trace kernel's mode is a specialization constant: one pipeline per mode, an unknown mode refused") {
    GpuScene g = buildAndPack(randomSoup(2000, 4));
    DeviceTracer tracer(context(), g, ReadMode::Texel);
    const auto rays = randomRays(512, 7);
    // Modes in turn on one tracer, each from its own pipeline (compareWithCpu
    // checks them against the CPU); the first pipeline still answers after
    // the second was built.
    const auto closest = tracer.trace(rays, gpu::kTraceClosest);
    const auto any = tracer.trace(rays, gpu::kTraceAny);
    const auto closestAgain = tracer.trace(rays, gpu::kTraceClosest);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += closest[i].triangle != gpu::kNoHit;
        CHECK((any[i].t > 0.0f) == (closest[i].triangle != gpu::kNoHit));
        CHECK(closestAgain[i].triangle == closest[i].triangle);
        CHECK(closestAgain[i].t == closest[i].t);
    }
    CHECK(hits > rays.size() / 10);
    CHECK_THROWS_AS(tracer.trace(rays, 3u), std::invalid_argument);
    CHECK(vk::validationMessageCount() == 0);
}

// The work queue (SPEC_WORK_QUEUE, lavapipe's default) hands rays to
// subgroups from a counter, more at a time as it goes, until lavapipe's loop
// budget (65535 loop iterations an invocation, all loops together) is half
// spent. 300,000 rays (two dispatches) on a 20,000-triangle soup are enough
// for subgroups to reach that budget (without the checks, rays come back
// wrong); every ray must come back exactly as the plain dispatch traces it.
TEST_CASE("the trace kernel's work queue traces every ray once, with the plain dispatch's hits") {
    GpuScene g = buildAndPack(randomSoup(20000, 8));
    const auto rays = randomRays(300000, 12);
    DeviceTracer queued(context(), g, ReadMode::Texel, BvhStack::Registers, WorkQueue::On);
    DeviceTracer plain(context(), g, ReadMode::Texel, BvhStack::Registers, WorkQueue::Off);
    REQUIRE(queued.workQueue());
    REQUIRE_FALSE(plain.workQueue());
    for (std::uint32_t mode : {gpu::kTraceClosest, gpu::kTraceAny, gpu::kTraceSpawn}) {
        INFO("mode " << mode);
        const auto a = queued.trace(rays, mode);
        const auto b = plain.trace(rays, mode);
        std::size_t different = 0, hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            different += a[i].triangle != b[i].triangle || a[i].t != b[i].t || a[i].u != b[i].u || a[i].v != b[i].v;
            hits += b[i].t > 0.0f;
        }
        CHECK(hits > rays.size() / 10);
        CHECK(different == 0);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
