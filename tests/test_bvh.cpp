// BVH builder and CPU traversal: closest hits against brute force, structural
// invariants, degenerate triangles, determinism, depth bound, empty input.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iomanip>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>

#include "bvh/bvh.h"
#include "bvh/wide.h"

TEST_SUITE_BEGIN("unit");

namespace strata {
namespace {

constexpr float kPi = 3.14159265358979f;

struct Mesh {
    std::vector<glm::vec3> v0, v1, v2;
    std::vector<bool> degenerate;  // by input index

    void add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, bool degen = false) {
        v0.push_back(a);
        v1.push_back(b);
        v2.push_back(c);
        degenerate.push_back(degen);
    }
    std::size_t size() const { return v0.size(); }
};

float uniform(std::mt19937& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}

glm::vec3 uniformIn(std::mt19937& rng, const glm::vec3& lo, const glm::vec3& hi) {
    return {uniform(rng, lo.x, hi.x), uniform(rng, lo.y, hi.y), uniform(rng, lo.z, hi.z)};
}

glm::vec3 unitVector(std::mt19937& rng) {
    float z = uniform(rng, -1.0f, 1.0f), phi = uniform(rng, 0.0f, 2.0f * kPi);
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Random small triangles in [-1, 1]^3; every 64th repeats an earlier one
// exactly, so equal-t ties occur.
Mesh triangleSoup(std::mt19937& rng, int n) {
    Mesh m;
    for (int i = 0; i < n; ++i) {
        if (i % 64 == 63) {
            std::size_t j = std::size_t(rng() % m.size());
            m.add(m.v0[j], m.v1[j], m.v2[j]);
            continue;
        }
        glm::vec3 c = uniformIn(rng, glm::vec3(-1.0f), glm::vec3(1.0f));
        m.add(c + uniformIn(rng, glm::vec3(-0.08f), glm::vec3(0.08f)),
              c + uniformIn(rng, glm::vec3(-0.08f), glm::vec3(0.08f)),
              c + uniformIn(rng, glm::vec3(-0.08f), glm::vec3(0.08f)));
    }
    return m;
}

// Closed UV sphere of radius 1: shared vertex positions, a fan at each pole.
Mesh uvSphere(int slices, int stacks) {
    std::vector<glm::vec3> p;
    auto at = [&](int s, int k) -> const glm::vec3& {  // k in [1, stacks-1]
        return p[std::size_t((k - 1) * slices + (s % slices))];
    };
    for (int k = 1; k < stacks; ++k) {
        float theta = kPi * float(k) / float(stacks);
        for (int s = 0; s < slices; ++s) {
            float phi = 2.0f * kPi * float(s) / float(slices);
            p.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)});
        }
    }
    const glm::vec3 north(0.0f, 1.0f, 0.0f), south(0.0f, -1.0f, 0.0f);
    Mesh m;
    for (int s = 0; s < slices; ++s) {
        m.add(north, at(s + 1, 1), at(s, 1));
        for (int k = 1; k < stacks - 1; ++k) {
            m.add(at(s, k), at(s + 1, k), at(s + 1, k + 1));
            m.add(at(s, k), at(s + 1, k + 1), at(s, k + 1));
        }
        m.add(south, at(s, stacks - 1), at(s + 1, stacks - 1));
    }
    return m;
}

// Noisy height field over [-1, 1]^2 in xz: 2 * cells^2 triangles.
Mesh heightField(std::mt19937& rng, int cells) {
    std::vector<glm::vec3> p;
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            float x = -1.0f + 2.0f * float(i) / float(cells), z = -1.0f + 2.0f * float(j) / float(cells);
            p.push_back({x, 0.2f * std::sin(3.0f * x) * std::cos(2.0f * z) + uniform(rng, -0.02f, 0.02f), z});
        }
    }
    auto at = [&](int i, int j) { return p[std::size_t(j * (cells + 1) + i)]; };
    Mesh m;
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
            m.add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return m;
}

// A soup mixed with degenerate triangles: points, two equal vertices, and
// collinear vertices on dyadic coordinates (exactly collinear in float).
Mesh withDegenerates(std::mt19937& rng, int n) {
    Mesh m = triangleSoup(rng, n);
    auto dyadic = [&](int range) { return float(int(rng() % unsigned(2 * range + 1)) - range) / 64.0f; };
    for (int i = 0; i < n / 4; ++i) {
        glm::vec3 a(dyadic(64), dyadic(64), dyadic(64));
        glm::vec3 d(dyadic(8), dyadic(8), dyadic(8));
        switch (i % 5) {
            case 0: m.add(a, a, a, true); break;
            case 1: m.add(a, a + d, a, true); break;
            case 2: m.add(a, a + d, a + d, true); break;
            case 3: m.add(a, a + d, a + 2.0f * d, true); break;
            default: m.add(a + 3.0f * d, a - d, a + d, true); break;
        }
    }
    return m;
}

// Triangle k at x = 2.1^(k - n/2), sized in proportion: with 2 bins every
// SAH split peels off the largest triangle, a chain as deep as the mesh is
// long, so only the depth bound keeps the tree shallower than kBvhStackSize.
// Coordinates stay within 1e12 so the triangle test does not overflow.
Mesh exponentialChain(int n) {
    Mesh m;
    for (int i = 0; i < n; ++i) {
        float x = std::pow(2.1f, float(i - n / 2)), s = 0.3f * x;
        m.add({x, 0.0f, 0.0f}, {x + s, s, 0.0f}, {x, s, s});
    }
    return m;
}

std::vector<gpu::TriVerts> bvhOrder(const Bvh& bvh, const Mesh& m) {
    std::vector<gpu::TriVerts> tris(m.size());
    for (std::size_t i = 0; i < m.size(); ++i) {
        std::uint32_t k = bvh.triIndices[i];
        tris[i] = {glm::vec4(m.v0[k], 0.0f), glm::vec4(m.v1[k], 0.0f), glm::vec4(m.v2[k], 0.0f)};
    }
    return tris;
}

// Rays around a mesh with bounds [lo, hi]: origins outside aimed into the
// box, origins inside with random directions, and axis-aligned directions
// with +0/-0 components whose origins often lie exactly on a vertex
// coordinate (and so on box planes).
std::vector<Ray> makeRays(std::mt19937& rng, const Mesh& m, int count) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t i = 0; i < m.size(); ++i) {
        for (const glm::vec3& p : {m.v0[i], m.v1[i], m.v2[i]}) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(hi - lo);
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Ray r;
        int kind = i % 10;
        if (kind < 4) {
            r.origin = center + 2.0f * radius * unitVector(rng);
            r.dir = glm::normalize(uniformIn(rng, lo, hi) - r.origin);
        } else if (kind < 7) {
            r.origin = uniformIn(rng, lo, hi);
            r.dir = unitVector(rng);
        } else {
            r.origin = uniformIn(rng, lo, hi);
            int axis = int(rng() % 3);
            for (int a = 0; a < 3; ++a) r.dir[a] = (rng() & 1) ? -0.0f : 0.0f;
            r.dir[axis] = (rng() & 1) ? -1.0f : 1.0f;
            if (rng() & 1) {
                std::size_t t = std::size_t(rng() % m.size());
                for (int a = 0; a < 3; ++a) {
                    if (a != axis) r.origin[a] = (rng() & 1) ? m.v0[t][a] : m.v2[t][a];
                }
            }
        }
        if (i % 13 == 5) {
            r.tmin = uniform(rng, 0.0f, radius);
            r.tmax = r.tmin + uniform(rng, 0.0f, 2.0f * radius);
        }
        rays.push_back(r);
    }
    return rays;
}

// f(i) for i in [0, n) on two threads.
template <class F>
void parallelFor(std::size_t n, F f) {
    std::thread worker([&] {
        for (std::size_t i = 0; i < n; i += 2) f(i);
    });
    for (std::size_t i = 1; i < n; i += 2) f(i);
    worker.join();
}

struct Comparison {
    std::size_t rays = 0, hits = 0, mismatches = 0, degenerateHits = 0;
};

Comparison compareWithBruteForce(const Mesh& m, const Bvh& bvh, const std::vector<Ray>& rays) {
    const auto tris = bvhOrder(bvh, m);
    std::vector<Hit> fast(rays.size()), slow(rays.size());
    parallelFor(rays.size(), [&](std::size_t i) {
        fast[i] = traceClosest(bvh, tris, rays[i]);
        slow[i] = traceBruteForce(tris, rays[i]);
    });
    Comparison c;
    c.rays = rays.size();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Hit& a = fast[i];
        const Hit& b = slow[i];
        auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
        bool same = a.triangle == b.triangle && bits(a.t) == bits(b.t) && bits(a.u) == bits(b.u) &&
                    bits(a.v) == bits(b.v);
        if (!same && c.mismatches++ < 5) {
            MESSAGE("ray " << i << ": bvh tri " << a.triangle << " t " << a.t << ", brute force tri "
                           << b.triangle << " t " << b.t);
        }
        if (b.hit()) {
            ++c.hits;
            if (!m.degenerate.empty() && m.degenerate[bvh.triIndices[b.triangle]]) ++c.degenerateHits;
        }
    }
    return c;
}

// Walks the tree from the root and checks layout, containment, coverage and
// the stats.
void checkStructure(const Mesh& m, const Bvh& bvh) {
    const auto tris = bvhOrder(bvh, m);
    const std::size_t n = m.size();
    REQUIRE(bvh.triIndices.size() == n);
    std::vector<int> seenInput(n, 0), seenSlot(n, 0);
    for (std::uint32_t k : bvh.triIndices) {
        if (k < n) seenInput[k]++;
    }
    CHECK(std::count(seenInput.begin(), seenInput.end(), 1) == std::ptrdiff_t(n));

    auto contains = [](const gpu::BvhNode& outer, const glm::vec3& lo, const glm::vec3& hi) {
        return glm::all(glm::lessThanEqual(outer.bmin, lo)) && glm::all(glm::lessThanEqual(hi, outer.bmax));
    };
    struct Item {
        std::uint32_t index, depth;
    };
    std::vector<Item> stack{{0, 0}};
    std::size_t visited = 0, leaves = 0, badBox = 0, badLayout = 0;
    std::uint32_t maxDepth = 0;
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        ++visited;
        const gpu::BvhNode& node = bvh.nodes[it.index];
        maxDepth = std::max(maxDepth, it.depth);
        if (node.count > 0) {
            ++leaves;
            if (std::size_t(node.leftOrFirst) + node.count > n) {
                ++badLayout;
                continue;
            }
            for (std::uint32_t i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
                seenSlot[i]++;
                for (const glm::vec4& p : {tris[i].v0, tris[i].v1, tris[i].v2}) {
                    if (!contains(node, glm::vec3(p), glm::vec3(p))) ++badBox;
                }
            }
            continue;
        }
        const std::uint32_t left = it.index + 1, right = node.leftOrFirst;
        if (right <= left || right >= bvh.nodes.size()) {
            ++badLayout;
            continue;
        }
        for (std::uint32_t child : {left, right}) {
            if (!contains(node, bvh.nodes[child].bmin, bvh.nodes[child].bmax)) ++badBox;
            stack.push_back({child, it.depth + 1});
        }
    }
    CHECK(badLayout == 0);
    CHECK(badBox == 0);
    CHECK(visited == bvh.nodes.size());
    CHECK(std::count(seenSlot.begin(), seenSlot.end(), 1) == std::ptrdiff_t(n));
    CHECK(bvh.stats.nodes == bvh.nodes.size());
    CHECK(bvh.stats.leaves == leaves);
    CHECK(bvh.stats.maxDepth == maxDepth);
    CHECK(bvh.stats.maxDepth < kBvhStackSize);
    CHECK(bvh.stats.bytes == bvh.nodes.size() * 32);
    CHECK(bvh.stats.sahCost > 0.0);
}

struct Case {
    std::string name;
    Mesh mesh;
    int rays;
    double minHitFraction;
    BvhBuildOptions options = {};
};

std::vector<Case> testCases() {
    std::mt19937 rng(20240611u);
    std::vector<Case> cases;
    cases.push_back({"soup", triangleSoup(rng, 6000), 30000, 0.3});
    cases.push_back({"sphere", uvSphere(64, 32), 25000, 0.5});
    cases.push_back({"heightfield", heightField(rng, 224), 2000, 0.3});
    cases.push_back({"degenerate", withDegenerates(rng, 3000), 30000, 0.3});
    cases.push_back({"chain", exponentialChain(72), 13000, 0.01, {2, 1, 1.0f}});
    return cases;
}

}  // namespace

TEST_CASE("bvh: closest hits equal brute force, and the structure holds") {
    std::mt19937 rng(7u);
    std::size_t totalRays = 0;
    for (Case& c : testCases()) {
        CAPTURE(c.name);
        Bvh bvh = buildBvh(c.mesh.v0, c.mesh.v1, c.mesh.v2, c.options);
        INFO(c.name << ": " << c.mesh.size() << " triangles, " << bvh.stats.nodes << " nodes, depth "
                       << bvh.stats.maxDepth << ", SAH " << bvh.stats.sahCost << ", " << bvh.stats.buildMs
                       << " ms");
        checkStructure(c.mesh, bvh);
        Comparison r = compareWithBruteForce(c.mesh, bvh, makeRays(rng, c.mesh, c.rays));
        CHECK(r.mismatches == 0);
        CHECK(double(r.hits) >= c.minHitFraction * double(r.rays));
        CHECK(r.degenerateHits == 0);
        totalRays += r.rays;
    }
    CHECK(totalRays >= 100000);
}

TEST_CASE("bvh: closed sphere is watertight from inside") {
    Mesh m = uvSphere(96, 48);
    Bvh bvh = buildBvh(m.v0, m.v1, m.v2);
    const auto tris = bvhOrder(bvh, m);
    std::mt19937 rng(11u);
    std::size_t misses = 0;
    // Random rays, and rays from the centre straight at vertices (shared by
    // up to 96 triangles at the poles) and along the axes with +-0 components.
    for (int i = 0; i < 4000; ++i) {
        Ray r{uniformIn(rng, glm::vec3(-0.5f), glm::vec3(0.5f)), unitVector(rng)};
        misses += traceClosest(bvh, tris, r).hit() ? 0 : 1;
    }
    for (std::size_t i = 0; i < m.size(); i += 7) {
        Ray r{glm::vec3(0.0f), m.v1[i]};
        misses += traceClosest(bvh, tris, r).hit() ? 0 : 1;
    }
    for (int s = 0; s < 64; ++s) {
        glm::vec3 d((s & 1) ? -0.0f : 0.0f, (s & 2) ? -0.0f : 0.0f, (s & 4) ? -0.0f : 0.0f);
        d[(s >> 3) % 3] = (s & 32) ? -1.0f : 1.0f;
        misses += traceClosest(bvh, tris, Ray{glm::vec3(0.0f), d}).hit() ? 0 : 1;
    }
    CHECK(misses == 0);
}

TEST_CASE("bvh: degenerate triangles are never hit") {
    std::mt19937 rng(13u);
    Mesh m = withDegenerates(rng, 400);
    Bvh bvh = buildBvh(m.v0, m.v1, m.v2);
    const auto tris = bvhOrder(bvh, m);
    std::size_t degenerateHits = 0, tested = 0;
    for (std::size_t i = 0; i < m.size(); ++i) {
        if (!m.degenerate[i]) continue;
        const glm::vec3 mid = 0.5f * (m.v0[i] + m.v2[i]), centre = (m.v0[i] + m.v1[i] + m.v2[i]) / 3.0f;
        for (const glm::vec3& target : {m.v0[i], m.v1[i], mid, centre}) {
            for (int k = 0; k < 4; ++k) {
                glm::vec3 o = target + 3.0f * unitVector(rng);
                Ray r{o, target - o};
                float t, u, v;
                degenerateHits += intersectTriangle(r, m.v0[i], m.v1[i], m.v2[i], t, u, v) ? 1 : 0;
                for (const Hit& h : {traceClosest(bvh, tris, r), traceBruteForce(tris, r)}) {
                    if (h.hit() && m.degenerate[bvh.triIndices[h.triangle]]) ++degenerateHits;
                }
                ++tested;
            }
        }
    }
    CHECK(tested > 1000);
    CHECK(degenerateHits == 0);
}

TEST_CASE("bvh: intersectTriangle") {
    const glm::vec3 a(0.0f, 0.0f, 0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    float t, u, v;
    SUBCASE("front and back faces, barycentrics of b and c") {
        REQUIRE(intersectTriangle(Ray{{0.25f, 0.5f, 2.0f}, {0.0f, 0.0f, -1.0f}}, a, b, c, t, u, v));
        CHECK(t == 2.0f);
        CHECK(u == 0.25f);
        CHECK(v == 0.5f);
        REQUIRE(intersectTriangle(Ray{{0.25f, 0.5f, -2.0f}, {-0.0f, 0.0f, 1.0f}}, a, b, c, t, u, v));
        CHECK(t == 2.0f);
    }
    SUBCASE("tmin < t < tmax strictly") {
        const glm::vec3 o(0.25f, 0.25f, 2.0f), d(0.0f, 0.0f, -1.0f);
        CHECK_FALSE(intersectTriangle(Ray{o, d, 0.0f, 2.0f}, a, b, c, t, u, v));
        CHECK_FALSE(intersectTriangle(Ray{o, d, 2.0f, 3.0f}, a, b, c, t, u, v));
        CHECK(intersectTriangle(Ray{o, d, 1.99f, 2.01f}, a, b, c, t, u, v));
    }
    SUBCASE("edges and vertices hit, outside missed") {
        CHECK(intersectTriangle(Ray{{0.5f, 0.0f, 1.0f}, {0.0f, -0.0f, -1.0f}}, a, b, c, t, u, v));
        CHECK(intersectTriangle(Ray{{0.5f, 0.5f, 1.0f}, {0.0f, 0.0f, -1.0f}}, a, b, c, t, u, v));
        CHECK(intersectTriangle(Ray{{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, -1.0f}}, a, b, c, t, u, v));
        CHECK_FALSE(intersectTriangle(Ray{{0.5f, 0.51f, 1.0f}, {0.0f, 0.0f, -1.0f}}, a, b, c, t, u, v));
        CHECK_FALSE(intersectTriangle(Ray{{-0.01f, 0.5f, 1.0f}, {0.0f, 0.0f, -1.0f}}, a, b, c, t, u, v));
    }
    SUBCASE("ray in the triangle's plane misses") {
        CHECK_FALSE(intersectTriangle(Ray{{-1.0f, 0.25f, 0.0f}, {1.0f, 0.0f, 0.0f}}, a, b, c, t, u, v));
    }
}

TEST_CASE("bvh: +-0 direction with the origin on a box plane") {
    // The node boxes span y in [0, 1]; the ray runs in the plane y = 0 with
    // direction y = +-0, where (bmin.y - o.y) / dir.y is 0 * inf = NaN.
    Mesh m;
    m.add({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.5f});
    m.add({2.0f, 0.0f, 0.0f}, {3.0f, 0.0f, 1.0f}, {2.0f, 1.0f, 0.5f});
    Bvh bvh = buildBvh(m.v0, m.v1, m.v2, {16, 1, 1.0f});
    const auto tris = bvhOrder(bvh, m);
    for (float zx : {0.0f, -0.0f}) {
        for (float zy : {0.0f, -0.0f}) {
            Hit h = traceClosest(bvh, tris, Ray{{0.5f, 0.0f, 5.0f}, {zx, zy, -1.0f}});
            CHECK(h.hit());
            CHECK(h.t == 4.5f);
            h = traceClosest(bvh, tris, Ray{{2.0f, 0.0f, -5.0f}, {zx, zy, 1.0f}});
            CHECK(h.hit());
            CHECK(h.t == 5.0f);
            CHECK(bvh.triIndices[h.triangle] == 1u);
        }
    }
}

TEST_CASE("bvh: building twice gives identical output") {
    std::mt19937 rng(17u);
    Mesh m = heightField(rng, 224);
    Bvh a = buildBvh(m.v0, m.v1, m.v2);
    Bvh b = buildBvh(m.v0, m.v1, m.v2);
    REQUIRE(a.nodes.size() == b.nodes.size());
    CHECK(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(gpu::BvhNode)) == 0);
    CHECK(a.triIndices == b.triIndices);
    CHECK(a.stats.sahCost == b.stats.sahCost);
    CHECK(a.stats.maxDepth == b.stats.maxDepth);
}

TEST_CASE("bvh: empty input") {
    Bvh bvh = buildBvh({}, {}, {});
    REQUIRE(bvh.nodes.size() == 1);
    CHECK(bvh.nodes[0].count == 0);
    CHECK(bvh.nodes[0].leftOrFirst == 0);
    CHECK(bvh.nodes[0].bmin.x > bvh.nodes[0].bmax.x);
    CHECK(bvh.triIndices.empty());
    CHECK(bvh.stats.nodes == 1);
    CHECK(bvh.stats.leaves == 0);
    CHECK(bvh.stats.bytes == 32);
    const std::vector<gpu::TriVerts> none;
    CHECK_FALSE(traceClosest(bvh, none, Ray{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}}).hit());
    CHECK_FALSE(traceClosest(bvh, none, Ray{{NAN, 0.0f, 0.0f}, {0.0f, -0.0f, 1.0f}}).hit());
    CHECK_FALSE(traceBruteForce(none, Ray{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}}).hit());
}

TEST_CASE("bvh: single triangle and all-coincident centroids") {
    Mesh one;
    one.add({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    Bvh bvh = buildBvh(one.v0, one.v1, one.v2);
    REQUIRE(bvh.nodes.size() == 1);
    CHECK(bvh.nodes[0].count == 1);
    CHECK(bvh.stats.sahCost == 1.0);
    CHECK(traceClosest(bvh, bvhOrder(bvh, one), Ray{{0.2f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}}).t == 1.0f);

    Mesh same;  // 40 copies: cannot be split, one leaf above maxLeafSize
    for (int i = 0; i < 40; ++i) same.add({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    Bvh s = buildBvh(same.v0, same.v1, same.v2);
    REQUIRE(s.nodes.size() == 1);
    CHECK(s.nodes[0].count == 40);
    CHECK(s.stats.sahCost == 40.0);
    Hit h = traceClosest(s, bvhOrder(s, same), Ray{{0.2f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}});
    CHECK(h.triangle == 0u);
}

}  // namespace strata

namespace strata {

// Large enough for the parallel top levels (chunked binning and partition,
// subtrees as tasks): the output must not depend on the thread count, and the
// tree must match the one-thread builder of before (the SAH cost recorded
// here, within float rounding of the sum).
TEST_CASE("bvh: parallel build equals the one-thread build") {
    std::mt19937 rng(99u);
    Mesh m = withDegenerates(rng, 48000);
    Mesh hf = heightField(rng, 160);
    for (std::size_t i = 0; i < hf.size(); ++i) m.add(hf.v0[i], hf.v1[i], hf.v2[i]);
    BvhBuildOptions one;
    one.threads = 1;
    const Bvh a = buildBvh(m.v0, m.v1, m.v2, one);
    MESSAGE(m.size() << " triangles, SAH " << std::setprecision(10) << a.stats.sahCost);
    checkStructure(m, a);
    CHECK(a.stats.sahCost <= 379.629969 * (1.0 + 1e-6));  // before the parallel builder
    for (int threads : {2, 3, 8}) {
        CAPTURE(threads);
        BvhBuildOptions options;
        options.threads = threads;
        const Bvh b = buildBvh(m.v0, m.v1, m.v2, options);
        REQUIRE(a.nodes.size() == b.nodes.size());
        CHECK(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(gpu::BvhNode)) == 0);
        CHECK(a.triIndices == b.triIndices);
        CHECK(a.stats.sahCost == b.stats.sahCost);
        CHECK(a.stats.maxDepth == b.stats.maxDepth);
    }
    std::mt19937 rayRng(5u);
    Comparison r = compareWithBruteForce(m, a, makeRays(rayRng, m, 1500));
    CHECK(r.mismatches == 0);
    CHECK(r.degenerateHits == 0);
}

}  // namespace strata


namespace strata {
namespace {

// A wide leaf reference's first triangle and triangle count (gpu::BvhNode4).
std::uint32_t leafFirst(std::uint32_t ref) { return (ref & ~gpu::kBvhLeafBit) >> gpu::kBvhLeafCountBits; }
std::uint32_t leafCount(std::uint32_t ref) { return (ref & ((1u << gpu::kBvhLeafCountBits) - 1u)) + 1u; }

// SAH cost of a wide tree as WideBvh::sahCost defines it, from its boxes.
double wideSah(const WideBvh& w) {
    double sum = 0.0, rootArea = 0.0;
    auto area = [](const gpu::BvhNode4& n, int k) {
        const double ex = double(n.maxX[k]) - n.minX[k], ey = double(n.maxY[k]) - n.minY[k],
                     ez = double(n.maxZ[k]) - n.minZ[k];
        return ex * ey + ey * ez + ez * ex;
    };
    for (const gpu::BvhNode4& n : w.nodes)
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t ref = n.child[k];
            if (ref == gpu::kBvhChildEmpty) continue;
            const bool leaf = (ref & gpu::kBvhLeafBit) != 0;
            sum += area(n, k) * (leaf ? double(leafCount(ref)) : kWideNodeCost);
        }
    // The root's box: the union of its children's.
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    const gpu::BvhNode4& r = w.nodes[0];
    for (int k = 0; k < 4; ++k)
        if (r.child[k] != gpu::kBvhChildEmpty) {
            lo = glm::min(lo, glm::dvec3(r.minX[k], r.minY[k], r.minZ[k]));
            hi = glm::max(hi, glm::dvec3(r.maxX[k], r.maxY[k], r.maxZ[k]));
        }
    const glm::dvec3 e = hi - lo;
    rootArea = e.x * e.y + e.y * e.z + e.z * e.x;
    return kWideNodeCost + sum / rootArea;
}

// The same cost for the collapse in which a wide node holds its BVH2 node's
// grandchildren (a child that is a leaf stays one slot).
double grandchildrenSah(const Bvh& bvh) {
    const auto& nodes = bvh.nodes;
    auto area = [&](std::uint32_t i) {
        const glm::dvec3 e = glm::dvec3(nodes[i].bmax) - glm::dvec3(nodes[i].bmin);
        return e.x * e.y + e.y * e.z + e.z * e.x;
    };
    std::function<double(std::uint32_t)> slots = [&](std::uint32_t i) {  // the children of wide node i
        double sum = 0.0;
        for (std::uint32_t c : {i + 1, nodes[i].leftOrFirst}) {
            if (nodes[c].count > 0) {
                sum += area(c) * nodes[c].count;
                continue;
            }
            for (std::uint32_t g : {c + 1, nodes[c].leftOrFirst})
                sum += nodes[g].count > 0 ? area(g) * nodes[g].count : area(g) * kWideNodeCost + slots(g);
        }
        return sum;
    };
    return kWideNodeCost + slots(0) / area(0);
}

// Walks the four-wide tree: every input triangle is referenced exactly once,
// every child box holds its subtree, empty slots are empty, no wide node is
// unreachable, and maxDepth is the deepest leaf reference.
void checkWide(const Mesh& m, const Bvh& bvh, const WideBvh& w) {
    const std::size_t n = m.size();
    std::vector<int> seen(n, 0);
    std::vector<int> reached(w.nodes.size(), 0);
    std::uint32_t deepest = 0;
    std::size_t badBox = 0, badEmpty = 0;
    struct Item { std::uint32_t node, depth; glm::vec3 lo, hi; };
    std::vector<Item> pending{{0, 0, glm::vec3(-INFINITY), glm::vec3(INFINITY)}};
    auto inside = [](glm::vec3 p, glm::vec3 lo, glm::vec3 hi) {
        return glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi));
    };
    while (!pending.empty()) {
        const Item it = pending.back();
        pending.pop_back();
        REQUIRE(it.node < w.nodes.size());
        ++reached[it.node];
        const gpu::BvhNode4& wn = w.nodes[it.node];
        for (int k = 0; k < 4; ++k) {
            const glm::vec3 lo(wn.minX[k], wn.minY[k], wn.minZ[k]), hi(wn.maxX[k], wn.maxY[k], wn.maxZ[k]);
            const std::uint32_t c = wn.child[k];
            if (c == gpu::kBvhChildEmpty) {
                badEmpty += !(lo.x > hi.x && lo.y > hi.y && lo.z > hi.z);
                continue;
            }
            if (!inside(lo, it.lo, it.hi) || !inside(hi, it.lo, it.hi)) ++badBox;
            if (c & gpu::kBvhLeafBit) {
                const std::uint32_t first = leafFirst(c), count = leafCount(c);
                deepest = std::max(deepest, it.depth + 1);
                for (std::uint32_t i = first; i < first + count; ++i) {
                    REQUIRE(i < n);
                    const std::uint32_t t = bvh.triIndices[i];
                    ++seen[t];
                    for (const glm::vec3& v : {m.v0[t], m.v1[t], m.v2[t]}) badBox += !inside(v, lo, hi);
                }
            } else {
                pending.push_back({c, it.depth + 1, lo, hi});
            }
        }
    }
    CHECK(std::count(seen.begin(), seen.end(), 1) == std::ptrdiff_t(n));
    CHECK(std::count(reached.begin(), reached.end(), 1) == std::ptrdiff_t(w.nodes.size()));
    CHECK(badBox == 0);
    CHECK(badEmpty == 0);
    CHECK(w.maxDepth == deepest);
}

}  // namespace

TEST_CASE("wide bvh: collapsed tree covers every triangle once, boxes nest") {
    for (Case& c : testCases()) {
        CAPTURE(c.name);
        Bvh bvh = buildBvh(c.mesh.v0, c.mesh.v1, c.mesh.v2, c.options);
        WideBvh w = collapseBvh4(bvh.nodes);
        INFO(c.name << ": " << bvh.nodes.size() << " BVH2 nodes, depth " << bvh.stats.maxDepth << "; "
                    << w.nodes.size() << " wide nodes, depth " << w.maxDepth);
        checkWide(c.mesh, bvh, w);
        // Each wide node stands for a distinct BVH2 interior node.
        CHECK(w.nodes.size() <= bvh.stats.nodes - bvh.stats.leaves);
        CHECK(w.maxDepth <= bvh.stats.maxDepth);
        // The reported cost is the tree's, and no more than that of another
        // collapse the optimum chooses among: each wide node taking its BVH2
        // node's grandchildren.
        const double cost = wideSah(w);
        CHECK(w.sahCost == doctest::Approx(cost).epsilon(1e-4));
        CHECK(w.sahCost <= grandchildrenSah(bvh) * (1.0 + 1e-5));
        // A leaf is a BVH2 leaf or a subtree of at most kWideLeafMax triangles.
        std::set<std::pair<std::uint32_t, std::uint32_t>> bvh2Leaves;
        for (const gpu::BvhNode& n : bvh.nodes)
            if (n.count > 0) bvh2Leaves.insert({n.leftOrFirst, n.count});
        std::size_t oversized = 0;
        for (const gpu::BvhNode4& n : w.nodes)
            for (int k = 0; k < 4; ++k)
                if (const std::uint32_t ref = n.child[k]; ref != gpu::kBvhChildEmpty && (ref & gpu::kBvhLeafBit)) {
                    const std::uint32_t count = leafCount(ref);
                    oversized += count > kWideLeafMax && !bvh2Leaves.count({leafFirst(ref), count});
                }
        CHECK(oversized == 0);
    }
}

// Triangles along one line: every box has no area, so the plan finds an
// interior node no dearer as one slot than its children and keeps it in
// one (a fuzzed scene found this: the collapse then gathered five children
// into a node's four slots, tests/data/fuzz/gltf/stack-overflow-bvh4-*).
TEST_CASE("wide bvh: subtrees whose cost is not a number still fill at most four slots") {
    // Flat (y = 0) triangles, three of them across the float range in x:
    // the boxes above those have an infinite side and a zero one, so their
    // area, inf x 0, is NaN. The plan then keeps such a node in one slot
    // (a fuzzed scene found this: the collapse gathered five children into
    // a node's four slots, tests/data/fuzz/gltf/stack-overflow-bvh4-*).
    std::mt19937 rng(5u);
    std::uniform_real_distribution<float> u(0.0f, 10.0f);
    Mesh m;
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 a(u(rng), 0.0f, u(rng));
        m.add(a, a + glm::vec3(0.3f, 0.0f, 0.1f), a + glm::vec3(0.1f, 0.0f, 0.3f));
    }
    for (int i = 0; i < 3; ++i) m.add({-3.0e38f, 0.0f, float(i)}, {3.0e38f, 0.0f, float(i)}, {0.0f, 0.0f, float(i) + 1.0f});
    const Bvh bvh = buildBvh(m.v0, m.v1, m.v2);
    const WideBvh w = collapseBvh4(bvh.nodes);
    checkWide(m, bvh, w);
}

// Large enough that the plan splits into subtrees planned in parallel
// (kPlanMinNodes in host/bvh/wide.cpp): the tree must not depend on the
// thread count.
TEST_CASE("wide bvh: the parallel collapse equals the one-thread collapse") {
    std::mt19937 rng(31u);
    Mesh m = triangleSoup(rng, 40000);
    Mesh hf = heightField(rng, 120);
    for (std::size_t i = 0; i < hf.size(); ++i) m.add(hf.v0[i], hf.v1[i], hf.v2[i]);
    const Bvh bvh = buildBvh(m.v0, m.v1, m.v2);
    REQUIRE(bvh.nodes.size() > 4u * (1u << 14));
    const WideBvh a = collapseBvh4(bvh.nodes, 1);
    checkWide(m, bvh, a);
    for (unsigned threads : {2u, 3u, 8u}) {
        CAPTURE(threads);
        const WideBvh b = collapseBvh4(bvh.nodes, threads);
        REQUIRE(a.nodes.size() == b.nodes.size());
        CHECK(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(gpu::BvhNode4)) == 0);
        CHECK(a.sahCost == b.sahCost);
        CHECK(a.maxDepth == b.maxDepth);
    }
}

TEST_CASE("wide bvh: the collapse merges small subtrees into leaves where that lowers the cost") {
    // Eight tiny triangles in a corner of a big box: the BVH2 (leaves of one
    // triangle) splits them apart; one leaf of eight under a wide node is cheaper.
    Mesh m;
    for (int i = 0; i < 8; ++i) {
        const float x = 0.01f * float(i);
        m.add({x, 0.0f, 0.0f}, {x + 0.005f, 0.0f, 0.0f}, {x, 0.005f, 0.0f});
    }
    m.add({100.0f, 100.0f, 100.0f}, {101.0f, 100.0f, 100.0f}, {100.0f, 101.0f, 100.0f});
    Bvh bvh = buildBvh(m.v0, m.v1, m.v2, {16, 1, 1.0f});
    REQUIRE(bvh.stats.leaves == 9);
    WideBvh w = collapseBvh4(bvh.nodes);
    checkWide(m, bvh, w);
    std::size_t merged = 0;
    for (const gpu::BvhNode4& n : w.nodes)
        for (int k = 0; k < 4; ++k)
            if (const std::uint32_t ref = n.child[k]; ref != gpu::kBvhChildEmpty && (ref & gpu::kBvhLeafBit))
                merged += leafCount(ref) > 1u;
    CHECK(merged > 0);
    CHECK(w.sahCost <= grandchildrenSah(bvh));
}

namespace {

// The stack discipline of the shader's four-wide traversal
// (shaders/lib/bvh4.glsl, bvhTrace4) on the CPU with an unbounded stack: one
// entry per wide node on the path, pushed with its children still to visit.
// (The shader groups these steps two node passes to an iteration and may
// push a node back with a second leaf it cannot test yet, which changes
// neither the hits nor the entries held.) Its closest hits equal brute force,
// and it never holds more entries than the wide depth, the bound the
// shader's register stack is sized by (bvhRegsFor).
struct WideTrace {
    Hit hit;
    std::uint32_t maxEntries = 0;
};

WideTrace traceWide(const WideBvh& w, const std::vector<gpu::TriVerts>& tris, const Ray& ray) {
    const glm::vec3 inv(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
    WideTrace out;
    float bestT = ray.tmax;
    std::vector<std::uint32_t> stack;
    std::uint32_t ref = 15u;
    for (;;) {
        bool descend = false;
        if (ref & gpu::kBvhLeafBit) {
            const std::uint32_t first = leafFirst(ref), end = first + leafCount(ref);
            for (std::uint32_t i = first; i < end; ++i) {
                float t, u, v;
                const auto& tv = tris[i];
                if (intersectTriangle(Ray{ray.origin, ray.dir, ray.tmin, ray.tmax}, glm::vec3(tv.v0),
                                      glm::vec3(tv.v1), glm::vec3(tv.v2), t, u, v) &&
                    (t < bestT || (t == bestT && i < out.hit.triangle))) {
                    bestT = t;
                    out.hit = Hit{t, i, u, v};
                }
            }
        } else {
            const gpu::BvhNode4& n = w.nodes[ref >> 4];
            float best = INFINITY;
            int slot = -1;
            std::uint32_t mask = 0;
            for (int k = 0; k < 4; ++k) {
                if (!(ref & (1u << k)) || n.child[k] == gpu::kBvhChildEmpty) continue;
                // A slightly widened slab test: a superset of the shader's boxes.
                float tnear = ray.tmin, tfar = bestT;
                const float lo[3] = {n.minX[k], n.minY[k], n.minZ[k]}, hi[3] = {n.maxX[k], n.maxY[k], n.maxZ[k]};
                for (int a = 0; a < 3; ++a) {
                    float t0 = (lo[a] - ray.origin[a]) * inv[a], t1 = (hi[a] - ray.origin[a]) * inv[a];
                    if (std::signbit(ray.dir[a])) std::swap(t0, t1);  // by sign, as NaNs need
                    tnear = t0 > tnear ? t0 : tnear;
                    tfar = t1 < tfar ? t1 : tfar;
                }
                if (!(tnear <= tfar * 1.0001f)) continue;
                mask |= 1u << k;
                if (tnear < best || slot < 0) best = tnear, slot = k;
            }
            if (mask) {
                const std::uint32_t rest = mask & ~(1u << slot);
                if (rest) stack.push_back((ref & ~15u) | rest);
                out.maxEntries = std::max(out.maxEntries, std::uint32_t(stack.size()));
                const std::uint32_t c = n.child[slot];
                ref = (c & gpu::kBvhLeafBit) ? c : (c << 4) | 15u;
                descend = true;
            }
        }
        if (descend) continue;
        if (stack.empty()) break;
        ref = stack.back();
        stack.pop_back();
    }
    return out;
}

}  // namespace

TEST_CASE("wide bvh: the register-stack traversal finds the brute-force hits within the wide depth") {
    std::mt19937 rng(31u);
    for (Case& c : testCases()) {
        CAPTURE(c.name);
        Bvh bvh = buildBvh(c.mesh.v0, c.mesh.v1, c.mesh.v2, c.options);
        WideBvh w = collapseBvh4(bvh.nodes);
        const std::vector<gpu::TriVerts> tris = bvhOrder(bvh, c.mesh);
        std::size_t mismatches = 0, hits = 0;
        std::uint32_t most = 0;
        for (const Ray& r : makeRays(rng, c.mesh, 4000)) {
            const WideTrace wt = traceWide(w, tris, r);
            const Hit ref = traceBruteForce(tris, r);
            hits += ref.hit();
            mismatches += wt.hit.triangle != ref.triangle || (ref.hit() && wt.hit.t != ref.t);
            most = std::max(most, wt.maxEntries);
        }
        INFO("wide depth " << w.maxDepth << ", most entries held " << most);
        CHECK(mismatches == 0);
        CHECK(hits > 0);
        CHECK(most <= w.maxDepth);
    }
}

TEST_CASE("wide bvh: empty input, a leaf root, and a leaf above the reference's count") {
    Bvh empty = buildBvh({}, {}, {});
    WideBvh we = collapseBvh4(empty.nodes);
    REQUIRE(we.nodes.size() == 1);
    for (int k = 0; k < 4; ++k) CHECK(we.nodes[0].child[k] == gpu::kBvhChildEmpty);
    CHECK(we.maxDepth == 0);

    Mesh one;
    one.add({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    Bvh b1 = buildBvh(one.v0, one.v1, one.v2);
    WideBvh w1 = collapseBvh4(b1.nodes);
    REQUIRE(w1.nodes.size() == 1);
    CHECK(w1.nodes[0].child[0] == gpu::kBvhLeafBit);  // first 0, count 1
    checkWide(one, b1, w1);

    Mesh same;  // 100 copies: one BVH2 leaf, more than 2^kBvhLeafCountBits triangles
    for (int i = 0; i < 100; ++i) same.add({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    Bvh bs = buildBvh(same.v0, same.v1, same.v2);
    REQUIRE(bs.nodes.size() == 1);
    WideBvh ws = collapseBvh4(bs.nodes);
    CHECK(ws.nodes.size() == 2);  // the root and one node of four chunks (32 + 32 + 32 + 4)
    CHECK(ws.maxDepth == 2);
    checkWide(same, bs, ws);
}

TEST_CASE("wide bvh: stack registers follow the wide depth") {
    CHECK(bvhRegsFor(0) == 16);
    CHECK(bvhRegsFor(16) == 16);
    CHECK(bvhRegsFor(17) == 24);
    CHECK(bvhRegsFor(32) == 32);
    CHECK(bvhRegsFor(33) == 0);
}

}  // namespace strata

TEST_SUITE_END();
