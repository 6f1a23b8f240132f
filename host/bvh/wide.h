// Four-wide BVH collapsed from the binary one (gpu::BvhNode4, shaders/shared/types.h).
// Each wide node takes a BVH2 node and repeatedly opens its interior child of
// largest surface area until it has four children or only leaves; the boxes
// are the BVH2 boxes, so a traversal of either tree visits the same triangles
// with the same slab tests and finds the same closest hit.
#pragma once
#include <cstdint>
#include <vector>

#include "../../shaders/shared/types.h"

namespace strata {

// The four-wide traversal keeps one stack entry per wide node on its path
// (shaders/lib/bvh.glsl), in at most kBvhMaxRegs registers; a tree deeper
// than that is traversed as the BVH2.
inline constexpr std::uint32_t kBvhMaxRegs = gpu::kBvhMaxWideDepth;

struct WideBvh {
    std::vector<gpu::BvhNode4> nodes;  // depth-first; nodes[0] is the root
    std::uint32_t maxDepth = 0;        // wide nodes from the root to the deepest leaf
                                       // reference: the most stack entries a traversal holds
};

// Stack registers for a tree of that depth: 16, 24 or 32; 0 above kBvhMaxRegs.
std::uint32_t bvhRegsFor(std::uint32_t wideDepth);

// Throws strata::Error when a leaf starts at or beyond gpu::kBvhMaxLeafFirst.
WideBvh collapseBvh4(const std::vector<gpu::BvhNode>& nodes);

}  // namespace strata
