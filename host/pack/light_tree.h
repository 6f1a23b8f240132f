// The light tree (kFeatureLightTree; shaders/lib/light_tree.glsl reads it):
// a binary tree over the bounded lights (emissive triangles, point and spot
// lights), after Conty Estevez & Kulla 2018, "Importance Sampling of Many
// Lights with Adaptive Tree Splitting", and pbrt-v4's BVH light sampler.
// Each node bounds its lights' positions (a box), their total estimated
// power and their orientation (a cone of normals and the spread of emission
// beyond it); a shading point descends once, choosing each child in
// proportion to a bound of its contribution. The directional and
// environment lights stay outside: the alias table over all emitters
// chooses them with their own probabilities, and where it chooses a bounded
// light the tree chooses instead (lib/lights.glsl).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "../../shaders/shared/types.h"

namespace strata {

// --light-sampler: how next-event estimation chooses a light. Power: the
// alias table alone, in proportion to estimated power everywhere. Tree: the
// light tree for the bounded lights. Auto: the tree where the bounded lights
// form at least kLightTreeMinClusters clusters (lightClusters), else power
// (docs/benchmarks.md measures the choice).
enum class LightSampler { Auto, Tree, Power };
inline constexpr std::size_t kLightTreeMinClusters = 16;
inline constexpr double kLightClusterSize = 0.25;  // of the root's radius

// Whether `sampler` keeps a tree with this many clusters over at least one light.
bool useLightTree(LightSampler sampler, std::size_t clusters);

// Directional and environment lights: chosen outside the tree.
inline bool isInfiniteLight(const gpu::Emitter& e) {
    return e.kind == gpu::kLightDirectional || e.kind == gpu::kLightEnvironment;
}

struct LightTree {
    std::vector<gpu::LightNode> nodes;  // node 0 the root; depth-first, a first child after its parent
    std::uint32_t depth = 0;            // of the deepest leaf (root 0); at most kLightTreeMaxDepth
};
// A light's trail holds one bit per level.
inline constexpr std::uint32_t kLightTreeMaxDepth = 32;

// An emitter of a mesh that moves during the shutter (SharedMesh::lights):
// the tree bounds it over the shutter, not by its Emitter's pose at the
// open. `lo`, `hi`: a box around its vertices at every time; `turns`: its
// normal changes, so its cone holds every direction.
struct SweptLight {
    std::uint32_t emitter = 0;
    glm::dvec3 lo{0.0}, hi{0.0};
    bool turns = false;
};

// Builds the tree over the bounded lights of `emitters` (every emitter
// that is not isInfiniteLight), each with its estimated power from
// `weights` (packScene's, one per emitter), top-down: each node's lights
// are split in two along the axis and at the bucket (12 per axis, by the
// centroids) that minimise power x solid angle of the orientation bounds x
// surface area of the box, with the box's aspect as a regulariser (pbrt-v4's
// cost), in O(n log n). Sets each bounded light's Emitter::trail. Every
// leaf holds one light; where a split would leave the tree deeper than
// kLightTreeMaxDepth the lights are halved by count instead. Throws
// std::invalid_argument where no emitter is bounded. Each of `swept` is
// bounded as it says (and by its Emitter, which holds its pose at the open).
LightTree buildLightTree(std::vector<gpu::Emitter>& emitters, const std::vector<double>& weights,
                         const std::vector<SweptLight>& swept = {});

// Spatially apart groups of lights: the subtrees, largest first, whose
// bounding sphere's radius is at most `size` times the root's (a leaf
// counts as one). The tree chooses well between groups where power alone
// cannot (by distance and facing); within a compact group (a sphere lamp's
// triangles) it mostly costs its descent.
std::size_t lightClusters(const LightTree& tree, double size = kLightClusterSize);

}  // namespace strata
