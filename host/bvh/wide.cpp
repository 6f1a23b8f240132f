#include "bvh/wide.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <thread>

#include "bvh/build_memory.h"
#include "bvh/task_pool.h"
#include "util/error.h"

namespace strata {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// Subtrees smaller than this are planned whole by one thread.
constexpr std::uint32_t kPlanMinNodes = 1u << 14;

float halfArea(const gpu::BvhNode& n) {
    const glm::vec3 e = n.bmax - n.bmin;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

struct Collapser {
    const std::vector<gpu::BvhNode>& in;
    WideBvh out;

    // What the plan keeps of BVH2 node i: decision[i] bits 2(j-2) and up
    // say how many of the (at most j, 2 <= j <= 4) slots of its subtree its
    // left subtree takes (0: the subtree takes one slot itself), bit
    // kAsLeaf that a slot it takes itself is a leaf (else a wide node).
    static constexpr std::uint8_t kAsLeaf = 0x40;
    std::unique_ptr<std::uint8_t[]> decision;

    int splitOf(std::uint32_t i, int j) const { return j < 2 ? 0 : (decision[i] >> (2 * (j - 2))) & 3; }
    bool asLeaf(std::uint32_t i) const { return (decision[i] & kAsLeaf) != 0; }

    // A subtree's plan: cost[j - 1] is the least SAH cost of holding it in
    // at most j child slots; first and tris its triangle range (tris stops
    // counting at 255; only ranges of at most kWideLeafMax are used).
    struct Plan {
        std::array<float, 4> cost;
        std::uint32_t first;
        std::uint32_t tris;
    };

    // Node i from its subtrees' plans (Ylitie et al.'s recurrence for four
    // slots); records the decision and returns i's plan.
    Plan combine(std::uint32_t i, const Plan& l, const Plan& r) {
        const gpu::BvhNode& b = in[i];
        const float area = halfArea(b);
        Plan p;
        p.first = l.first;
        p.tris = std::min(l.tris + r.tris, 255u);
        float spread[4] = {kInf, kInf, kInf, kInf};  // both subtrees, in at most j slots
        int left[4] = {0, 0, 0, 0};
        for (int j = 2; j <= 4; ++j)
            for (int k = 1; k < j; ++k) {
                const float c = l.cost[k - 1] + r.cost[j - k - 1];
                if (c < spread[j - 1]) spread[j - 1] = c, left[j - 1] = k;
            }
        // The builder keeps a subtree's triangles together; checked here.
        const bool contiguous = l.first + l.tris == r.first;
        const float leaf = contiguous && p.tris <= kWideLeafMax ? area * float(p.tris) : kInf;
        const float node = area * kWideNodeCost + spread[3];
        std::uint8_t d = leaf <= node ? kAsLeaf : 0;
        p.cost[0] = std::min(leaf, node);
        int k = 0;
        for (int j = 2; j <= 4; ++j) {
            const bool fewer = p.cost[j - 2] <= spread[j - 1];
            p.cost[j - 1] = fewer ? p.cost[j - 2] : spread[j - 1];
            k = fewer ? k : left[j - 1];
            d = std::uint8_t(d | k << (2 * (j - 2)));
        }
        decision[i] = d;
        return p;
    }

    Plan leafPlan(std::uint32_t i) {
        const gpu::BvhNode& b = in[i];
        decision[i] = kAsLeaf;
        Plan p;
        p.cost.fill(halfArea(b) * float(b.count));
        p.first = b.leftOrFirst;
        p.tris = std::min(b.count, 255u);
        return p;
    }

    // Depth first, so the nodes are read in array order (children follow
    // their parent; the BVH2 is at most kBvhStackSize deep).
    Plan planSubtree(std::uint32_t i) {
        if (in[i].count > 0) return leafPlan(i);
        const Plan l = planSubtree(i + 1);
        const Plan r = planSubtree(in[i].leftOrFirst);
        return combine(i, l, r);
    }

    // The subtrees under a cut through the top of the tree (a subtree is
    // the contiguous range [i, end)) are planned in parallel, then the nodes
    // above the cut from the highest index down (each after its children).
    // The decisions do not depend on the cut.
    void plan(unsigned threads) {
        const std::size_t n = in.size();
        decision = allocateLarge<std::uint8_t>(n);
        struct Range {
            std::uint32_t begin, end;
        };
        std::vector<Range> ranges{{0, std::uint32_t(n)}};
        std::vector<std::uint32_t> top;
        const std::size_t want = threads > 1 ? 4 * std::size_t(threads) : 1;
        while (ranges.size() < want) {
            auto largest = std::max_element(ranges.begin(), ranges.end(), [](const Range& a, const Range& b) {
                return a.end - a.begin < b.end - b.begin;
            });
            const Range r = *largest;
            if (r.end - r.begin < kPlanMinNodes || in[r.begin].count > 0) break;
            top.push_back(r.begin);
            *largest = {r.begin + 1, in[r.begin].leftOrFirst};
            ranges.push_back({in[r.begin].leftOrFirst, r.end});
        }
        if (ranges.size() == 1) {
            planSubtree(0);
            return;
        }
        std::vector<Plan> plans(ranges.size());
        TaskPool pool(threads - 1);
        pool.parallelFor(std::uint32_t(ranges.size()),
                         [&](std::uint32_t k) { plans[k] = planSubtree(ranges[k].begin); });
        std::vector<std::pair<std::uint32_t, Plan>> done;  // (node, plan) above and at the cut
        for (std::size_t k = 0; k < ranges.size(); ++k) done.push_back({ranges[k].begin, plans[k]});
        auto planOf = [&done](std::uint32_t i) {
            return std::find_if(done.begin(), done.end(), [i](const auto& e) { return e.first == i; })->second;
        };
        std::sort(top.begin(), top.end(), std::greater<>());
        for (std::uint32_t i : top) done.push_back({i, combine(i, planOf(i + 1), planOf(in[i].leftOrFirst))});
    }

    // The triangle range of node i's subtree, from its leaves.
    std::uint32_t firstTri(std::uint32_t i) const {
        while (in[i].count == 0) ++i;  // the leftmost leaf: left children follow their parent
        return in[i].leftOrFirst;
    }
    std::uint32_t triCount(std::uint32_t i) const {
        return in[i].count > 0 ? in[i].count : triCount(i + 1) + triCount(in[i].leftOrFirst);
    }

    // The BVH2 nodes that take the (at most j) slots of node i's subtree.
    void gather(std::uint32_t i, int j, std::uint32_t* kids, int& n) const {
        const int k = splitOf(i, j);
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
        // The plan may keep this subtree in one slot (0: a node whose box
        // has no area costs no more than its children, or costs are not
        // finite); a node opened here spreads it over both children.
        const int left = std::clamp(splitOf(root, 4), 1, 3);
        gather(root + 1, left, kids, n);
        gather(in[root].leftOrFirst, 4 - left, kids, n);
        const std::uint32_t index = newNode();
        for (int k = 0; k < n; ++k) {
            const std::uint32_t i = kids[k];
            const gpu::BvhNode& c = in[i];
            const bool leaf = asLeaf(i);
            const std::uint32_t tris = leaf ? triCount(i) : 0;
            const std::uint32_t ref = leaf ? leafRef(firstTri(i), tris, c, depth + 1) : node(i, depth + 1);
            setBox(index, k, c);
            out.nodes[index].child[k] = ref;
            out.sahCost += double(halfArea(c)) * (leaf ? double(tris) : double(kWideNodeCost));
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

WideBvh collapseBvh4(const std::vector<gpu::BvhNode>& nodes, unsigned threads) {
    const auto start = std::chrono::steady_clock::now();
    Collapser c{nodes, {}};
    c.out.nodes.reserve(nodes.size() / 2 + 1);
    adviseHugePages(c.out.nodes.data(), c.out.nodes.capacity() * sizeof(gpu::BvhNode4));
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
        c.plan(std::max(threads > 0 ? threads : std::thread::hardware_concurrency(), 1u));
        c.node(0, 0);
        const float rootArea = halfArea(nodes[0]);
        c.out.sahCost = rootArea > 0.0f ? kWideNodeCost + c.out.sahCost / rootArea : 0.0;
    }
    c.out.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return std::move(c.out);
}

}  // namespace strata
