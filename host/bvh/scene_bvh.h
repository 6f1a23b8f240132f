// The BVH stage of a render: a loaded Scene's triangles -> the binary BVH
// (bvh.h) and the four-wide tree collapsed from it (wide.h). Packing
// (pack/gpu_scene.h) takes this value and lays the scene out in BVH order.
// With instancing (Scene::instances) the two trees hold one bottom level
// per triangle range, concatenated, and `top` is the BVH2 over the
// placements' world boxes.
#pragma once
#include <cstdint>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/wide.h"
#include "scene/scene.h"

namespace strata {

// One bottom level: its roots in the concatenated trees.
struct BottomLevel {
    std::uint32_t root2 = 0;  // index into SceneBvh::binary.nodes
    std::uint32_t root4 = 0;  // index into SceneBvh::wide.nodes
    bool empty = true;        // no triangles: placements of it are dropped
    glm::vec3 lo{0.0f}, hi{0.0f};  // its root box
};

// A placement of a bottom level (the top level's input).
struct Placement {
    std::uint32_t bottom = 0;  // 0: the world triangles (identity); 1 + j: Scene::sharedMeshes[j]
    glm::mat4 toWorld{1.0f};
    std::vector<MotionKey> motion;  // MeshInstance::motion: empty when it does not move
};

struct SceneBvh {
    Bvh binary;    // nodes, triIndices (BVH order -> scene triangle) and stats
    WideBvh wide;  // collapsed from binary.nodes
    // Instancing only (all empty otherwise): the bottom levels (0: the
    // world triangles, 1 + j: Scene::sharedMeshes[j]), the placements, and
    // the top level over them: its leaves hold one placement each, and
    // top.triIndices maps a leaf's position to its index in `placements`.
    std::vector<BottomLevel> bottoms;
    std::vector<Placement> placements;
    Bvh top;
    bool instanced() const { return !placements.empty(); }
};

// Builds over scene.triangles in place (a strided view, no copy of the
// vertices); the collapse runs on options.threads threads (0: all).
SceneBvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options = {});

// The placements of the scene's instances (the world's triangles first,
// unless empty) over out.bottoms, and the top level over their world boxes.
void buildTopLevel(const Scene& scene, SceneBvh& out, const BvhBuildOptions& options = {});

// The world box of `bottom` placed by `toWorld`: its eight corners
// transformed in double, rounded outwards to float.
void placedBox(const BottomLevel& bottom, const glm::mat4& toWorld, glm::vec3& lo, glm::vec3& hi);

// The world box of `bottom` over a placement's motion: the boxes of its
// poses at kMotionBoxSteps times per key interval (interpolated as the
// shaders do), each widened by a quarter of the largest distance a corner
// moves between two of those times, which bounds how far its path strays
// from the chords.
void motionBox(const BottomLevel& bottom, const std::vector<MotionKey>& motion, glm::vec3& lo, glm::vec3& hi);
inline constexpr int kMotionBoxSteps = 16;

}  // namespace strata
