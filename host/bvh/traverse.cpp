// CPU reference traversal of the flattened BVH2. shaders/lib/bvh2.glsl mirrors
// it step for step (same triangle test, slab test, child order and tie rule).
// Nothing here may be contracted into FMAs: watertightness relies on two
// triangles evaluating a shared edge identically, and the comparison with
// brute force on t being computed the same wherever intersect() is inlined
// (with -march=x86-64-v3 and contraction, both failed). The pragmas below
// turn contraction off for this file.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "bvh/bvh.h"

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

namespace strata {
namespace {

// 1 + 2*gamma(3), gamma(n) = n*u / (1 - n*u), u = 2^-24, rounded up to a float
// (1 + 4 * 2^-23). Scaling the far end of a slab interval by it makes the
// ray/box test conservative under float rounding (Ize 2013, "Robust BVH Ray
// Traversal", JCGT 2(2)).
constexpr float kSlabScale = 1.0f + 4.0f * 0x1p-23f;

// Per-ray constants of the slab test and of the watertight triangle test.
struct RayPre {
    glm::vec3 origin;
    glm::vec3 invDir;  // 1/dir; +-inf for a +-0 component
    bool neg[3];       // sign bit of dir: the slab's near plane is bmax
    int kx, ky, kz;    // kz: axis of largest |dir|; (kx, ky, kz) keeps winding
    float sx, sy, sz;  // shear to the ray's space: dir maps to (0, 0, 1)
};

RayPre prepareRay(const glm::vec3& origin, const glm::vec3& dir) {
    RayPre r;
    r.origin = origin;
    for (int a = 0; a < 3; ++a) {
        r.invDir[a] = 1.0f / dir[a];
        r.neg[a] = std::signbit(dir[a]);
    }
    const float ax = std::fabs(dir.x), ay = std::fabs(dir.y), az = std::fabs(dir.z);
    r.kz = (ax >= ay) ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    r.kx = r.kz == 2 ? 0 : r.kz + 1;
    r.ky = r.kx == 2 ? 0 : r.kx + 1;
    if (dir[r.kz] < 0.0f) std::swap(r.kx, r.ky);
    r.sx = dir[r.kx] / dir[r.kz];
    r.sy = dir[r.ky] / dir[r.kz];
    r.sz = 1.0f / dir[r.kz];
    return r;
}

// Woop, Benthin, Wald 2013, "Watertight Ray/Triangle Intersection", JCGT 2(1),
// without backface culling. t is computed first and compared with (tmin,
// tmax) afterwards, so the decision depends on t alone.
bool intersect(const RayPre& r, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
               float tmin, float tmax, float& tOut, float& uOut, float& vOut) {
    const float A[3] = {a.x - r.origin.x, a.y - r.origin.y, a.z - r.origin.z};
    const float B[3] = {b.x - r.origin.x, b.y - r.origin.y, b.z - r.origin.z};
    const float C[3] = {c.x - r.origin.x, c.y - r.origin.y, c.z - r.origin.z};
    const float Ax = A[r.kx] - r.sx * A[r.kz];
    const float Ay = A[r.ky] - r.sy * A[r.kz];
    const float Bx = B[r.kx] - r.sx * B[r.kz];
    const float By = B[r.ky] - r.sy * B[r.kz];
    const float Cx = C[r.kx] - r.sx * C[r.kz];
    const float Cy = C[r.ky] - r.sy * C[r.kz];

    float U = Cx * By - Cy * Bx;
    float V = Ax * Cy - Ay * Cx;
    float W = Bx * Ay - By * Ax;
    // Bitwise | and & on the comparisons: fewer unpredictable branches.
    if ((U == 0.0f) | (V == 0.0f) | (W == 0.0f)) {
        // Products of two floats are exact in double: only the difference rounds.
        U = float(double(Cx) * double(By) - double(Cy) * double(Bx));
        V = float(double(Ax) * double(Cy) - double(Ay) * double(Cx));
        W = float(double(Bx) * double(Ay) - double(By) * double(Ax));
    }
    const bool anyNegative = (U < 0.0f) | (V < 0.0f) | (W < 0.0f);
    const bool anyPositive = (U > 0.0f) | (V > 0.0f) | (W > 0.0f);
    if (anyNegative & anyPositive) return false;
    const float det = U + V + W;
    if (det == 0.0f) return false;

    const float Az = r.sz * A[r.kz];
    const float Bz = r.sz * B[r.kz];
    const float Cz = r.sz * C[r.kz];
    const float T = U * Az + V * Bz + W * Cz;
    const float rcpDet = 1.0f / det;
    const float t = T * rcpDet;
    if (!(t > tmin && t < tmax)) return false;

    // Degenerate: the float cross product of the edges is exactly zero.
    const glm::vec3 e1 = b - a, e2 = c - a;
    const float nx = e1.y * e2.z - e1.z * e2.y;
    const float ny = e1.z * e2.x - e1.x * e2.z;
    const float nz = e1.x * e2.y - e1.y * e2.x;
    if (nx == 0.0f && ny == 0.0f && nz == 0.0f) return false;

    tOut = t;
    uOut = V * rcpDet;
    vOut = W * rcpDet;
    return true;
}

// Slab test (Kay & Kajiya 1986) against [tmin, tmax]. A 0 * inf product (origin
// on a slab plane, direction component 0) is NaN; `x > acc ? x : acc` and
// `x < acc ? x : acc` keep acc then, so that axis does not limit the interval
// (the box is closed). Returns the entry distance max(tmin, near) in tEntry.
bool slab(const RayPre& r, const gpu::BvhNode& node, float tmin, float tmax, float& tEntry) {
    float tnear = tmin;
    float tfar = tmax;
    for (int a = 0; a < 3; ++a) {
        const float t0 = (node.bmin[a] - r.origin[a]) * r.invDir[a];
        const float t1 = (node.bmax[a] - r.origin[a]) * r.invDir[a];
        const float lo = r.neg[a] ? t1 : t0;
        const float hi = r.neg[a] ? t0 : t1;
        tnear = lo > tnear ? lo : tnear;
        tfar = hi < tfar ? hi : tfar;
    }
    tEntry = tnear;
    return tnear <= tfar * kSlabScale;
}

inline glm::vec3 xyz(const glm::vec4& v) { return glm::vec3(v.x, v.y, v.z); }

// Closest-hit bookkeeping shared by both traversals: a hit replaces the best
// one if nearer, or equally near with a lower BVH-order index.
struct Best {
    float t;
    std::uint32_t tri = gpu::kNoHit;
    float u = 0.0f, v = 0.0f;

    void test(const RayPre& r, const gpu::TriVerts& tri3, std::uint32_t i, float tmin, float tmax) {
        float t, u, v;
        if (intersect(r, xyz(tri3.v0), xyz(tri3.v1), xyz(tri3.v2), tmin, tmax, t, u, v) &&
            (t < this->t || (t == this->t && i < this->tri))) {
            this->t = t;
            this->tri = i;
            this->u = u;
            this->v = v;
        }
    }
    Hit hit() const {
        Hit h;
        if (tri != gpu::kNoHit) {
            h.t = t;
            h.triangle = tri;
            h.u = u;
            h.v = v;
        }
        return h;
    }
};

}  // namespace

bool intersectTriangle(const Ray& ray, const glm::vec3& a, const glm::vec3& b,
                       const glm::vec3& c, float& t, float& u, float& v) {
    return intersect(prepareRay(ray.origin, ray.dir), a, b, c, ray.tmin, ray.tmax, t, u, v);
}

Hit traceClosest(const Bvh& bvh, const std::vector<gpu::TriVerts>& tris, const Ray& ray) {
    Best best{ray.tmax};
    if (bvh.nodes.empty()) return best.hit();
    const RayPre r = prepareRay(ray.origin, ray.dir);
    std::uint32_t index = 0;
    gpu::BvhNode node = bvh.nodes[0];
    float tEntry;
    if ((node.count == 0 && node.leftOrFirst == 0) || !slab(r, node, ray.tmin, ray.tmax, tEntry)) {
        return best.hit();
    }
    std::uint32_t stack[kBvhStackSize];
    std::uint32_t sp = 0;
    for (;;) {
        if (node.count > 0) {
            for (std::uint32_t i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
                best.test(r, tris[i], i, ray.tmin, ray.tmax);
            }
        } else {
            const std::uint32_t left = index + 1, right = node.leftOrFirst;
            const gpu::BvhNode& nl = bvh.nodes[left];
            const gpu::BvhNode& nr = bvh.nodes[right];
            float tl, tr;
            const bool hl = slab(r, nl, ray.tmin, best.t, tl);
            const bool hr = slab(r, nr, ray.tmin, best.t, tr);
            if (hl && hr) {
                const bool rightFirst = tr < tl;
                if (sp < kBvhStackSize) stack[sp++] = rightFirst ? left : right;
                index = rightFirst ? right : left;
                node = rightFirst ? nr : nl;
                continue;
            }
            if (hl || hr) {
                index = hl ? left : right;
                node = hl ? nl : nr;
                continue;
            }
        }
        if (sp == 0) break;
        index = stack[--sp];
        node = bvh.nodes[index];
    }
    return best.hit();
}

Hit traceBruteForce(const std::vector<gpu::TriVerts>& tris, const Ray& ray) {
    Best best{ray.tmax};
    const RayPre r = prepareRay(ray.origin, ray.dir);
    for (std::uint32_t i = 0; i < std::uint32_t(tris.size()); ++i) {
        best.test(r, tris[i], i, ray.tmin, ray.tmax);
    }
    return best.hit();
}

}  // namespace strata
