// Closest-hit and any-hit traversal of the BVH built by host/bvh/build.cpp:
// the flattened BVH2, mirroring host/bvh/traverse.cpp step for step (the same
// watertight triangle test, slab test, nearer-child-first order and tie rule,
// equal t: lowest BVH-order triangle index), or the same tree collapsed four
// wide (host/bvh/wide.h), which finds the same hits. Compile-time defines
// select the traversal: STRATA_BVH2 (the bvh2 axis, host/spirv/features.cpp) the binary
// one (lib/bvh2.glsl), STRATA_BVH4_MEMSTACK (the bvh4m axis) the four-wide one with
// an array stack (GPUs), neither the four-wide one with a register stack (CPU
// devices; both in lib/bvh4.glsl). The unused ones are compiled out rather
// than folded by a specialization constant: pipeline creation on lavapipe
// translates every branch of the module before the constants fold
// (docs/experiments/traversal.md, kernel and compiler).
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
// Differences from the C++: traverse.cpp recomputes an edge function that
// is exactly 0 in double precision, the shaders do not, so rays through a
// vertex or along an edge may pick a neighbouring triangle with a t one ULP
// apart. Vulkan's division is accurate to 2.5 ULP rather than 0.5, so the
// slab scale is wider (kBvhSlabScale).
#ifndef STRATA_LIB_BVH_GLSL
#define STRATA_LIB_BVH_GLSL

#ifdef STRATA_BVH2
#include "lib/bvh2.glsl"
#else
#include "lib/bvh4.glsl"
#endif

// Entries of the top-level traversal's stack: the top level is built by the
// same builder, whose leaves stay at depth < 64 (host/bvh/bvh.h).
const uint kTopStackSize = 64u;

#ifdef STRATA_INSTANCING
// The instance of the last closest hit (its record's first texel, lib/scene.glsl).
uint gHitInstance = kNoInstance;
#endif

// Closest (anyHit false) or any hit: the bottom-level traversal chosen by
// define, called once. Without STRATA_INSTANCING the scene is one BVH,
// traversed from root 0. With it (the inst axis, for scenes
// with kFeatureInstancing), the top level (a BVH2 over the placements' world
// boxes, lib/scene.glsl) hands out the instances the ray enters within the
// closest hit so far, and each is traversed with the ray taken to its space
// by worldToObject: the direction is not renormalised, so t is the same in
// both spaces. Ties between instances keep the first found.
bool bvhTrace(vec3 origin, vec3 dir, float tmin, float tmax, const bool anyHit, out TraceHit hit) {
    hit = TraceHit(-1.0, kNoHit, 0.0, 0.0);
    BvhRay r = bvhMakeRay(origin, dir);
    uint rayHash = (kFeatures & kFeatureAlphaTest) != 0u ? bvhRayHash(origin, dir) : 0u;
    float bestT = tmax;  // stays tmax for anyHit
    uint bestTri = kNoHit;
    float bestU = 0.0;
    float bestV = 0.0;
#ifdef STRATA_INSTANCING
    BvhRay world = r;
    uint record = kNoInstance, bestRecord = kNoInstance;
    const uint kTopDone = 0xffffffffu;
    // The next top-level node the ray enters (its box tested already);
    // kTopDone: none left. The nearer entered child first, the other pushed.
    float tRoot;
    uint top = bvhSlab(world, bvhFetchTopNode(0u), tmin, bestT, tRoot) ? 0u : kTopDone;
    uint topStack[kTopStackSize];
    uint topSp = 0u;
    for (;;) {
        record = kNoInstance;
        while (record == kNoInstance && top != kTopDone) {
            gBvhTicks += 2u;
            BvhNode n = bvhFetchTopNode(top);
            uint next = kTopDone;
            if (n.count != 0u) {
                record = n.leftOrFirst;
            } else {
                uint left = top + 1u, right = n.leftOrFirst;
                float tl, tr;
                bool hl = bvhSlab(world, bvhFetchTopNode(left), tmin, bestT, tl);
                bool hr = bvhSlab(world, bvhFetchTopNode(right), tmin, bestT, tr);
                bool rightFirst = hr && (!hl || tr < tl);
                if (hl && hr && topSp < kTopStackSize) topStack[topSp++] = rightFirst ? left : right;
                if (hl || hr) next = rightFirst ? right : left;
            }
            top = next != kTopDone ? next : (topSp > 0u ? topStack[--topSp] : kTopDone);
        }
        if (record == kNoInstance) break;
        vec4 r0 = instanceRow(record, 0u), r1 = instanceRow(record, 1u), r2 = instanceRow(record, 2u);
        r = bvhMakeRay(rowsPoint(r0, r1, r2, origin), rowsVector(r0, r1, r2, dir));
        uint root = instanceRoot(record);
        float lastT = bestT;
        uint lastTri = bestTri;
#else
        const uint root = 0u;
#endif
#ifdef STRATA_BVH2
        bool found = bvhTrace2(r, root, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV);
#elif defined(STRATA_BVH4_MEMSTACK)
        bool found = bvhTrace4Sorted(r, root, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV);
#else
        bool found = bvhTrace4(r, root, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV);
#endif
#ifdef STRATA_INSTANCING
        if (found) {
            gHitInstance = record;
            return true;
        }
        if (bestT != lastT || bestTri != lastTri) bestRecord = record;
    }
    gHitInstance = bestRecord;
#else
        if (found) return true;
#endif
    return bvhSetHit(bestT, bestTri, bestU, bestV, hit);
}

// Closest hit with tmin < t < tmax. On a miss hit.t = -1 and
// hit.triangle = kNoHit. With STRATA_INSTANCING gHitInstance is the hit's instance.
bool bvhTraceClosest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
    return bvhTrace(origin, dir, tmin, tmax, false, hit);
}

// True if any triangle is hit with tmin < t < tmax (shadow rays); stops at
// the first hit found.
bool bvhTraceAny(vec3 origin, vec3 dir, float tmin, float tmax) {
    TraceHit unused;
    return bvhTrace(origin, dir, tmin, tmax, true, unused);
}

#endif
