// What the BVH traversals (lib/bvh2.glsl, lib/bvh4.glsl) share: the per-ray
// constants, Woop et al.'s watertight triangle test, the slab tests, the
// leaf loops with their tie rule, the loop-budget counter gBvhTicks and the
// hit result. Mirrors host/bvh/traverse.cpp; lib/bvh.glsl lists what the
// including shader defines and the differences from the C++.
#ifndef STRATA_LIB_BVH_COMMON_GLSL
#define STRATA_LIB_BVH_COMMON_GLSL

#include "shared/types.h"

// 1 + 2*gamma(7), gamma(n) = n*u / (1 - n*u), u = 2^-24, rounded up to a float
// (1 + 8 * 2^-23): Ize 2013 ("Robust BVH Ray Traversal", JCGT 2(2)) with
// 1/d and (b - o) * (1/d) carrying 2.5 + 0.5 + 0.5 ULP instead of 3 x 0.5.
const float kBvhSlabScale = 1.00000095367431640625;

// An upper bound, per lane, of the loop iterations lavapipe counts for the
// traversals of this invocation. gallivm keeps one loop limiter per
// invocation for all its loops together and ends every loop once 65535
// iterations are spent (LP_MAX_TGSI_LOOP_ITERATIONS), so a kernel that runs
// many traversals in one invocation (trace.comp's work queue) must stop in
// time. Each pass of a traversal loop adds 2 (itself and the leaf loop
// inside it, whose body lavapipe runs at least once) and each leaf visit its
// triangles; the sum over a subgroup's lanes bounds what it spent, since a loop
// runs as long as its longest lane. Kernels that do not read it compile it out.
uint gBvhTicks = 0u;

// Per-ray constants of the slab and triangle tests.
struct BvhRay {
    vec3 origin;
    vec3 invDir;   // 1/dir; +-inf for a +-0 component
    bvec3 neg;     // sign bit of dir: the slab's near plane is bmax
    uint kz;       // axis of largest |dir|
    bool swapXY;   // dir[kz] < 0: swap kx and ky to keep the winding
    vec3 shear;    // (dir[kx]/dir[kz], dir[ky]/dir[kz], 1/dir[kz])
};

// (p[kx], p[ky], p[kz]) with kx = (kz+1)%3, ky = (kx+1)%3, then kx/ky swapped.
vec3 bvhPermute(vec3 p, BvhRay r) {
    vec3 q = r.kz == 0u ? p.yzx : (r.kz == 1u ? p.zxy : p.xyz);
    return r.swapXY ? q.yxz : q;
}

BvhRay bvhMakeRay(vec3 origin, vec3 dir) {
    BvhRay r;
    r.origin = origin;
    uvec3 signBits = floatBitsToUint(dir) & 0x80000000u;
    r.neg = notEqual(signBits, uvec3(0u));
    // Division by 0 is outside Vulkan's precision guarantees: build +-inf from
    // the sign bit.
    vec3 signedInf = uintBitsToFloat(signBits | 0x7f800000u);
    r.invDir = mix(1.0 / dir, signedInf, equal(dir, vec3(0.0)));
    vec3 a = abs(dir);
    r.kz = (a.x >= a.y) ? (a.x >= a.z ? 0u : 2u) : (a.y >= a.z ? 1u : 2u);
    r.swapXY = false;
    vec3 d = bvhPermute(dir, r);
    r.swapXY = d.z < 0.0;
    d = r.swapXY ? d.yxz : d;
    r.shear = vec3(d.x / d.z, d.y / d.z, 1.0 / d.z);
    return r;
}

// Woop, Benthin, Wald 2013, "Watertight Ray/Triangle Intersection", JCGT 2(1),
// both faces. `precise` keeps the arithmetic free of FMA contraction, so
// triangles sharing an edge evaluate it identically and t rounds as in C++.
// Degenerate triangles (float cross product of the edges exactly zero) are
// never hit.
bool bvhIntersectTri(BvhRay r, vec3 a, vec3 b, vec3 c, float tmin, float tmax,
                     out float tOut, out float uOut, out float vOut) {
    precise vec3 A = bvhPermute(a - r.origin, r);
    precise vec3 B = bvhPermute(b - r.origin, r);
    precise vec3 C = bvhPermute(c - r.origin, r);
    precise float Ax = A.x - r.shear.x * A.z;
    precise float Ay = A.y - r.shear.y * A.z;
    precise float Bx = B.x - r.shear.x * B.z;
    precise float By = B.y - r.shear.y * B.z;
    precise float Cx = C.x - r.shear.x * C.z;
    precise float Cy = C.y - r.shear.y * C.z;

    precise float U = Cx * By - Cy * Bx;
    precise float V = Ax * Cy - Ay * Cx;
    precise float W = Bx * Ay - By * Ax;
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    precise float det = U + V + W;
    if (det == 0.0) return false;

    precise float T = U * (r.shear.z * A.z) + V * (r.shear.z * B.z) + W * (r.shear.z * C.z);
    precise float rcpDet = 1.0 / det;
    precise float t = T * rcpDet;
    if (!(t > tmin && t < tmax)) return false;

    precise vec3 e1 = b - a;
    precise vec3 e2 = c - a;
    precise vec3 n = vec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                          e1.x * e2.y - e1.y * e2.x);
    if (all(equal(n, vec3(0.0)))) return false;

    tOut = t;
    uOut = V * rcpDet;
    vOut = W * rcpDet;
    return true;
}

// Slab test (Kay & Kajiya 1986) against [tmin, tmax]; returns the entry
// distance max(tmin, near) in tEntry. A 0 * inf product (origin on a slab
// plane, direction component 0) is NaN; `x > acc ? x : acc` keeps acc then,
// so that axis does not limit the interval (the box is closed). Should a
// compiler turn the selects into min/max, GPU min/max return the non-NaN
// operand (IEEE 754 minNum), which is the same.
bool bvhSlab(BvhRay r, BvhNode node, float tmin, float tmax, out float tEntry) {
    vec3 t0 = (node.bmin - r.origin) * r.invDir;
    vec3 t1 = (node.bmax - r.origin) * r.invDir;
    vec3 lo = mix(t0, t1, r.neg);
    vec3 hi = mix(t1, t0, r.neg);
    float tnear = tmin;
    float tfar = tmax;
    tnear = lo.x > tnear ? lo.x : tnear;
    tnear = lo.y > tnear ? lo.y : tnear;
    tnear = lo.z > tnear ? lo.z : tnear;
    tfar = hi.x < tfar ? hi.x : tfar;
    tfar = hi.y < tfar ? hi.y : tfar;
    tfar = hi.z < tfar ? hi.z : tfar;
    tEntry = tnear;
    return tnear <= tfar * kBvhSlabScale;
}

// Slab tests of a wide node's four children against [tmin, tmax], as bvhSlab
// does for one (the same arithmetic, so the same boxes are entered). Returns
// the entry distances; `hit` says which children the ray enters. Empty
// children (+inf / -inf boxes) are never entered.
vec4 bvhSlab4(BvhRay r, BvhNode4 n, float tmin, float tmax, out bvec4 hit) {
    vec4 x0 = (n.minX - r.origin.x) * r.invDir.x;
    vec4 x1 = (n.maxX - r.origin.x) * r.invDir.x;
    vec4 y0 = (n.minY - r.origin.y) * r.invDir.y;
    vec4 y1 = (n.maxY - r.origin.y) * r.invDir.y;
    vec4 z0 = (n.minZ - r.origin.z) * r.invDir.z;
    vec4 z1 = (n.maxZ - r.origin.z) * r.invDir.z;
    vec4 loX = r.neg.x ? x1 : x0, hiX = r.neg.x ? x0 : x1;
    vec4 loY = r.neg.y ? y1 : y0, hiY = r.neg.y ? y0 : y1;
    vec4 loZ = r.neg.z ? z1 : z0, hiZ = r.neg.z ? z0 : z1;
    vec4 tnear = vec4(tmin);
    vec4 tfar = vec4(tmax);
    tnear = mix(tnear, loX, greaterThan(loX, tnear));
    tnear = mix(tnear, loY, greaterThan(loY, tnear));
    tnear = mix(tnear, loZ, greaterThan(loZ, tnear));
    tfar = mix(tfar, hiX, lessThan(hiX, tfar));
    tfar = mix(tfar, hiY, lessThan(hiY, tfar));
    tfar = mix(tfar, hiZ, lessThan(hiZ, tfar));
    hit = lessThanEqual(tnear, tfar * kBvhSlabScale);
    return tnear;
}

// The triangles [first, end) of a leaf within (tmin, tmax). With anyHit (a
// literal: the call is inlined and folded), true at the first one hit; else
// false, and a hit replaces the closest so far if nearer, or equally near
// with a lower BVH-order index. Alpha-tested holes (kFeatureAlphaTest) are
// skipped.
bool bvhLeaf(BvhRay r, uint first, uint end, float tmin, float tmax, uint rayHash, const bool anyHit,
             inout float bestT, inout uint bestTri, inout float bestU, inout float bestV) {
    const bool alphaTest = (kFeatures & kFeatureAlphaTest) != 0u;
    gBvhTicks += end - first;
    for (uint i = first; i < end; ++i) {
        TriVerts tri = bvhFetchTri(i);
        float t, u, v;
        if (bvhIntersectTri(r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, tmax, t, u, v) &&
            (anyHit || t < bestT || (t == bestT && i < bestTri)) && !(alphaTest && bvhIsHole(i, u, v, rayHash))) {
            if (anyHit) return true;
            bestT = t;
            bestTri = i;
            bestU = u;
            bestV = v;
        }
    }
    return false;
}

// The result of a closest-hit traversal: false (hit left a miss) or true
// with the hit.
bool bvhSetHit(float t, uint triangle, float u, float v, inout TraceHit hit) {
    if (triangle == kNoHit) return false;
    hit = TraceHit(t, triangle, u, v);
    return true;
}

#endif
