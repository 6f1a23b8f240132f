#include "pack/instances.h"

#include <cstring>

#include <glm/gtc/matrix_access.hpp>

namespace strata {

// The instances array (GpuScene::instances) from the BVH stage's top level
// and placements; the roots refer to the concatenated bottom levels. With
// `records`, each bottom level's PlacedRecord (SharedMesh::lights copies
// have one placement each).
void packInstances(const Scene& scene, const SceneBvh& bvh, GpuScene& g, std::vector<PlacedRecord>* records) {
    if (records) records->assign(bvh.bottoms.size(), {});
    const std::vector<gpu::BvhNode>& nodes = bvh.top.nodes;
    const std::size_t n = bvh.top.triIndices.size();
    const std::size_t recordBase = nodes.size() * gpu::kBvhNodeTexels;
    g.instances.reserve(recordBase + n * gpu::kInstanceTexels);
    for (gpu::BvhNode node : nodes) {
        if (node.count > 0) node.leftOrFirst = std::uint32_t(recordBase + std::size_t(node.leftOrFirst) * gpu::kInstanceTexels);
        glm::uvec4 t[gpu::kBvhNodeTexels];
        std::memcpy(t, &node, sizeof node);
        for (const glm::uvec4& w : t) g.instances.push_back(w);
    }
    // The moving placements' MotionKeys follow the records.
    std::size_t keyTexel = recordBase + n * gpu::kInstanceTexels;
    for (std::size_t k = 0; k < n; ++k) {
        const Placement& p = bvh.placements[bvh.top.triIndices[k]];
        const BottomLevel& b = bvh.bottoms[p.bottom];
        if (records) (*records)[p.bottom] = {std::uint32_t(recordBase + k * gpu::kInstanceTexels), bvh.top.triIndices[k]};
        const glm::dmat4 toWorld(p.toWorld);
        const glm::dmat4 toObject = glm::inverse(toWorld);
        gpu::Instance rec{};
        for (int r = 0; r < 3; ++r) {
            rec.objectToWorld[r] = glm::vec4(glm::row(toWorld, r));
            rec.worldToObject[r] = glm::vec4(glm::row(toObject, r));
        }
        rec.root4 = b.root4;
        rec.root2 = b.root2;
        if (!p.motion.empty()) {
            rec.motionFirst = std::uint32_t(keyTexel);
            rec.motionCount = std::uint32_t(p.motion.size());
            keyTexel += p.motion.size() * gpu::kMotionKeyTexels;
        }
        glm::uvec4 t[gpu::kInstanceTexels];
        std::memcpy(t, &rec, sizeof rec);
        for (const glm::uvec4& w : t) g.instances.push_back(w);
        g.placedTriangles += p.bottom == 0 ? scene.worldTriangles() : scene.sharedMeshes[p.bottom - 1].count;
    }
    for (std::size_t k = 0; k < n; ++k) {
        for (const MotionKey& m : bvh.placements[bvh.top.triIndices[k]].motion) {
            const gpu::MotionKey key{m.time, m.translation, m.rotation, m.scale, 0.0f};
            glm::uvec4 t[gpu::kMotionKeyTexels];
            std::memcpy(t, &key, sizeof key);
            for (const glm::uvec4& w : t) g.instances.push_back(w);
        }
    }
    g.placementCount = n;
    g.sharedMeshCount = scene.sharedMeshes.size();
    g.top = bvh.top.stats;
    g.features.bits |= gpu::kFeatureInstancing;
}


std::vector<glm::uvec4> packInstanceArray(const Scene& scene, const SceneBvh& bvh) {
    GpuScene g;
    packInstances(scene, bvh, g);
    return std::move(g.instances);
}

}  // namespace strata
