// Closest-hit and any-hit traversal of the flattened BVH2 built by
// host/bvh/build.cpp, mirroring host/bvh/traverse.cpp step for step: the same
// watertight triangle test, slab test, nearer-child-first order and tie rule
// (equal t: lowest BVH-order triangle index).
//
// The including shader defines, before including this file:
//   BvhNode bvhFetchNode(uint index);
//   TriVerts bvhFetchTri(uint index);   // BVH order
//   const uint kFeatures;               // SPEC_FEATURES
//   uint bvhRayHash(vec3 origin, vec3 dir);
//   bool bvhIsHole(uint tri, float u, float v, uint rayHash);
// With kFeatureAlphaTest set, a hit for which bvhIsHole is true (an alpha
// MASK or BLEND hole, lib/material.glsl) is skipped by both traversals; the
// test is compiled out otherwise, leaving the hot loop as it was.
// Differences from the C++: the double-precision edge-function fallback is
// compiled only when the shader defines STRATA_BVH_FLOAT64 (and enables
// GL_ARB_gpu_shader_fp64; the device needs shaderFloat64). Without it, rays
// through a vertex or along an edge may pick a neighbouring triangle with a
// t one ULP apart. Vulkan's division is accurate to 2.5 ULP rather than 0.5,
// so the slab scale is wider (kBvhSlabScale). With STRATA_BVH_FLOAT64, hits
// on lavapipe (Mesa 22.3) matched traceClosest bit for bit on 131k rays.
#ifndef STRATA_LIB_BVH_GLSL
#define STRATA_LIB_BVH_GLSL

#include "shared/types.h"

// Entries of the traversal stack; buildBvh keeps every leaf at depth
// < kBvhStackSize (host/bvh/bvh.h), and a traversal holds at most depth entries.
const uint kBvhStackSize = 64u;

// 1 + 2*gamma(7), gamma(n) = n*u / (1 - n*u), u = 2^-24, rounded up to a float
// (1 + 8 * 2^-23): Ize 2013 ("Robust BVH Ray Traversal", JCGT 2(2)) with
// 1/d and (b - o) * (1/d) carrying 2.5 + 0.5 + 0.5 ULP instead of 3 x 0.5.
const float kBvhSlabScale = 1.00000095367431640625;

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
#ifdef STRATA_BVH_FLOAT64
    if (U == 0.0 || V == 0.0 || W == 0.0) {
        precise double dU = double(Cx) * double(By) - double(Cy) * double(Bx);
        precise double dV = double(Ax) * double(Cy) - double(Ay) * double(Cx);
        precise double dW = double(Bx) * double(Ay) - double(By) * double(Ax);
        U = float(dU);
        V = float(dV);
        W = float(dW);
    }
#endif
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

// The empty BVH is a single node with count 0 and leftOrFirst 0 (an interior
// node's right child is never node 0).
bool bvhIsEmpty(BvhNode root) {
    return root.count == 0u && root.leftOrFirst == 0u;
}

// Closest hit with tmin < t < tmax. On a miss hit.t = -1 and
// hit.triangle = kNoHit.
bool bvhTraceClosest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
    hit.t = -1.0;
    hit.triangle = kNoHit;
    hit.u = 0.0;
    hit.v = 0.0;
    BvhRay r = bvhMakeRay(origin, dir);
    uint index = 0u;
    BvhNode node = bvhFetchNode(0u);
    float tEntry;
    if (bvhIsEmpty(node) || !bvhSlab(r, node, tmin, tmax, tEntry)) return false;

    const bool alphaTest = (kFeatures & kFeatureAlphaTest) != 0u;
    uint rayHash = alphaTest ? bvhRayHash(origin, dir) : 0u;
    float bestT = tmax;
    uint bestTri = kNoHit;
    float bestU = 0.0;
    float bestV = 0.0;
    uint stack[kBvhStackSize];
    uint sp = 0u;
    for (;;) {
        if (node.count > 0u) {
            uint end = node.leftOrFirst + node.count;
            for (uint i = node.leftOrFirst; i < end; ++i) {
                TriVerts tri = bvhFetchTri(i);
                float t, u, v;
                if (bvhIntersectTri(r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, tmax, t, u, v) &&
                    (t < bestT || (t == bestT && i < bestTri)) &&
                    !(alphaTest && bvhIsHole(i, u, v, rayHash))) {
                    bestT = t;
                    bestTri = i;
                    bestU = u;
                    bestV = v;
                }
            }
        } else {
            uint left = index + 1u;
            uint right = node.leftOrFirst;
            BvhNode nl = bvhFetchNode(left);
            BvhNode nr = bvhFetchNode(right);
            float tl, tr;
            bool hl = bvhSlab(r, nl, tmin, bestT, tl);
            bool hr = bvhSlab(r, nr, tmin, bestT, tr);
            if (hl && hr) {
                bool rightFirst = tr < tl;
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
        if (sp == 0u) break;
        index = stack[--sp];
        node = bvhFetchNode(index);
    }
    if (bestTri == kNoHit) return false;
    hit.t = bestT;
    hit.triangle = bestTri;
    hit.u = bestU;
    hit.v = bestV;
    return true;
}

// True if any triangle is hit with tmin < t < tmax (shadow rays); stops at
// the first hit found.
bool bvhTraceAny(vec3 origin, vec3 dir, float tmin, float tmax) {
    BvhRay r = bvhMakeRay(origin, dir);
    uint index = 0u;
    BvhNode node = bvhFetchNode(0u);
    float tEntry;
    if (bvhIsEmpty(node) || !bvhSlab(r, node, tmin, tmax, tEntry)) return false;

    const bool alphaTest = (kFeatures & kFeatureAlphaTest) != 0u;
    uint rayHash = alphaTest ? bvhRayHash(origin, dir) : 0u;
    uint stack[kBvhStackSize];
    uint sp = 0u;
    for (;;) {
        if (node.count > 0u) {
            uint end = node.leftOrFirst + node.count;
            for (uint i = node.leftOrFirst; i < end; ++i) {
                TriVerts tri = bvhFetchTri(i);
                float t, u, v;
                if (bvhIntersectTri(r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, tmax, t, u, v) &&
                    !(alphaTest && bvhIsHole(i, u, v, rayHash))) {
                    return true;
                }
            }
        } else {
            uint left = index + 1u;
            uint right = node.leftOrFirst;
            BvhNode nl = bvhFetchNode(left);
            BvhNode nr = bvhFetchNode(right);
            float tl, tr;
            bool hl = bvhSlab(r, nl, tmin, tmax, tl);
            bool hr = bvhSlab(r, nr, tmin, tmax, tr);
            if (hl && hr) {
                bool rightFirst = tr < tl;
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
        if (sp == 0u) break;
        index = stack[--sp];
        node = bvhFetchNode(index);
    }
    return false;
}

#endif
