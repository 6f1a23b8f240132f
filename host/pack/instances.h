// The instances array of a scene with a top level (GpuScene::instances:
// the top level's nodes, each placement's gpu::Instance record, the moving
// placements' MotionKeys), and the lights of moving meshes, whose emitters
// point at their placement's record (kEmitterInstanced).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bvh/scene_bvh.h"
#include "pack/gpu_scene.h"
#include "pack/light_tree.h"
#include "scene/pose.h"
#include "scene/scene.h"

namespace strata {

// Where a bottom level is placed: the first texel of the record of its
// (last) placement, and that placement (an index into SceneBvh::placements).
struct PlacedRecord {
    std::uint32_t texel = 0;
    std::size_t placement = SIZE_MAX;
};

// The instances array (GpuScene::instances) from the BVH stage's top level
// and placements; the roots refer to the concatenated bottom levels. With
// `records`, each bottom level's PlacedRecord (SharedMesh::lights copies
// have one placement each).
void packInstances(const Scene& scene, const SceneBvh& bvh, GpuScene& g, std::vector<PlacedRecord>* records = nullptr);

// The lights of moving meshes (SharedMesh::lights, one placement each):
// which placement a scene triangle is a light of, the triangle at the
// shutter's open and its bounds over the shutter (for the light tree).
class InstancedLights {
public:
    InstancedLights(const Scene& scene, const SceneBvh& bvh, const std::vector<PlacedRecord>& records) : bvh_(bvh) {
        for (std::size_t j = 0; j < scene.sharedMeshes.size(); ++j) {
            const SharedMesh& m = scene.sharedMeshes[j];
            if (m.lights && j + 1 < records.size() && records[j + 1].placement != SIZE_MAX)
                ranges_.push_back({m.first, m.first + m.count, j + 1, records[j + 1].placement});
        }
    }

    // The placement of scene triangle `index` where it is such a light, else SIZE_MAX.
    std::size_t placementOf(std::size_t index) const {
        const Range* r = find(index);
        return r ? r->placement : SIZE_MAX;
    }
    // Its bottom level (an index into SceneBvh::bottoms); such a triangle only.
    std::size_t bottomOf(std::size_t index) const { return find(index)->bottom; }

    // The triangle (in its mesh's space) where `placement` puts it at the open.
    Triangle atOpen(std::size_t placement, const Triangle& t) const {
        const glm::dmat4 m(bvh_.placements[placement].toWorld);
        Triangle w = t;
        for (int k = 0; k < 3; ++k) w.v[k] = glm::vec3(m * glm::dvec4(glm::dvec3(t.v[k]), 1.0));
        return w;
    }

    // Emitter `emitter`'s bounds over the shutter: the box its vertices'
    // box sweeps (motionBox), and whether its normal turns between keys.
    SweptLight swept(std::size_t placement, const Triangle& t, std::size_t emitter) const {
        const Placement& p = bvh_.placements[placement];
        BottomLevel box;
        box.lo = glm::min(t.v[0], glm::min(t.v[1], t.v[2]));
        box.hi = glm::max(t.v[0], glm::max(t.v[1], t.v[2]));
        glm::vec3 lo, hi;
        if (p.motion.empty()) placedBox(box, p.toWorld, lo, hi);
        else motionBox(box, p.motion, lo, hi);
        SweptLight out{static_cast<std::uint32_t>(emitter), glm::dvec3(lo), glm::dvec3(hi), false};
        const glm::dvec3 n = glm::cross(glm::dvec3(t.v[1] - t.v[0]), glm::dvec3(t.v[2] - t.v[0]));
        glm::dvec3 first(0.0);
        for (const MotionKey& key : p.motion) {
            const glm::dmat3 normals = glm::transpose(glm::inverse(glm::dmat3(interpolatePose(key, key, 0.0))));
            const glm::dvec3 w = glm::normalize(normals * n);
            if (&key == &p.motion.front()) first = w;
            out.turns = out.turns || !(glm::dot(w, first) > 1.0 - 1e-9);
        }
        return out;
    }

private:
    struct Range {
        std::size_t first, end;  // scene triangles
        std::size_t bottom, placement;
    };
    const Range* find(std::size_t index) const {
        auto it = std::upper_bound(ranges_.begin(), ranges_.end(), index,
                                   [](std::size_t i, const Range& r) { return i < r.first; });
        if (it == ranges_.begin()) return nullptr;
        --it;
        return index < it->end ? &*it : nullptr;
    }
    const SceneBvh& bvh_;
    std::vector<Range> ranges_;  // in order of `first`
};

}  // namespace strata
