// Closest-hit and any-hit traversal of the BVH built by host/bvh/build.cpp:
// the flattened BVH2, mirroring host/bvh/traverse.cpp step for step (the same
// watertight triangle test, slab test, nearer-child-first order and tie rule,
// equal t: lowest BVH-order triangle index), or the same tree collapsed four
// wide (host/bvh/wide.h), which finds the same hits. Compile-time defines
// select the traversal: STRATA_BVH2 (the *_bvh2 shader variants) the binary
// one (lib/bvh2.glsl), STRATA_BVH4_MEMSTACK (*_bvh4m) the four-wide one with
// an array stack (GPUs), neither the four-wide one with a register stack (CPU
// devices; both in lib/bvh4.glsl). The unused ones are compiled out rather
// than folded by a specialization constant: pipeline creation on lavapipe
// translates every branch of the module before the constants fold
// (docs/experiments.md).
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

// Closest hit with tmin < t < tmax. On a miss hit.t = -1 and
// hit.triangle = kNoHit.
bool bvhTraceClosest(vec3 origin, vec3 dir, float tmin, float tmax, out TraceHit hit) {
#ifdef STRATA_BVH2
    return bvhTrace2(origin, dir, tmin, tmax, false, hit);
#elif defined(STRATA_BVH4_MEMSTACK)
    return bvhTrace4Sorted(origin, dir, tmin, tmax, false, hit);
#else
    return bvhTrace4(origin, dir, tmin, tmax, false, hit);
#endif
}

// True if any triangle is hit with tmin < t < tmax (shadow rays); stops at
// the first hit found.
bool bvhTraceAny(vec3 origin, vec3 dir, float tmin, float tmax) {
    TraceHit unused;
#ifdef STRATA_BVH2
    return bvhTrace2(origin, dir, tmin, tmax, true, unused);
#elif defined(STRATA_BVH4_MEMSTACK)
    return bvhTrace4Sorted(origin, dir, tmin, tmax, true, unused);
#else
    return bvhTrace4(origin, dir, tmin, tmax, true, unused);
#endif
}

#endif
