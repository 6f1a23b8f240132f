// The binary traversal (STRATA_BVH2, the bvh2 axis) of the
// flattened BVH2, mirroring host/bvh/traverse.cpp step for step: the same
// slab test, nearer child first, and the tie rule of bvhLeaf.
#ifndef STRATA_LIB_BVH2_GLSL
#define STRATA_LIB_BVH2_GLSL

#include "lib/bvh_common.glsl"

// Entries of the traversal stack; buildBvh keeps every leaf at depth
// < kBvhStackSize (host/bvh/bvh.h), and a traversal holds at most depth entries.
const uint kBvhStackSize = 64u;

// The empty BVH is a single node with count 0 and leftOrFirst 0 (an interior
// node's right child is never node 0).
bool bvhIsEmpty(BvhNode root) {
    return root.count == 0u && root.leftOrFirst == 0u;
}

// Closest (anyHit false) or any hit with tmin < t < tmax on the BVH2 from
// node `root` (0, or a bottom level's root: lib/bvh.glsl), updating the
// closest hit so far (bestT starts at tmax and stays tmax for anyHit); true
// when anyHit found one. `anyHit` must be a literal (the call is inlined and
// folded).
bool bvhTrace2(BvhRay r, uint root, float tmin, float tmax, uint rayHash, const bool anyHit,
               inout float bestT, inout uint bestTri, inout float bestU, inout float bestV) {
    uint index = root;
    BvhNode node = bvhFetchNode(root);
    float tEntry;
    if (bvhIsEmpty(node) || !bvhSlab(r, node, tmin, bestT, tEntry)) return false;

    uint stack[kBvhStackSize];
    uint sp = 0u;
    for (;;) {
        gBvhTicks += 2u;
        if (node.count > 0u) {
            if (bvhLeaf(r, node.leftOrFirst, node.leftOrFirst + node.count, tmin, tmax, rayHash, anyHit, bestT,
                        bestTri, bestU, bestV))
                return true;
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
    return false;
}

#endif
