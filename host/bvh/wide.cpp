#include "bvh/wide.h"

#include <algorithm>
#include <limits>
#include <string>

#include "util/error.h"

namespace strata {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float halfArea(const gpu::BvhNode& n) {
    const glm::vec3 e = n.bmax - n.bmin;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

struct Collapser {
    const std::vector<gpu::BvhNode>& in;
    WideBvh out;

    // Leaf reference(s) for BVH2 leaf [first, first + count): one child, or
    // (count above 2^kBvhLeafCountBits, only where centroids coincide) a node
    // of up to four chunks under the same box, nested as needed.
    std::uint32_t leafRef(std::uint32_t first, std::uint32_t count, const gpu::BvhNode& box,
                          std::uint32_t depth) {
        constexpr std::uint32_t kMax = 1u << gpu::kBvhLeafCountBits;
        if (count <= kMax) {
            if (first >= gpu::kBvhMaxLeafFirst)
                throw Error("strata: error: the scene has too many triangles for the BVH's leaf references (" +
                            std::to_string(first) + " or more)");
            out.maxDepth = std::max(out.maxDepth, depth);
            return gpu::kBvhLeafBit | first << gpu::kBvhLeafCountBits | (count - 1);
        }
        const std::uint32_t index = newNode();
        const std::uint32_t chunk = std::max(kMax, (count + 3) / 4);
        std::uint32_t refs[4] = {gpu::kBvhChildEmpty, gpu::kBvhChildEmpty, gpu::kBvhChildEmpty,
                                 gpu::kBvhChildEmpty};
        int k = 0;
        for (std::uint32_t f = first; f < first + count; f += chunk, ++k) {
            const std::uint32_t c = std::min(chunk, first + count - f);
            refs[k] = leafRef(f, c, box, depth + 1);
            setBox(index, k, box);
        }
        for (int j = 0; j < 4; ++j) out.nodes[index].child[j] = refs[j];
        for (int j = k; j < 4; ++j) setEmpty(index, j);
        return index;
    }

    void setBox(std::uint32_t index, int k, const gpu::BvhNode& n) {
        gpu::BvhNode4& w = out.nodes[index];
        w.minX[k] = n.bmin.x, w.minY[k] = n.bmin.y, w.minZ[k] = n.bmin.z;
        w.maxX[k] = n.bmax.x, w.maxY[k] = n.bmax.y, w.maxZ[k] = n.bmax.z;
    }
    void setEmpty(std::uint32_t index, int k) {
        gpu::BvhNode4& w = out.nodes[index];
        w.minX[k] = w.minY[k] = w.minZ[k] = kInf;
        w.maxX[k] = w.maxY[k] = w.maxZ[k] = -kInf;
        w.child[k] = gpu::kBvhChildEmpty;
    }

    // A new wide node's index; the traversal's stack entries keep it in 27
    // bits ((index << 4) | children mask, below kBvhLeafBit).
    std::uint32_t newNode() {
        if (out.nodes.size() >= (std::size_t(1) << 27))
            throw Error("strata: error: the scene's four-wide BVH needs more than 2^27 nodes");
        out.nodes.emplace_back();
        return static_cast<std::uint32_t>(out.nodes.size() - 1);
    }

    // Wide node for interior BVH2 node `root` at `depth` wide nodes below the root.
    std::uint32_t node(std::uint32_t root, std::uint32_t depth) {
        std::uint32_t kids[4] = {root + 1, in[root].leftOrFirst, 0, 0};
        int n = 2;
        while (n < 4) {
            int best = -1;
            float bestArea = -1.0f;
            for (int k = 0; k < n; ++k)
                if (in[kids[k]].count == 0 && halfArea(in[kids[k]]) > bestArea)
                    best = k, bestArea = halfArea(in[kids[k]]);
            if (best < 0) break;
            const std::uint32_t open = kids[best];
            kids[best] = open + 1;
            kids[n++] = in[open].leftOrFirst;
        }
        const std::uint32_t index = newNode();
        for (int k = 0; k < n; ++k) {
            const gpu::BvhNode& c = in[kids[k]];
            const std::uint32_t ref = c.count > 0 ? leafRef(c.leftOrFirst, c.count, c, depth + 1)
                                                  : node(kids[k], depth + 1);
            setBox(index, k, c);
            out.nodes[index].child[k] = ref;
        }
        for (int k = n; k < 4; ++k) setEmpty(index, k);
        return index;
    }
};

}  // namespace

std::uint32_t bvhRegsFor(std::uint32_t wideDepth) {
    for (std::uint32_t regs : {16u, 24u, 32u})
        if (wideDepth <= regs) return regs;
    return 0;
}

WideBvh collapseBvh4(const std::vector<gpu::BvhNode>& nodes) {
    Collapser c{nodes, {}};
    c.out.nodes.reserve(nodes.size() / 2 + 1);
    const bool empty = nodes.empty() || (nodes[0].count == 0 && nodes[0].leftOrFirst == 0);
    if (empty) {
        c.out.nodes.emplace_back();
        for (int k = 0; k < 4; ++k) c.setEmpty(0, k);
    } else if (nodes[0].count > 0) {  // a leaf root: one child under the root's box
        c.out.nodes.emplace_back();
        for (int k = 1; k < 4; ++k) c.setEmpty(0, k);
        const std::uint32_t ref = c.leafRef(nodes[0].leftOrFirst, nodes[0].count, nodes[0], 1);
        c.setBox(0, 0, nodes[0]);
        c.out.nodes[0].child[0] = ref;
    } else {
        c.node(0, 0);
    }
    return std::move(c.out);
}

}  // namespace strata
