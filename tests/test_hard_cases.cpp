// Numerical hard cases, traced by the real shader (trace.comp) on the device.
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

void addTriangle(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    Triangle t;
    t.v[0] = a, t.v[1] = b, t.v[2] = c;
    glm::vec3 n = glm::cross(b - a, c - a);
    n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1);
    t.n[0] = t.n[1] = t.n[2] = n;
    s.triangles.push_back(t);
}

// UV sphere of radius r around c: closed, every edge shared by two triangles.
Scene sphere(glm::vec3 c, float r, int rings, int segments) {
    Scene s;
    s.materials.push_back(MaterialDesc{});
    auto p = [&](int i, int j) {
        const double th = M_PI * i / rings, ph = 2.0 * M_PI * (j % segments) / segments;
        return c + r * glm::vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            if (i > 0) addTriangle(s, p(i, j), p(i + 1, j), p(i, j + 1));
            if (i < rings - 1) addTriangle(s, p(i, j + 1), p(i + 1, j), p(i + 1, j + 1));
        }
    return s;
}

gpu::TraceRay rayTo(glm::vec3 origin, glm::vec3 target) {
    gpu::TraceRay r{};
    r.origin = origin;
    r.dir = glm::normalize(target - origin);
    r.tmin = 0.0f;
    r.tmax = 1e30f;
    return r;
}

}  // namespace

// Woop, Benthin & Wald 2013: rays through shared edges and vertices of a
// closed mesh must hit one of the triangles sharing them, never slip through.
TEST_CASE("watertight: 10^5 rays aimed at the vertices and edges of a closed mesh all hit") {
    const glm::vec3 centre(0.3f, -0.2f, 0.1f);
    Scene s = sphere(centre, 1.0f, 60, 120);
    GpuScene g = buildAndPack(s);
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::uniform_int_distribution<std::size_t> pick(0, s.triangles.size() - 1);
    std::vector<gpu::TraceRay> rays;
    for (int i = 0; i < 100000; ++i) {
        const Triangle& t = s.triangles[pick(rng)];
        const int k = i % 3;
        // Half aimed at a vertex, half at a point on an edge.
        const glm::vec3 target = (i % 2) ? t.v[k] : glm::mix(t.v[k], t.v[(k + 1) % 3], u(rng));
        // The ray must cross the surface at the target: from outside along
        // the line from an interior point q through the target (a ray that
        // only touches the convex mesh at an edge or vertex is a supporting
        // line, which may legitimately miss), or from q itself.
        const glm::vec3 q = centre + 0.2f * glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
        const glm::vec3 outward = glm::normalize(target - q);
        const glm::vec3 origin = (i % 4 < 2) ? target + outward * (2.0f + 3.0f * u(rng)) : q;
        rays.push_back(rayTo(origin, target));
    }
    const GpuScene g2 = buildAndPack(s, {}, 2);
    for (ReadMode mode : {ReadMode::Texel, ReadMode::Storage}) for (int width : {4, 2}) {
        const auto hits = traceOnDevice(context(), width == 4 ? g : g2, rays, mode, gpu::kTraceClosest);
        std::size_t misses = 0, nonFinite = 0;
        for (const auto& h : hits) {
            misses += h.triangle == gpu::kNoHit;
            nonFinite += !std::isfinite(h.t);
        }
        CHECK(misses == 0);
        CHECK(nonFinite == 0);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// Rays whose direction has components of exactly +0 and -0, starting on the
// slab planes of BVH nodes: the slab test meets 0 * inf = NaN there (Ize
// 2013). Every such ray must find the triangle it is aimed at.
TEST_CASE("axis-aligned rays with +-0 components starting on node slab planes never miss") {
    Scene s;
    s.materials.push_back(MaterialDesc{});
    // A 6x6x6 grid of axis-aligned unit squares facing each axis.
    for (int x = 0; x < 6; ++x)
        for (int y = 0; y < 6; ++y)
            for (int z = 0; z < 6; ++z) {
                const glm::vec3 o(2.0f * x, 2.0f * y, 2.0f * z);
                addTriangle(s, o, o + glm::vec3(1, 0, 0), o + glm::vec3(1, 1, 0));
                addTriangle(s, o, o + glm::vec3(0, 1, 0), o + glm::vec3(0, 1, 1));
                addTriangle(s, o, o + glm::vec3(0, 0, 1), o + glm::vec3(1, 0, 1));
            }
    GpuScene g = buildAndPack(s);
    Bvh bvh;
    bvh.nodes = g.nodes;
    std::vector<gpu::TraceRay> rays;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.05f, 0.3f);
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
        const auto& node = g.nodes[n];
        for (int axis = 0; axis < 3; ++axis)
            for (int sign : {-1, 1}) {
                // Origin on the node's min or max plane of `axis` (the slab
                // plane), inside the box across the other two axes.
                glm::vec3 o = glm::mix(node.bmin, node.bmax, glm::vec3(u(rng), u(rng), u(rng)));
                o[axis] = sign > 0 ? node.bmin[axis] : node.bmax[axis];
                glm::vec3 d(0.0f);
                d[(axis + 1) % 3] = -0.0f;  // the other components are +0 and -0
                d[axis] = static_cast<float>(sign);
                gpu::TraceRay r{};
                r.origin = o;
                r.dir = d;
                r.tmax = 1e30f;
                rays.push_back(r);
            }
    }
    const GpuScene g2 = buildAndPack(s, {}, 2);
    for (int width : {4, 2}) {
        INFO("BVH" << width);
        const auto hits = traceOnDevice(context(), width == 4 ? g : g2, rays, ReadMode::Texel, gpu::kTraceClosest);
        std::size_t expectedHits = 0, mismatches = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const Hit ref = traceBruteForce(g.tris, Ray{rays[i].origin, rays[i].dir, 0.0f, 1e30f});
            expectedHits += ref.hit();
            CHECK(std::isfinite(hits[i].t));
            mismatches += ref.triangle != hits[i].triangle || (ref.hit() && ref.t != hits[i].t);
        }
        CHECK(expectedHits > rays.size() / 4);
        CHECK(mismatches == 0);
    }
    CHECK(vk::validationMessageCount() == 0);
}

// pbrt-v4's Reintersect test (src/pbrt/shapes_test.cpp), on the device: rays
// leaving a hit from the origin the path tracer uses (Wächter & Binder 2019
// offset) never hit their own triangle again, at any scale from 1e-8 to 1e8.
TEST_CASE("self-intersection: spawned rays never re-hit their own triangle (log-uniform scales)") {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto coord = [&] {
        const double mag = std::pow(10.0, -8.0 + 16.0 * u(rng));
        return static_cast<float>(u(rng) < 0.5 ? -mag : mag);
    };
    Scene s;
    s.materials.push_back(MaterialDesc{});
    for (int i = 0; i < 1000; ++i) {
        // One log-uniform centre per triangle, vertices at log-uniform offsets
        // of a similar magnitude, so tiny and huge triangles both occur.
        const glm::vec3 c(coord(), coord(), coord());
        const float scale = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
        auto near = [&] {
            return c + scale * glm::vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        };
        addTriangle(s, near(), near(), near());
    }
    GpuScene g = buildAndPack(s);
    std::vector<gpu::TraceRay> rays;
    for (std::size_t i = 0; i < g.tris.size(); ++i) {
        const auto& t = g.tris[i];
        const glm::vec3 a(t.v0), b(t.v1), c(t.v2);
        if (glm::length(glm::cross(b - a, c - a)) == 0.0f) continue;
        for (int k = 0; k < 20; ++k) {
            double b1 = u(rng), b2 = u(rng);
            if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
            const glm::vec3 target = a + static_cast<float>(b1) * (b - a) + static_cast<float>(b2) * (c - a);
            const float size = glm::length(b - a) + glm::length(c - a);
            glm::vec3 dir = glm::normalize(glm::vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
            rays.push_back(rayTo(target + dir * size * 2.0f, target));
            gpu::TraceRay spawn{};
            spawn.dir = glm::normalize(glm::vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
            spawn.tmax = 1e30f;
            rays.push_back(spawn);
        }
    }
    const auto hits = traceOnDevice(context(), g, rays, ReadMode::Texel, gpu::kTraceSpawn);
    std::size_t primaryHits = 0, reHits = 0;
    for (std::size_t i = 0; i < hits.size(); i += 2) {
        if (hits[i].triangle == gpu::kNoHit) continue;
        ++primaryHits;
        reHits += hits[i + 1].triangle == hits[i].triangle;
    }
    CHECK(primaryHits > rays.size() / 2 * 9 / 10);
    CHECK(reHits == 0);
    CHECK(vk::validationMessageCount() == 0);
}

// Degenerate input: zero-area (repeated vertex, all three equal) and collinear
// triangles are kept as geometry but never hit, even by rays aimed right at them.
TEST_CASE("degenerate triangles are never hit by the shader") {
    Scene s;
    s.materials.push_back(MaterialDesc{});
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-5.0f, 5.0f), t(0.0f, 1.0f);
    std::uniform_int_distribution<int> ik(-5, 5);
    std::vector<glm::vec3> targets;
    for (int i = 0; i < 300; ++i) {
        // Integer coordinates keep the collinear case exactly collinear in
        // float (a rounded "collinear" point makes a real sliver, which may be hit).
        const glm::vec3 a(ik(rng), ik(rng), ik(rng)), d(ik(rng), ik(rng), ik(rng) + 11);
        const glm::vec3 b = a + 2.0f * d;
        switch (i % 3) {
            case 0: addTriangle(s, a, a, b); break;       // repeated vertex
            case 1: addTriangle(s, a, a, a); break;       // a point
            default: addTriangle(s, a, a + d, b); break;  // collinear
        }
        targets.push_back(glm::mix(a, b, t(rng)));
        targets.push_back(a);
    }
    GpuScene g = buildAndPack(s);
    std::vector<gpu::TraceRay> rays;
    for (const glm::vec3& target : targets)
        for (int k = 0; k < 20; ++k) {
            const glm::vec3 dir = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + 1e-3f);
            rays.push_back(rayTo(target - dir * 20.0f, target));
        }
    const GpuScene g2 = buildAndPack(s, {}, 2);
    for (ReadMode mode : {ReadMode::Texel, ReadMode::Storage}) for (int width : {4, 2}) {
        const auto hits = traceOnDevice(context(), width == 4 ? g : g2, rays, mode, gpu::kTraceClosest);
        std::size_t hitCount = 0;
        for (const auto& h : hits) hitCount += h.triangle != gpu::kNoHit;
        CHECK(hitCount == 0);
    }
    CHECK(vk::validationMessageCount() == 0);
}

TEST_SUITE_END();
