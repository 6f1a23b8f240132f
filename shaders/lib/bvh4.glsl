// The four-wide traversals of the BVH2 collapsed four wide (host/bvh/wide.h),
// which find the closest hit bvhTrace2 finds: the boxes, the slab test and
// the tie rule are the same, and the result does not depend on the visiting
// order. bvhTrace4 keeps its stack in registers (CPU devices); with
// STRATA_BVH4_MEMSTACK (the bvh4m axis, GPUs) bvhTrace4Sorted
// keeps it in an indexed array.
#ifndef STRATA_LIB_BVH4_GLSL
#define STRATA_LIB_BVH4_GLSL

#include "lib/bvh_common.glsl"

const float kBvhFloatMax = 3.402823466e38;

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

// The triangles of a wide leaf reference, as bvhLeaf.
bool bvhVisitLeaf(BvhRay r, uint ref, float tmin, float tmax, uint rayHash, const bool anyHit,
                  inout float bestT, inout uint bestTri, inout float bestU, inout float bestV) {
    uint first = (ref & ~kBvhLeafBit) >> kBvhLeafCountBits;
    uint end = first + (ref & ((1u << kBvhLeafCountBits) - 1u)) + 1u;
    return bvhLeaf(r, first, end, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV);
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

// Closest (anyHit false) or any hit on the four-wide BVH with the register
// stack, from wide node `root` (0, or a bottom level's root: lib/bvh.glsl),
// updating the closest hit so far (bestT starts at tmax and stays tmax for
// anyHit); true when anyHit found one. `anyHit` must be a literal (the call
// is inlined and folded).
bool bvhTrace4(BvhRay r, uint root, float tmin, float tmax, uint rayHash, const bool anyHit,
               inout float bestT, inout uint bestTri, inout float bestU, inout float bestV) {
    BVH_STACK_DECL;
    // An iteration makes two node passes, then tests the leaf (at most one)
    // that they entered. lavapipe runs every statement of the loop for all 8
    // lanes in every iteration, whichever a lane needs, and runs the leaf
    // loop's first pass each time, so an iteration for a leaf alone costs a
    // node pass, and an iteration of one node pass costs a triangle pass per
    // node (docs/experiments/traversal.md compares one, two and three
    // passes). A lane whose first pass entered a leaf or nothing pops for its
    // second pass; if that meets a second leaf, the node goes back on the
    // stack with it (re-tested after the first). Popped entries are always
    // wide nodes (leaves are never pushed).
    uint ref = (root << 4) | 15u;  // the next node entry to visit, the root first; 0: pop one
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
        if (held != 0u && bvhVisitLeaf(r, held, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV)) return true;
        if (ref == 0u) {
            if (count == 0u) break;
            BVH_POP(ref);
        }
    }
    return false;
}

#ifdef STRATA_BVH4_MEMSTACK
// Compare-exchange of (key, child) pairs: the nearer first.
#define BVH_CX(ka, ca, kb, cb) { bool sw = kb < ka; float tk = ka; uint tc = ca; \
    ka = sw ? kb : ka; ca = sw ? cb : ca; kb = sw ? tk : kb; cb = sw ? tc : cb; }

// The four-wide traversal for GPUs (STRATA_BVH4_MEMSTACK, the bvh4m
// shaders): a stack of child references in an indexed array (local memory),
// a node's entered children sorted by entry distance, the nearest visited
// next and the others pushed farthest first, at most 3 per wide level. A
// push or pop is one local-memory access where bvhTrace4 shifts 16-32
// registers; on lavapipe an indexed array is a per-lane scalar loop, so CPU
// devices take bvhTrace4 (docs/experiments/traversal.md and nvidia-h200.md
// have the figures of both).
// The arguments and result are bvhTrace4's.
bool bvhTrace4Sorted(BvhRay r, uint root, float tmin, float tmax, uint rayHash, const bool anyHit,
                     inout float bestT, inout uint bestTri, inout float bestU, inout float bestV) {
    uint stk[3u * kBvhMaxWideDepth];
    uint sp = 0u;
    uint ref = root;
    const float inf = uintBitsToFloat(0x7f800000u);
    for (;;) {
        gBvhTicks += 2u;
        if ((ref & kBvhLeafBit) != 0u) {
            if (bvhVisitLeaf(r, ref, tmin, tmax, rayHash, anyHit, bestT, bestTri, bestU, bestV)) return true;
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
    return false;
}
#endif

#endif
