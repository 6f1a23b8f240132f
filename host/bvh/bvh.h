// Binned SAH BVH2 over triangles, flattened depth-first into the 32-byte
// nodes shared with GLSL (shaders/shared/types.h).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "../../shaders/shared/types.h"

namespace strata {

struct BvhBuildOptions {
    int bins = 16;            // SAH bins per axis (>= 16)
    int maxLeafSize = 8;      // a node with more triangles is always split
    float traversalCost = 1.0f;  // SAH cost of an interior node, relative to
                                 // one triangle intersection
};

struct BvhStats {
    std::uint32_t nodes = 0;
    std::uint32_t leaves = 0;
    std::uint32_t maxDepth = 0;
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
// (zero area, collinear) are kept; they are never hit.
Bvh buildBvh(const std::vector<glm::vec3>& v0, const std::vector<glm::vec3>& v1,
             const std::vector<glm::vec3>& v2, const BvhBuildOptions& options = {});

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

// Watertight ray/triangle test (Woop, Benthin, Wald 2013). Returns true and
// fills t/u/v when the ray hits within (tmin, tmax).
bool intersectTriangle(const Ray& ray, const glm::vec3& a, const glm::vec3& b,
                       const glm::vec3& c, float& t, float& u, float& v);

// Closest hit, CPU reference traversal of the flattened BVH. `tris` are in BVH
// order (tris[i] = input triangle bvh.triIndices[i]).
Hit traceClosest(const Bvh& bvh, const std::vector<gpu::TriVerts>& tris, const Ray& ray);

// Closest hit by testing every triangle (BVH order), for tests.
Hit traceBruteForce(const std::vector<gpu::TriVerts>& tris, const Ray& ray);

}  // namespace strata
