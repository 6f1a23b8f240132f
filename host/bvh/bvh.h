// Binned SAH BVH2 over triangles, flattened depth-first into the 32-byte
// nodes shared with GLSL (shaders/shared/types.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/glm.hpp>

#include "../../shaders/shared/types.h"

namespace strata {

// Entries of the fixed traversal stack (here and in shaders/lib/bvh2.glsl). A
// traversal holds at most maxDepth entries; buildBvh guarantees
// stats.maxDepth < kBvhStackSize by splitting at the object median where
// depth + ceil(log2(triangles)) would reach kBvhStackSize - 1.
inline constexpr std::uint32_t kBvhStackSize = 64;

struct BvhBuildOptions {
    int bins = 16;            // SAH bins per axis (16 or more; clamped to [2, 256])
    int maxLeafSize = 8;      // a node with more triangles is always split
    float traversalCost = 1.0f;  // SAH cost of an interior node, relative to
                                 // one triangle intersection
    int threads = 0;          // build threads; 0: std::thread::hardware_concurrency()
};

struct BvhStats {
    std::uint32_t nodes = 0;
    std::uint32_t leaves = 0;
    std::uint32_t maxDepth = 0;  // edges from the root to the deepest leaf
    double sahCost = 0.0;     // expected cost per ray, relative to the root area
    double buildMs = 0.0;
    std::uint64_t bytes = 0;  // nodes only
};

struct Bvh {
    std::vector<gpu::BvhNode> nodes;          // depth-first; nodes[0] is the root
    std::vector<std::uint32_t> triIndices;    // BVH order -> input triangle index
    BvhStats stats;
};

// Builds over triangles given by their three vertices. Degenerate triangles
// (zero area, collinear) are kept; they are never hit. Output depends only on
// the input and options other than `threads`: neither the thread count nor
// thread timing changes it.
// No triangles: nodes holds one node with an empty box (bmin = +inf,
// bmax = -inf), count 0 and leftOrFirst 0; stats.leaves is 0. An interior
// node always has leftOrFirst >= 2, so traversals treat a root with
// count == 0 && leftOrFirst == 0 as a miss before testing its box.
Bvh buildBvh(const std::vector<glm::vec3>& v0, const std::vector<glm::vec3>& v1,
             const std::vector<glm::vec3>& v2, const BvhBuildOptions& options = {});

// The builder's view of its input without a copy: vertex k of triangle i is
// the glm::vec3 at base[k] + i * stride bytes (an array of structs holding
// the three vertices, or three arrays with stride sizeof(glm::vec3)).
struct TriangleVertices {
    const std::byte* base[3] = {nullptr, nullptr, nullptr};
    std::size_t stride = sizeof(glm::vec3);
    std::size_t count = 0;
    glm::vec3 vertex(std::size_t i, int k) const {
        glm::vec3 v;
        std::memcpy(&v, base[k] + i * stride, sizeof v);
        return v;
    }
};

// The same over a view; what buildBvh above calls.
Bvh buildBvh(const TriangleVertices& triangles, const BvhBuildOptions& options = {});

struct Ray {
    glm::vec3 origin;
    glm::vec3 dir;
    float tmin = 0.0f;
    float tmax = 1e30f;
};

struct Hit {
    float t = -1.0f;
    std::uint32_t triangle = gpu::kNoHit;  // BVH-order index
    float u = 0.0f, v = 0.0f;
    bool hit() const { return triangle != gpu::kNoHit; }
};

// Watertight ray/triangle test (Woop, Benthin, Wald 2013), both faces. Returns
// true and fills t/u/v (barycentric weights of b and c) when the ray hits with
// tmin < t < tmax. A triangle whose float cross((b - a), (c - a)) is exactly
// zero is degenerate and never hit.
bool intersectTriangle(const Ray& ray, const glm::vec3& a, const glm::vec3& b,
                       const glm::vec3& c, float& t, float& u, float& v);

// Closest hit, CPU reference traversal of the flattened BVH. `tris` are in BVH
// order (tris[i] = input triangle bvh.triIndices[i]). Among hits at equal t the
// lowest BVH-order index wins, here and in traceBruteForce, so both agree
// exactly.
Hit traceClosest(const Bvh& bvh, const std::vector<gpu::TriVerts>& tris, const Ray& ray);

// Closest hit by testing every triangle (BVH order), for tests.
Hit traceBruteForce(const std::vector<gpu::TriVerts>& tris, const Ray& ray);

}  // namespace strata
