// Closest-hit and any-hit traversal of the BVH built by host/bvh/build.cpp:
// the flattened BVH2, mirroring host/bvh/traverse.cpp step for step (the same
// watertight triangle test, slab test, nearer-child-first order and tie rule,
// equal t: lowest BVH-order triangle index), or the same tree collapsed four
// wide (host/bvh/wide.h), which finds the same hits. Compile-time defines
// select the traversal: STRATA_BVH2 (the *_bvh2 shader variants) the binary
// one, STRATA_BVH4_MEMSTACK (*_bvh4m) the four-wide one with an array stack
// (GPUs), neither the four-wide one with a register stack (CPU devices).
// Compiling the unused ones out rather than folding them by a specialization
// constant took about a fifth off pipeline creation on lavapipe.
//
// The including shader defines, before including this file:
//   BvhNode bvhFetchNode(uint index);    // with STRATA_BVH2
//   BvhNode4 bvhFetchNode4(uint index);  // without
//   const uint kBvhRegs;                 // SPEC_BVH_REGS, without STRATA_BVH2
//   TriVerts bvhFetchTri(uint index);    // BVH order
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

const float kBvhFloatMax = 3.402823466e38;

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

// The triangles [first, end) of a leaf against the closest hit so far: a hit
// replaces it if nearer, or equally near with a lower BVH-order index.
// Alpha-tested holes (kFeatureAlphaTest) are skipped.
void bvhLeafClosest(BvhRay r, uint first, uint end, float tmin, float tmax, uint rayHash, inout float bestT,
                    inout uint bestTri, inout float bestU, inout float bestV) {
    const bool alphaTest = (kFeatures & kFeatureAlphaTest) != 0u;
    gBvhTicks += end - first;
    for (uint i = first; i < end; ++i) {
        TriVerts tri = bvhFetchTri(i);
        float t, u, v;
        if (bvhIntersectTri(r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, tmax, t, u, v) &&
            (t < bestT || (t == bestT && i < bestTri)) && !(alphaTest && bvhIsHole(i, u, v, rayHash))) {
            bestT = t;
            bestTri = i;
            bestU = u;
            bestV = v;
        }
    }
}

// True if any triangle of [first, end) is hit within (tmin, tmax).
bool bvhLeafAny(BvhRay r, uint first, uint end, float tmin, float tmax, uint rayHash) {
    const bool alphaTest = (kFeatures & kFeatureAlphaTest) != 0u;
    gBvhTicks += end - first;
    for (uint i = first; i < end; ++i) {
        TriVerts tri = bvhFetchTri(i);
        float t, u, v;
        if (bvhIntersectTri(r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, tmin, tmax, t, u, v) &&
            !(alphaTest && bvhIsHole(i, u, v, rayHash)))
            return true;
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

// The empty BVH is a single node with count 0 and leftOrFirst 0 (an interior
// node's right child is never node 0).
bool bvhIsEmpty(BvhNode root) {
    return root.count == 0u && root.leftOrFirst == 0u;
}

// Closest hit with tmin < t < tmax. On a miss hit.t = -1 and
// hit.triangle = kNoHit.
bool bvhTraceClosest2(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
    hit = TraceHit(-1.0, kNoHit, 0.0, 0.0);
    BvhRay r = bvhMakeRay(origin, dir);
    uint index = 0u;
    BvhNode node = bvhFetchNode(0u);
    float tEntry;
    if (bvhIsEmpty(node) || !bvhSlab(r, node, tmin, tmax, tEntry)) return false;

    uint rayHash = (kFeatures & kFeatureAlphaTest) != 0u ? bvhRayHash(origin, dir) : 0u;
    float bestT = tmax;
    uint bestTri = kNoHit;
    float bestU = 0.0;
    float bestV = 0.0;
    uint stack[kBvhStackSize];
    uint sp = 0u;
    for (;;) {
        gBvhTicks += 2u;
        if (node.count > 0u) {
            bvhLeafClosest(r, node.leftOrFirst, node.leftOrFirst + node.count, tmin, tmax, rayHash, bestT,
                           bestTri, bestU, bestV);
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
    return bvhSetHit(bestT, bestTri, bestU, bestV, hit);
}

// bvhTraceAny on the BVH2.
bool bvhTraceAny2(vec3 origin, vec3 dir, float tmin, float tmax) {
    BvhRay r = bvhMakeRay(origin, dir);
    uint index = 0u;
    BvhNode node = bvhFetchNode(0u);
    float tEntry;
    if (bvhIsEmpty(node) || !bvhSlab(r, node, tmin, tmax, tEntry)) return false;

    uint rayHash = (kFeatures & kFeatureAlphaTest) != 0u ? bvhRayHash(origin, dir) : 0u;
    uint stack[kBvhStackSize];
    uint sp = 0u;
    for (;;) {
        gBvhTicks += 2u;
        if (node.count > 0u) {
            if (bvhLeafAny(r, node.leftOrFirst, node.leftOrFirst + node.count, tmin, tmax, rayHash)) return true;
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

// The four-wide traversal's stack holds one entry per wide node on the path
// from the root, (node << 4) | mask of its children still to visit, so it
// needs at most the wide tree's depth (host/bvh/wide.h) and lives in
// kBvhRegs variables (SPEC_BVH_REGS: 16, 24 or 32, the host's choice from
// that depth): a push or pop shifts them (selects; the unused ones are
// compiled out). On lavapipe an indexed private array is a per-lane scalar
// loop that runs on every push and pop whether or not a lane takes that
// branch. Resuming a node re-fetches it and re-tests the remaining children
// against the closest hit so far, so children that moved out of reach are
// culled.
#define BVH_PUSH(x) { \
    if (kBvhRegs > 24u) { s31 = s30; s30 = s29; s29 = s28; s28 = s27; s27 = s26; s26 = s25; s25 = s24; s24 = s23; } \
    if (kBvhRegs > 16u) { s23 = s22; s22 = s21; s21 = s20; s20 = s19; s19 = s18; s18 = s17; s17 = s16; s16 = s15; } \
    s15 = s14; s14 = s13; s13 = s12; s12 = s11; s11 = s10; s10 = s9; s9 = s8; s8 = s7; \
    s7 = s6; s6 = s5; s5 = s4; s4 = s3; s3 = s2; s2 = s1; s1 = s0; s0 = (x); ++count; }
#define BVH_POP(dst) { dst = s0; \
    s0 = s1; s1 = s2; s2 = s3; s3 = s4; s4 = s5; s5 = s6; s6 = s7; s7 = s8; \
    s8 = s9; s9 = s10; s10 = s11; s11 = s12; s12 = s13; s13 = s14; s14 = s15; \
    if (kBvhRegs > 16u) { s15 = s16; s16 = s17; s17 = s18; s18 = s19; s19 = s20; s20 = s21; s21 = s22; s22 = s23; } \
    if (kBvhRegs > 24u) { s23 = s24; s24 = s25; s25 = s26; s26 = s27; s27 = s28; s28 = s29; s29 = s30; s30 = s31; } \
    --count; }
#define BVH_STACK_DECL uint s0 = 0u, s1 = 0u, s2 = 0u, s3 = 0u, s4 = 0u, s5 = 0u, s6 = 0u, s7 = 0u, s8 = 0u, s9 = 0u, s10 = 0u, s11 = 0u, s12 = 0u, s13 = 0u, s14 = 0u, s15 = 0u; \
    uint s16 = 0u, s17 = 0u, s18 = 0u, s19 = 0u, s20 = 0u, s21 = 0u, s22 = 0u, s23 = 0u, s24 = 0u, s25 = 0u, s26 = 0u, s27 = 0u, s28 = 0u, s29 = 0u, s30 = 0u, s31 = 0u; uint count = 0u

// The triangles of a wide leaf reference: with anyHit (a literal), true at
// the first hit, with hit.t = 1 and hit.triangle = 0; else the closest hit so
// far is updated and false returned.
bool bvhVisitLeaf(BvhRay r, uint ref, float tmin, float tmax, uint rayHash, const bool anyHit,
                  inout float bestT, inout uint bestTri, inout float bestU, inout float bestV, inout TraceHit hit) {
    uint first = (ref & ~kBvhLeafBit) >> kBvhLeafCountBits;
    uint end = first + (ref & ((1u << kBvhLeafCountBits) - 1u)) + 1u;
    if (anyHit) {
        if (!bvhLeafAny(r, first, end, tmin, tmax, rayHash)) return false;
        hit.t = 1.0;
        hit.triangle = 0u;
        return true;
    }
    bvhLeafClosest(r, first, end, tmin, tmax, rayHash, bestT, bestTri, bestU, bestV);
    return false;
}

// Interior reference of a child: all four of its children to visit.
uint bvhEnter(uint child) {
    return (child & kBvhLeafBit) != 0u ? child : (child << 4) | 15u;
}

// Visits wide node (ref >> 4) restricted to the children in (ref & 15) that
// the ray enters within [tmin, tmax]: the nearest becomes `next`, the rest
// stay in the returned mask (0: none entered).
uint bvhVisit4(BvhRay r, uint ref, float tmin, float tmax, out uint next, out uint nextSlot) {
    BvhNode4 n = bvhFetchNode4(ref >> 4);
    bvec4 h;
    vec4 tn = bvhSlab4(r, n, tmin, tmax, h);
    uvec4 bit = uvec4(1u, 2u, 4u, 8u);
    bvec4 allowed = notEqual(bit & uvec4(ref & 15u), uvec4(0u));
    h = bvec4(h.x && allowed.x, h.y && allowed.y, h.z && allowed.z, h.w && allowed.w);
    vec4 key = mix(vec4(uintBitsToFloat(0x7f800000u)), min(tn, vec4(kBvhFloatMax)), h);
    // Nearest entered child; ties to the lower slot.
    uint slot = key.y < key.x ? 1u : 0u;
    float best = min(key.x, key.y);
    uint slot2 = key.w < key.z ? 3u : 2u;
    float best2 = min(key.z, key.w);
    slot = best2 < best ? slot2 : slot;
    uint mask = (h.x ? 1u : 0u) | (h.y ? 2u : 0u) | (h.z ? 4u : 0u) | (h.w ? 8u : 0u);
    next = n.child[slot];
    nextSlot = slot;
    return mask;
}

// Closest (anyHit false) or any hit on the four-wide BVH;
// `anyHit` must be a literal (the call is inlined and folded). The closest
// hit is the one bvhTraceClosest2 finds: the boxes, the slab test and the tie
// rule are the same, and the result does not depend on the visiting order.
bool bvhTrace4(vec3 origin, vec3 dir, float tmin, float tmax, const bool anyHit, out TraceHit hit) {
    hit = TraceHit(-1.0, kNoHit, 0.0, 0.0);
    BvhRay r = bvhMakeRay(origin, dir);
    uint rayHash = (kFeatures & kFeatureAlphaTest) != 0u ? bvhRayHash(origin, dir) : 0u;
    float bestT = tmax;  // stays tmax for anyHit
    uint bestTri = kNoHit;
    float bestU = 0.0;
    float bestV = 0.0;
    BVH_STACK_DECL;
    // An iteration makes two node passes, then tests the leaf (at most one)
    // that they entered. lavapipe runs every statement of the loop for all 8
    // lanes in every iteration, whichever a lane needs, and pays the leaf
    // loop's first pass each time: a leaf in an iteration of its own cost a
    // whole node pass, one node pass per iteration a triangle pass per node
    // (three passes: 0.78-0.97x of two). A lane whose first pass entered a
    // leaf or nothing pops for its second pass; if that meets a second leaf,
    // the node goes back on the stack with it (re-tested after the first).
    // Popped entries are always wide nodes (leaves are never pushed).
    uint ref = 15u;  // the next node entry to visit, the root first; 0: pop one
    for (;;) {
        gBvhTicks += 2u;
        uint next, slot;
        // First pass.
        uint mask = bvhVisit4(r, ref, tmin, bestT, next, slot);
        uint rest = mask & ~(1u << slot);
        if (rest != 0u) BVH_PUSH((ref & ~15u) | rest);
        ref = bvhEnter(next);
        bool leaf = mask != 0u && (ref & kBvhLeafBit) != 0u;
        uint held = leaf ? ref : 0u;  // the leaf to test this iteration
        bool pop = mask == 0u || leaf;
        bool empty = pop && count == 0u;
        if (pop && !empty) BVH_POP(ref);
        // Second pass.
        if (!empty) {
            mask = bvhVisit4(r, ref, tmin, bestT, next, slot);
            uint child = bvhEnter(next);
            leaf = mask != 0u && (child & kBvhLeafBit) != 0u;
            bool second = leaf && held != 0u;
            rest = second ? mask : mask & ~(1u << slot);
            if (rest != 0u) BVH_PUSH((ref & ~15u) | rest);
            if (leaf && !second) held = child;
            ref = (mask == 0u || leaf) ? 0u : child;
        } else {
            ref = 0u;
        }
        if (held != 0u && bvhVisitLeaf(r, held, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV, hit)) return true;
        if (ref == 0u) {
            if (count == 0u) break;
            BVH_POP(ref);
        }
    }
    return bvhSetHit(bestT, bestTri, bestU, bestV, hit);
}

#ifdef STRATA_BVH4_MEMSTACK
// Compare-exchange of (key, child) pairs: the nearer first.
#define BVH_CX(ka, ca, kb, cb) { bool sw = kb < ka; float tk = ka; uint tc = ca; \
    ka = sw ? kb : ka; ca = sw ? cb : ca; kb = sw ? tk : kb; cb = sw ? tc : cb; }

// The four-wide traversal for GPUs (STRATA_BVH4_MEMSTACK, the *_bvh4m
// shaders): a stack of child references in an indexed array (local memory),
// a node's entered children sorted by entry distance, the nearest visited
// next and the others pushed farthest first, at most 3 per wide level. On an
// NVIDIA H200 this ran 1.01-1.23x the BVH2 on diffuse rays (1.16-1.23x from
// 97k to 10M triangles) where the register stack below ran 0.76-0.85x
// (shifting 16-32 registers per push and pop costs a GPU more than a
// local-memory store); on lavapipe it runs 0.5x the register stack. Finds
// the same closest hit (the result does not depend on the order).
bool bvhTrace4Sorted(vec3 origin, vec3 dir, float tmin, float tmax, const bool anyHit, out TraceHit hit) {
    hit = TraceHit(-1.0, kNoHit, 0.0, 0.0);
    BvhRay r = bvhMakeRay(origin, dir);
    uint rayHash = (kFeatures & kFeatureAlphaTest) != 0u ? bvhRayHash(origin, dir) : 0u;
    float bestT = tmax;
    uint bestTri = kNoHit;
    float bestU = 0.0;
    float bestV = 0.0;
    uint stk[3u * kBvhMaxWideDepth];
    uint sp = 0u;
    uint ref = 0u;  // the root
    const float inf = uintBitsToFloat(0x7f800000u);
    for (;;) {
        gBvhTicks += 2u;
        if ((ref & kBvhLeafBit) != 0u) {
            if (bvhVisitLeaf(r, ref, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV, hit)) return true;
        } else {
            BvhNode4 n = bvhFetchNode4(ref);
            bvec4 h;
            vec4 tn = bvhSlab4(r, n, tmin, bestT, h);
            vec4 key = mix(vec4(inf), min(tn, vec4(kBvhFloatMax)), h);
            float k0 = key.x, k1 = key.y, k2 = key.z, k3 = key.w;
            uint c0 = n.child.x, c1 = n.child.y, c2 = n.child.z, c3 = n.child.w;
            BVH_CX(k0, c0, k1, c1);
            BVH_CX(k2, c2, k3, c3);
            BVH_CX(k0, c0, k2, c2);
            BVH_CX(k1, c1, k3, c3);
            BVH_CX(k1, c1, k2, c2);
            if (k0 < inf) {
                if (k3 < inf) stk[sp++] = c3;
                if (k2 < inf) stk[sp++] = c2;
                if (k1 < inf) stk[sp++] = c1;
                ref = c0;
                continue;
            }
        }
        if (sp == 0u) break;
        ref = stk[--sp];
    }
    return bvhSetHit(bestT, bestTri, bestU, bestV, hit);
}
#endif

bool bvhTraceClosest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
#ifdef STRATA_BVH2
    return bvhTraceClosest2(origin, dir, tmin, tmax, hit);
#elif defined(STRATA_BVH4_MEMSTACK)
    return bvhTrace4Sorted(origin, dir, tmin, tmax, false, hit);
#else
    return bvhTrace4(origin, dir, tmin, tmax, false, hit);
#endif
}

// True if any triangle is hit with tmin < t < tmax (shadow rays); stops at
// the first hit found.
bool bvhTraceAny(vec3 origin, vec3 dir, float tmin, float tmax) {
#ifdef STRATA_BVH2
    return bvhTraceAny2(origin, dir, tmin, tmax);
#elif defined(STRATA_BVH4_MEMSTACK)
    TraceHit unused;
    return bvhTrace4Sorted(origin, dir, tmin, tmax, true, unused);
#else
    TraceHit unused;
    return bvhTrace4(origin, dir, tmin, tmax, true, unused);
#endif
}

#endif
