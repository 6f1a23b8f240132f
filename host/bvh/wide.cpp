#include "bvh/wide.h"

#include <algorithm>
#include <array>
#include <chrono>
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

    // The least cost of BVH2 node i's subtree in at most j child slots of a
    // wide node is cost[i][j - 1]; split[i][j - 1] is how many of those slots
    // its left subtree takes (0: the subtree takes one slot itself, as a
    // leaf if asLeaf[i], else as a wide node); tris and firstTri give its
    // triangle range (contiguous: the builder keeps a subtree's triangles
    // together, checked below).
    std::vector<std::array<float, 4>> cost;
    std::vector<std::array<std::uint8_t, 4>> split;
    std::vector<std::uint8_t> asLeaf;
    std::vector<std::uint32_t> tris, firstTri;

    // Bottom-up over the BVH2 (children follow their parent in the array).
    void plan() {
        const std::size_t n = in.size();
        cost.assign(n, {});
        split.assign(n, {});
        asLeaf.assign(n, 0);
        tris.assign(n, 0);
        firstTri.assign(n, 0);
        for (std::size_t i = n; i-- > 0;) {
            const gpu::BvhNode& b = in[i];
            const float area = halfArea(b);
            if (b.count > 0) {
                tris[i] = b.count;
                firstTri[i] = b.leftOrFirst;
                asLeaf[i] = 1;
                cost[i].fill(area * float(b.count));
                continue;
            }
            const std::uint32_t l = std::uint32_t(i) + 1, r = b.leftOrFirst;
            tris[i] = tris[l] + tris[r];
            firstTri[i] = firstTri[l];
            float spread[4] = {kInf, kInf, kInf, kInf};  // both subtrees, in at most j slots
            std::uint8_t left[4] = {0, 0, 0, 0};
            for (int j = 2; j <= 4; ++j)
                for (int k = 1; k < j; ++k) {
                    const float c = cost[l][k - 1] + cost[r][j - k - 1];
                    if (c < spread[j - 1]) spread[j - 1] = c, left[j - 1] = std::uint8_t(k);
                }
            const bool contiguous = firstTri[l] + tris[l] == firstTri[r];
            const float leaf = contiguous && tris[i] <= kWideLeafMax ? area * float(tris[i]) : kInf;
            const float node = area * kWideNodeCost + spread[3];
            asLeaf[i] = leaf <= node;
            cost[i][0] = std::min(leaf, node);
            for (int j = 2; j <= 4; ++j) {
                const bool fewer = cost[i][j - 2] <= spread[j - 1];
                cost[i][j - 1] = fewer ? cost[i][j - 2] : spread[j - 1];
                split[i][j - 1] = fewer ? split[i][j - 2] : left[j - 1];
            }
        }
    }

    // The BVH2 nodes that take the (at most j) slots of node i's subtree.
    void gather(std::uint32_t i, int j, std::uint32_t* kids, int& n) const {
        const int k = split[i][j - 1];
        if (k == 0) {
            kids[n++] = i;
            return;
        }
        gather(i + 1, k, kids, n);
        gather(in[i].leftOrFirst, j - k, kids, n);
    }

    // Leaf reference(s) for triangles [first, first + count) (a BVH2 leaf or
    // a subtree made one leaf): one child, or (count above
    // 2^kBvhLeafCountBits, only a BVH2 leaf where centroids coincide) a node
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
        std::uint32_t kids[4] = {0, 0, 0, 0};
        int n = 0;
        gather(root + 1, split[root][3], kids, n);
        gather(in[root].leftOrFirst, 4 - split[root][3], kids, n);
        const std::uint32_t index = newNode();
        for (int k = 0; k < n; ++k) {
            const std::uint32_t i = kids[k];
            const gpu::BvhNode& c = in[i];
            const std::uint32_t ref = asLeaf[i] ? leafRef(firstTri[i], tris[i], c, depth + 1) : node(i, depth + 1);
            setBox(index, k, c);
            out.nodes[index].child[k] = ref;
            out.sahCost += double(halfArea(c)) * (asLeaf[i] ? double(tris[i]) : double(kWideNodeCost));
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
    const auto start = std::chrono::steady_clock::now();
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
        c.out.sahCost = kWideNodeCost + nodes[0].count;
    } else {
        c.plan();
        c.node(0, 0);
        const float rootArea = halfArea(nodes[0]);
        c.out.sahCost = rootArea > 0.0f ? kWideNodeCost + c.out.sahCost / rootArea : 0.0;
    }
    c.out.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return std::move(c.out);
}

}  // namespace strata
