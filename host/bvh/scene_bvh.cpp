#include "bvh/scene_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/pose.h"
#include "util/error.h"

namespace strata {
namespace {

TriangleVertices viewOf(const Scene& scene, std::size_t first, std::size_t count) {
    TriangleVertices view;
    if (count > 0)
        for (int k = 0; k < 3; ++k)
            view.base[k] = reinterpret_cast<const std::byte*>(&scene.triangles[first].v[k]);
    view.stride = sizeof(Triangle);
    view.count = count;
    return view;
}

// Appends `part`, built over triangles [first, first + count), to `out`:
// node and triangle references moved by the nodes and triangles before it.
BottomLevel append(SceneBvh& out, SceneBvh&& part, std::size_t first, std::size_t count) {
    BottomLevel b;
    b.empty = count == 0;
    if (b.empty) return b;
    const auto base2 = std::uint32_t(out.binary.nodes.size());
    const auto base4 = std::uint32_t(out.wide.nodes.size());
    const auto triBase = std::uint32_t(first);
    b.root2 = base2;
    b.root4 = base4;
    const gpu::BvhNode& root = part.binary.nodes[0];
    b.lo = root.bmin;
    b.hi = root.bmax;
    for (gpu::BvhNode n : part.binary.nodes) {
        n.leftOrFirst += n.count > 0 ? triBase : base2;
        out.binary.nodes.push_back(n);
    }
    for (std::uint32_t i : part.binary.triIndices) out.binary.triIndices.push_back(i + triBase);
    for (gpu::BvhNode4 n : part.wide.nodes) {
        for (int c = 0; c < 4; ++c) {
            std::uint32_t& ref = n.child[c];
            if (ref == gpu::kBvhChildEmpty) continue;
            if ((ref & gpu::kBvhLeafBit) == 0u) {
                ref += base4;
                continue;
            }
            const std::uint32_t countBits = ref & ((1u << gpu::kBvhLeafCountBits) - 1u);
            const std::uint64_t leafFirst = ((ref & ~gpu::kBvhLeafBit) >> gpu::kBvhLeafCountBits) + std::uint64_t(triBase);
            if (leafFirst >= gpu::kBvhMaxLeafFirst)
                throw Error("the scene's stored triangles exceed the four-wide BVH's leaf references (" +
                            std::to_string(gpu::kBvhMaxLeafFirst) + ")");
            ref = gpu::kBvhLeafBit | std::uint32_t(leafFirst) << gpu::kBvhLeafCountBits | countBits;
        }
        out.wide.nodes.push_back(n);
    }
    BvhStats& s = out.binary.stats;
    const BvhStats& p = part.binary.stats;
    s.nodes += p.nodes;
    s.leaves += p.leaves;
    s.maxDepth = std::max(s.maxDepth, p.maxDepth);
    s.sahCost = std::max(s.sahCost, p.sahCost);
    s.buildMs += p.buildMs;
    s.bytes += p.bytes;
    out.wide.maxDepth = std::max(out.wide.maxDepth, part.wide.maxDepth);
    out.wide.sahCost = std::max(out.wide.sahCost, part.wide.sahCost);
    out.wide.buildMs += part.wide.buildMs;
    return b;
}

SceneBvh buildRange(const Scene& scene, std::size_t first, std::size_t count, const BvhBuildOptions& options) {
    SceneBvh out;
    out.binary = buildBvh(viewOf(scene, first, count), options);
    out.wide = collapseBvh4(out.binary.nodes, unsigned(std::max(options.threads, 0)));
    return out;
}

// Corner c (bits x, y, z: 0 the low side, 1 the high) of a bottom level's box.
glm::dvec3 corner(const BottomLevel& bottom, int c) {
    return {(c & 1) ? bottom.hi.x : bottom.lo.x, (c & 2) ? bottom.hi.y : bottom.lo.y,
            (c & 4) ? bottom.hi.z : bottom.lo.z};
}

// The box [a, b] in float, rounded outwards (it contains the double box).
void roundOut(const glm::dvec3& a, const glm::dvec3& b, glm::vec3& lo, glm::vec3& hi) {
    for (int k = 0; k < 3; ++k) {
        lo[k] = std::nextafter(float(a[k]), -std::numeric_limits<float>::infinity());
        hi[k] = std::nextafter(float(b[k]), std::numeric_limits<float>::infinity());
    }
}

}  // namespace

void placedBox(const BottomLevel& bottom, const glm::mat4& toWorld, glm::vec3& lo, glm::vec3& hi) {
    const glm::dmat4 m(toWorld);
    glm::dvec3 a(std::numeric_limits<double>::max()), b(-std::numeric_limits<double>::max());
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 w(m * glm::dvec4(corner(bottom, c), 1.0));
        a = glm::min(a, w);
        b = glm::max(b, w);
    }
    roundOut(a, b, lo, hi);
}

void motionBox(const BottomLevel& bottom, const std::vector<MotionKey>& motion, glm::vec3& lo, glm::vec3& hi) {
    glm::dvec3 a(std::numeric_limits<double>::max()), b(-std::numeric_limits<double>::max());
    double pad = 0.0;
    for (std::size_t k = 0; k + 1 < motion.size(); ++k) {
        glm::dvec3 previous[8];
        for (int step = 0; step <= kMotionBoxSteps; ++step) {
            const glm::dmat4 m = interpolatePose(motion[k], motion[k + 1], double(step) / kMotionBoxSteps);
            for (int c = 0; c < 8; ++c) {
                const glm::dvec3 w(m * glm::dvec4(corner(bottom, c), 1.0));
                a = glm::min(a, w);
                b = glm::max(b, w);
                if (step > 0) pad = std::max(pad, 0.25 * glm::length(w - previous[c]));
                previous[c] = w;
            }
        }
    }
    roundOut(a - pad, b + pad, lo, hi);
}

SceneBvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options) {
    if (!scene.instanced()) return buildRange(scene, 0, scene.triangles.size(), options);
    SceneBvh out;
    const std::size_t world = scene.worldTriangles();
    out.bottoms.push_back(append(out, buildRange(scene, 0, world, options), 0, world));
    for (const SharedMesh& m : scene.sharedMeshes)
        out.bottoms.push_back(append(out, buildRange(scene, m.first, m.count, options), m.first, m.count));
    buildTopLevel(scene, out, options);
    if (out.placements.empty()) {  // nothing with triangles: the empty scene
        out.bottoms.clear();
        return buildRange(scene, 0, 0, options);
    }
    return out;
}

void buildTopLevel(const Scene& scene, SceneBvh& out, const BvhBuildOptions& options) {
    out.placements.clear();
    if (!out.bottoms[0].empty) out.placements.push_back({0, glm::mat4(1.0f), {}});
    for (const MeshInstance& i : scene.instances)
        if (!out.bottoms[1 + i.mesh].empty) out.placements.push_back({1 + i.mesh, i.toWorld, i.motion});
    if (out.placements.empty()) return;
    // The top level over the placements' world boxes, each given to the
    // builder as the degenerate triangle (lo, hi, centre), whose bounds are the box.
    const std::size_t n = out.placements.size();
    std::vector<glm::vec3> v0(n), v1(n), v2(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Placement& p = out.placements[i];
        if (p.motion.empty())
            placedBox(out.bottoms[p.bottom], p.toWorld, v0[i], v1[i]);
        else
            motionBox(out.bottoms[p.bottom], p.motion, v0[i], v1[i]);
        v2[i] = 0.5f * (v0[i] + v1[i]);
    }
    BvhBuildOptions top = options;
    top.maxLeafSize = 1;
    out.top = buildBvh(v0, v1, v2, top);
}

}  // namespace strata
