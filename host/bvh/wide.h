// Four-wide BVH collapsed from the binary one (gpu::BvhNode4, shaders/shared/types.h).
// The collapse has the least SAH cost over the BVH2's subtrees (Ylitie,
// Karras & Laine 2017, "Efficient Incoherent Ray Traversal on GPUs Through
// Compressed Wide BVHs", section 3, for four children): a dynamic program
// over the BVH2 decides for each wide node which BVH2 nodes below it take its
// four child slots, and which subtrees of at most kWideLeafMax triangles
// become one leaf. The boxes are BVH2 boxes and a leaf holds its subtree's
// triangles, so a traversal of either tree finds the same closest hit.
#pragma once
#include <cstdint>
#include <vector>

#include "../../shaders/shared/types.h"

namespace strata {

// The four-wide traversal keeps one stack entry per wide node on its path
// (shaders/lib/bvh4.glsl), in at most kBvhMaxRegs registers; a tree deeper
// than that is traversed as the BVH2.
inline constexpr std::uint32_t kBvhMaxRegs = gpu::kBvhMaxWideDepth;

// SAH cost of a wide node visit, in triangle tests: higher than a node
// pass's instruction count alone suggests, for fewer and fuller nodes over
// somewhat larger leaves (docs/experiments/bvh.md, the collapse).
inline constexpr float kWideNodeCost = 3.0f;
// Most triangles in a leaf made from a BVH2 subtree (the BVH2's own leaves
// keep their size).
inline constexpr std::uint32_t kWideLeafMax = 8;

struct WideBvh {
    std::vector<gpu::BvhNode4> nodes;  // depth-first; nodes[0] is the root
    std::uint32_t maxDepth = 0;        // wide nodes from the root to the deepest leaf
                                       // reference: the most stack entries a traversal holds
    double buildMs = 0.0;              // the collapse's time
    double sahCost = 0.0;              // expected cost per ray (kWideNodeCost a node
                                       // visit, 1 a triangle test), relative to the root area
};

// Stack registers for a tree of that depth: 16, 24 or 32; 0 above kBvhMaxRegs.
std::uint32_t bvhRegsFor(std::uint32_t wideDepth);

// The plan runs on `threads` threads (0: all the hardware's); the tree is
// the same for any count. Throws strata::Error when a leaf starts at or
// beyond gpu::kBvhMaxLeafFirst.
WideBvh collapseBvh4(const std::vector<gpu::BvhNode>& nodes, unsigned threads = 0);

}  // namespace strata
