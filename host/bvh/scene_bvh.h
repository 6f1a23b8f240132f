// The BVH stage of a render: a loaded Scene's triangles -> the binary BVH
// (bvh.h) and the four-wide tree collapsed from it (wide.h). Packing
// (pack/gpu_scene.h) takes this value and lays the scene out in BVH order.
#pragma once
#include "bvh/bvh.h"
#include "bvh/wide.h"
#include "scene/scene.h"

namespace strata {

struct SceneBvh {
    Bvh binary;    // nodes, triIndices (BVH order -> scene triangle) and stats
    WideBvh wide;  // collapsed from binary.nodes
};

// Builds over scene.triangles in place (a strided view, no copy of the
// vertices); the collapse runs on options.threads threads (0: all).
SceneBvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options = {});

}  // namespace strata
