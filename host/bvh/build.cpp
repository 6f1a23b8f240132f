// Binned SAH BVH2 builder (Wald 2007, "On fast construction of SAH-based
// bounding volume hierarchies"), flattened depth-first into gpu::BvhNode.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <thread>
#include <utility>

#include "bvh/build_bins.h"
#include "bvh/bvh.h"
#include "bvh/build_memory.h"
#include "bvh/task_pool.h"

namespace strata {
namespace {

using namespace bvhbuild;

inline std::uint32_t ceilLog2(std::uint32_t n) {
    return n <= 1 ? 0u : std::uint32_t(std::bit_width(n - 1));
}

// A node to build: prims [begin, end), their bounds and centroid bounds.
struct Task {
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
    Box box;
    Box cbox;  // bounds of doubled centroids
    std::uint32_t depth = 0;
};

// Nodes with at least this many triangles are built as tasks of their own
// (children handed to the pool); smaller ones are built by one thread.
constexpr std::uint32_t kTaskMinPrims = 1u << 12;
// Nodes with at least this many triangles bin and partition in chunks of
// kChunkPrims on all threads. Chunk bounds do not depend on the thread
// count, so neither does the output.
constexpr std::uint32_t kParallelMinPrims = 1u << 15;
constexpr std::uint32_t kChunkPrims = 1u << 13;
// Nodes with at most this many triangles find their split without bins.
constexpr std::uint32_t kFewPrims = 4;

// A built subtree: either `nodes`, a depth-first subtree with indices local to
// it, or (left set) one interior node nodes[0] over two child subtrees.
struct Subtree {
    NodeList nodes;
    gpu::BvhNode top;  // the interior node when left is set
    std::unique_ptr<Subtree> left, right;
    std::uint32_t size = 0;  // nodes in the whole subtree, set by layout()
    std::uint32_t maxDepth = 0;
};

class Builder {
public:
    Builder(PrimRef* prims, std::uint32_t* triIndices, NodeArena& arena, int bins,
            std::uint32_t maxLeaf, float traversalCost, TaskPool* pool)
        : prims_(prims), triIndices_(triIndices), arena_(arena), bins_(bins), maxLeaf_(maxLeaf),
          traversalCost_(traversalCost), pool_(pool) {}

    // Builds the subtree of `task` into `out`, handing large children to the
    // pool as tasks of their own.
    void buildTask(const Task& task, Subtree& out);

private:
    // Decides whether `task` splits; if so partitions it into left/right.
    bool split(const Task& task, Task& left, Task& right, BinSet& bins, bool parallel);
    void buildSerial(const Task& task, NodeList& nodes, std::uint32_t& maxDepth, BinSet& bins);
    SahSplit findSah(const Task& task, BinSet& bins, bool parallel);
    SahSplit findSahFew(const Task& task, V4 cmin, V4 scale, const bool valid[3]) const;
    void binRange(std::uint32_t begin, std::uint32_t end, V4 cmin, V4 scale, BinSet& bins) const;
    std::uint32_t partitionSah(const Task& task, const SahSplit& split, Box& lc, Box& rc,
                               bool parallel);
    std::uint32_t partitionRange(std::uint32_t begin, std::uint32_t end, int a, float cmin,
                                 const SahSplit& split, Box& lc, Box& rc);
    std::uint32_t partitionMedian(const Task& task, Task& left, Task& right);

    // Writes triIndices_ for prims [begin, end), whose order is final.
    void writeTriIndices(std::uint32_t begin, std::uint32_t end) const {
        for (std::uint32_t i = begin; i < end; ++i) triIndices_[i] = prims_[i].id();
    }

    PrimRef* prims_;  // buildBvh's array, partitioned in place
    std::uint32_t* triIndices_;  // Bvh::triIndices, written as subtrees finish
    NodeArena& arena_;
    int bins_;
    std::uint32_t maxLeaf_;
    float traversalCost_;
    TaskPool* pool_;
};

gpu::BvhNode makeNode(const Box& box, std::uint32_t leftOrFirst, std::uint32_t count) {
    gpu::BvhNode node;
    node.bmin = toVec3(box.lo);
    node.bmax = toVec3(box.hi);
    node.leftOrFirst = leftOrFirst;
    node.count = count;
    return node;
}

void Builder::binRange(std::uint32_t begin, std::uint32_t end, V4 cmin, V4 scale,
                       BinSet& bins) const {
    const float topf = float(bins_ - 1);
    const V4 top = {topf, topf, topf, topf};
    Bin* b0 = bins.axis(0);
    Bin* b1 = bins.axis(1);
    Bin* b2 = bins.axis(2);
    auto binAll = [&](auto&& mark) {
        for (std::uint32_t i = begin; i < end; ++i) {
            const PrimRef& p = prims_[i];
            const V4i k = binOf(centroid2(p), cmin, scale, top);
            b0[k[0]].add(p);
            b1[k[1]].add(p);
            b2[k[2]].add(p);
            mark(k);
        }
    };
    if (end - begin >= 4u * std::uint32_t(bins_)) {
        // Many triangles per bin: occupancy read from the counts afterwards.
        binAll([](V4i) {});
        for (int a = 0; a < 3; ++a) {
            const Bin* b = bins.axis(a);
            for (int k = 0; k < bins_; ++k) {
                if (b[k].count() != 0) bins.mark(a, k);
            }
        }
    } else if (bins_ > 64) {
        binAll([&](V4i k) {
            bins.mark(0, k[0]);
            bins.mark(1, k[1]);
            bins.mark(2, k[2]);
        });
    } else {
        // Occupancy kept in registers.
        std::uint64_t u0 = 0, u1 = 0, u2 = 0;
        binAll([&](V4i k) {
            u0 |= std::uint64_t(1) << k[0];
            u1 |= std::uint64_t(1) << k[1];
            u2 |= std::uint64_t(1) << k[2];
        });
        bins.used[0][0] |= u0;
        bins.used[1][0] |= u1;
        bins.used[2][0] |= u2;
    }
}

SahSplit Builder::findSah(const Task& task, BinSet& bins, bool parallel) {
    SahSplit best;
    V4 scale = {0.0f, 0.0f, 0.0f, 0.0f};
    bool valid[3];
    for (int a = 0; a < 3; ++a) {
        float extent = task.cbox.hi[a] - task.cbox.lo[a];
        float s = float(bins_) / extent;
        valid[a] = extent > 0.0f && std::isfinite(s);
        scale[a] = valid[a] ? s : 0.0f;
    }
    if (!valid[0] && !valid[1] && !valid[2]) return best;

    const V4 cmin = task.cbox.lo;
    if (task.end - task.begin <= kFewPrims) return findSahFew(task, cmin, scale, valid);
    if (parallel) {
        // Bin fixed chunks into their own sets, then merge them in order
        // (min, max and counts: the merged bins do not depend on the order).
        const std::uint32_t chunks = (task.end - task.begin + kChunkPrims - 1) / kChunkPrims;
        std::vector<BinSet> part(chunks, BinSet(bins_));
        pool_->parallelFor(chunks, [&](std::uint32_t c) {
            const std::uint32_t b = task.begin + c * kChunkPrims;
            binRange(b, std::min(task.end, b + kChunkPrims), cmin, scale, part[c]);
        });
        for (BinSet& p : part) {
            for (int a = 0; a < 3; ++a) {
                for (int k = 0; k < bins_; ++k) {
                    const Bin& s = p.axis(a)[k];
                    if (s.count() == 0) continue;
                    bins.axis(a)[k].merge(s);
                    bins.mark(a, k);
                }
            }
        }
    } else {
        binRange(task.begin, task.end, cmin, scale, bins);
    }

    // Right-to-left sweep stores the right side's area and count per split
    // (after occupied bin j of the m occupied ones).
    bins.collect();
    float rightArea[kMaxBins];
    std::uint32_t rightCount[kMaxBins];
    for (int a = 0; a < 3; ++a) {
        if (!valid[a]) continue;
        const Bin* ab = bins.axis(a);
        const std::uint16_t* idx = bins.occupied[a];
        const int m = bins.occupiedCount[a];
        Box acc;
        std::uint32_t n = 0;
        for (int j = m - 1; j > 0; --j) {
            acc.grow(ab[idx[j]].box);
            n += ab[idx[j]].count();
            rightArea[j - 1] = acc.halfArea();
            rightCount[j - 1] = n;
        }
        acc = Box();
        n = 0;
        for (int j = 0; j < m - 1; ++j) {
            acc.grow(ab[idx[j]].box);
            n += ab[idx[j]].count();
            float cost = acc.halfArea() * float(n) + rightArea[j] * float(rightCount[j]);
            takeIfCheaper(best, cost, a, idx[j]);
        }
    }
    if (best.found) {
        best.scale = scale[best.axis];
        const Bin* ab = bins.axis(best.axis);
        const std::uint16_t* idx = bins.occupied[best.axis];
        const int m = bins.occupiedCount[best.axis];
        for (int j = 0; j < m; ++j) {
            (idx[j] <= best.bin ? best.left : best.right).grow(ab[idx[j]].box);
        }
    }
    bins.clear();
    return best;
}

// findSah for at most kFewPrims triangles: per axis, the triangles sorted by
// bin (stably) stand in for the bins. Candidates are the boundaries between
// occupied bins, visited in the same order and costed from the same boxes
// (unions are exact) and counts, so the split equals the binned sweep's.
SahSplit Builder::findSahFew(const Task& task, V4 cmin, V4 scale, const bool valid[3]) const {
    const std::uint32_t n = task.end - task.begin;
    const float topf = float(bins_ - 1);
    const V4 top = {topf, topf, topf, topf};
    Box box[kFewPrims];
    V4i key[kFewPrims];
    for (std::uint32_t i = 0; i < n; ++i) {
        const PrimRef& p = prims_[task.begin + i];
        box[i] = Box{p.lo, p.hi};
        key[i] = binOf(centroid2(p), cmin, scale, top);
    }
    SahSplit best;
    float rightArea[kFewPrims];
    for (int a = 0; a < 3; ++a) {
        if (!valid[a]) continue;
        std::uint8_t order[kFewPrims];
        for (std::uint32_t i = 0; i < n; ++i) {
            std::uint32_t j = i;
            for (; j > 0 && key[order[j - 1]][a] > key[i][a]; --j) order[j] = order[j - 1];
            order[j] = std::uint8_t(i);
        }
        // Boundary after sorted position j: key[order[j]] < key[order[j + 1]].
        Box acc;
        for (std::uint32_t j = n - 1; j > 0; --j) {
            acc.grow(box[order[j]]);
            if (key[order[j - 1]][a] != key[order[j]][a]) rightArea[j - 1] = acc.halfArea();
        }
        acc = Box();
        for (std::uint32_t j = 0; j + 1 < n; ++j) {
            acc.grow(box[order[j]]);
            if (key[order[j]][a] == key[order[j + 1]][a]) continue;
            const float cost =
                acc.halfArea() * float(j + 1) + rightArea[j] * float(n - 1 - j);
            takeIfCheaper(best, cost, a, key[order[j]][a]);
        }
    }
    if (best.found) {
        best.scale = scale[best.axis];
        for (std::uint32_t i = 0; i < n; ++i) {
            (key[i][best.axis] <= best.bin ? best.left : best.right).grow(box[i]);
        }
    }
    return best;
}

// Hoare partition of [begin, end) by bin; returns the first index of the
// right side and grows lc/rc by the doubled centroids of both sides.
std::uint32_t Builder::partitionRange(std::uint32_t begin, std::uint32_t end, int a, float cmin,
                                      const SahSplit& split, Box& lc, Box& rc) {
    // binOf(c) <= split.bin, as binOf rounds: int(clamp(f)) <= bin exactly
    // when !(f >= bin + 1) (bin < bins - 1; a NaN f maps to bin 0).
    const float limit = float(split.bin + 1);
    auto isLeft = [&](const PrimRef& p) {
        return !((centroid2(p)[a] - cmin) * split.scale >= limit);
    };
    // Local accumulators: lc and rc may alias memory the swaps write, which
    // would keep them out of registers.
    Box l = lc, r = rc;
    std::uint32_t i = begin, j = end;
    for (;;) {
        while (i < j && isLeft(prims_[i])) l.grow(centroid2(prims_[i++]));
        while (i < j && !isLeft(prims_[j - 1])) r.grow(centroid2(prims_[--j]));
        if (i >= j) break;
        std::swap(prims_[i], prims_[j - 1]);
        l.grow(centroid2(prims_[i++]));
        r.grow(centroid2(prims_[--j]));
    }
    lc = l;
    rc = r;
    return i;
}

std::uint32_t Builder::partitionSah(const Task& task, const SahSplit& split, Box& lc, Box& rc,
                                    bool parallel) {
    const int a = split.axis;
    const float cmin = task.cbox.lo[a];
    if (!parallel) return partitionRange(task.begin, task.end, a, cmin, split, lc, rc);

    // Each fixed chunk is partitioned in place; then the right-side triangles
    // left of the final split point swap, in order, with the left-side
    // triangles right of it.
    const std::uint32_t chunks = (task.end - task.begin + kChunkPrims - 1) / kChunkPrims;
    std::vector<std::uint32_t> mid(chunks);
    std::vector<Box> lcs(chunks), rcs(chunks);
    pool_->parallelFor(chunks, [&](std::uint32_t c) {
        const std::uint32_t b = task.begin + c * kChunkPrims;
        mid[c] = partitionRange(b, std::min(task.end, b + kChunkPrims), a, cmin, split, lcs[c],
                                rcs[c]);
    });
    std::uint32_t split0 = task.begin;
    for (std::uint32_t c = 0; c < chunks; ++c) {
        split0 += mid[c] - (task.begin + c * kChunkPrims);
        lc.grow(lcs[c]);
        rc.grow(rcs[c]);
    }
    // Misplaced runs: [from, to) ranges, ascending.
    struct Run {
        std::uint32_t from, to;
    };
    std::vector<Run> wrongRight, wrongLeft;
    for (std::uint32_t c = 0; c < chunks; ++c) {
        const std::uint32_t b = task.begin + c * kChunkPrims;
        const std::uint32_t e = std::min(task.end, b + kChunkPrims);
        if (mid[c] < split0 && mid[c] < e) wrongRight.push_back({mid[c], std::min(e, split0)});
        if (b < mid[c] && mid[c] > split0) wrongLeft.push_back({std::max(b, split0), mid[c]});
    }
    std::size_t r = 0, l = 0;
    std::uint32_t ri = wrongRight.empty() ? 0 : wrongRight[0].from;
    std::uint32_t li = wrongLeft.empty() ? 0 : wrongLeft[0].from;
    while (r < wrongRight.size() && l < wrongLeft.size()) {
        const std::uint32_t n = std::min(wrongRight[r].to - ri, wrongLeft[l].to - li);
        std::swap_ranges(prims_ + ri, prims_ + ri + n, prims_ + li);
        ri += n;
        li += n;
        if (ri == wrongRight[r].to && ++r < wrongRight.size()) ri = wrongRight[r].from;
        if (li == wrongLeft[l].to && ++l < wrongLeft.size()) li = wrongLeft[l].from;
    }
    return split0;
}

// Object median on the axis of largest centroid extent, ties broken by input
// index. Used when SAH finds no split and to bound the depth.
std::uint32_t Builder::partitionMedian(const Task& task, Task& left, Task& right) {
    const V4 e = task.cbox.hi - task.cbox.lo;
    const int a = (e[0] >= e[1]) ? (e[0] >= e[2] ? 0 : 2) : (e[1] >= e[2] ? 1 : 2);
    auto key = [a](const PrimRef& p) {
        float c = centroid2(p)[a];
        return c == c ? c : -kInf;
    };
    const std::uint32_t mid = task.begin + (task.end - task.begin) / 2;
    std::nth_element(prims_ + task.begin, prims_ + mid, prims_ + task.end,
                     [&](const PrimRef& x, const PrimRef& y) {
                         float kx = key(x), ky = key(y);
                         return kx < ky || (kx == ky && x.id() < y.id());
                     });
    for (std::uint32_t i = task.begin; i < task.end; ++i) {
        Task& side = i < mid ? left : right;
        side.box.grow(Box{prims_[i].lo, prims_[i].hi});
        side.cbox.grow(centroid2(prims_[i]));
    }
    return mid;
}

bool Builder::split(const Task& task, Task& left, Task& right, BinSet& bins, bool parallel) {
    const std::uint32_t n = task.end - task.begin;
    const V4 cext = task.cbox.hi - task.cbox.lo;
    const bool coincide = !(cext[0] > 0.0f || cext[1] > 0.0f || cext[2] > 0.0f);
    if (n <= 1 || coincide) return false;

    left.depth = right.depth = task.depth + 1;
    left.begin = task.begin;
    right.end = task.end;
    // Splitting by object median keeps depth + ceil(log2(count)) constant,
    // so switching to it here keeps every leaf at depth < kBvhStackSize.
    if (task.depth + ceilLog2(n) >= kBvhStackSize - 1) {
        left.end = right.begin = partitionMedian(task, left, right);
        return true;
    }
    SahSplit sah = findSah(task, bins, parallel);
    if (sah.found) {
        const float area = task.box.halfArea();
        const float splitCost = traversalCost_ * area + sah.cost;
        const float leafCost = area * float(n);
        if (n <= maxLeaf_ && !(splitCost < leafCost)) return false;
        left.box = sah.left;
        right.box = sah.right;
        left.end = right.begin = partitionSah(task, sah, left.cbox, right.cbox, parallel);
        return true;
    }
    if (n <= maxLeaf_) return false;
    left.end = right.begin = partitionMedian(task, left, right);
    return true;
}

void Builder::buildSerial(const Task& task, NodeList& nodes, std::uint32_t& maxDepth,
                          BinSet& bins) {
    Task left, right;
    if (!split(task, left, right, bins, false)) {
        nodes.push_back(makeNode(task.box, task.begin, task.end - task.begin));
        maxDepth = std::max(maxDepth, task.depth);
        return;
    }
    const std::uint32_t index = nodes.size;
    nodes.push_back(makeNode(task.box, 0, 0));
    buildSerial(left, nodes, maxDepth, bins);
    nodes[index].leftOrFirst = nodes.size;
    buildSerial(right, nodes, maxDepth, bins);
}

void Builder::buildTask(const Task& task, Subtree& out) {
    const std::uint32_t n = task.end - task.begin;
    BinSet bins(bins_);
    if (n < kTaskMinPrims) {
        const std::size_t taken = 2 * std::size_t(n) - 1;
        out.nodes.data = arena_.take(taken);
        buildSerial(task, out.nodes, out.maxDepth, bins);
        // The unused tail of the range goes back to the kernel: on huge pages
        // a neighbour's writes would otherwise keep it resident (the whole
        // arena, twice the nodes built).
        discardPages(out.nodes.data + out.nodes.size, (taken - out.nodes.size) * sizeof(gpu::BvhNode));
        writeTriIndices(task.begin, task.end);
        return;
    }
    Task left, right;
    if (!split(task, left, right, bins, n >= kParallelMinPrims)) {
        out.nodes.data = arena_.take(1);
        out.nodes.push_back(makeNode(task.box, task.begin, n));
        out.maxDepth = task.depth;
        writeTriIndices(task.begin, task.end);
        return;
    }
    out.top = makeNode(task.box, 0, 0);
    out.maxDepth = task.depth;
    out.left = std::make_unique<Subtree>();
    out.right = std::make_unique<Subtree>();
    pool_->submit(left.end - left.begin, [this, left, sub = out.left.get()] { buildTask(left, *sub); });
    pool_->submit(right.end - right.begin,
                  [this, right, sub = out.right.get()] { buildTask(right, *sub); });
}

// Sets `size` bottom-up; returns the deepest leaf.
std::uint32_t measure(Subtree& t) {
    if (!t.left) {
        t.size = t.nodes.size;
        return t.maxDepth;
    }
    const std::uint32_t d = std::max(measure(*t.left), measure(*t.right));
    t.size = 1 + t.left->size + t.right->size;
    return d;
}

// A node's term of the SAH cost (times the root's half area).
double sahTerm(const gpu::BvhNode& node, float traversalCost) {
    return halfAreaD(node.bmin, node.bmax) *
           (node.count > 0 ? double(node.count) : double(traversalCost));
}

// Places the subtree at node index `base` of the depth-first order: interior
// nodes of the parallel top are written (their SAH terms added to sahSum),
// built subtrees listed for copying.
void layout(Subtree& t, std::uint32_t base, std::vector<gpu::BvhNode>& out,
            std::vector<std::pair<const Subtree*, std::uint32_t>>& copies, float traversalCost,
            double& sahSum) {
    if (!t.left) {
        copies.emplace_back(&t, base);
        return;
    }
    out[base] = t.top;
    out[base].leftOrFirst = base + 1 + t.left->size;
    sahSum += sahTerm(out[base], traversalCost);
    layout(*t.left, base + 1, out, copies, traversalCost, sahSum);
    layout(*t.right, base + 1 + t.left->size, out, copies, traversalCost, sahSum);
}

}  // namespace

Bvh buildBvh(const std::vector<glm::vec3>& v0, const std::vector<glm::vec3>& v1,
             const std::vector<glm::vec3>& v2, const BvhBuildOptions& options) {
    if (v0.size() != v1.size() || v0.size() != v2.size()) {
        throw std::invalid_argument("buildBvh: vertex arrays differ in length");
    }
    TriangleVertices view;
    const std::vector<glm::vec3>* arrays[3] = {&v0, &v1, &v2};
    for (int k = 0; k < 3; ++k) view.base[k] = reinterpret_cast<const std::byte*>(arrays[k]->data());
    view.count = v0.size();
    return buildBvh(view, options);
}

Bvh buildBvh(const TriangleVertices& tris, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    if (tris.count >= std::size_t(gpu::kNoHit)) {
        throw std::invalid_argument("buildBvh: too many triangles");
    }
    const std::uint32_t n = std::uint32_t(tris.count);

    Bvh bvh;
    if (n == 0) {
        gpu::BvhNode empty;
        empty.bmin = glm::vec3(kInf);
        empty.bmax = glm::vec3(-kInf);
        empty.leftOrFirst = 0;
        empty.count = 0;
        bvh.nodes.push_back(empty);
    } else {
        unsigned threads = options.threads > 0 ? unsigned(options.threads)
                                               : std::thread::hardware_concurrency();
        if (n < kTaskMinPrims) threads = 1;
        TaskPool pool(std::max(threads, 1u) - 1);
        const std::uint32_t chunks = (n + kChunkPrims - 1) / kChunkPrims;

        std::unique_ptr<PrimRef[]> prims = allocateLarge<PrimRef>(n);
        std::vector<Task> parts(chunks);
        pool.parallelFor(chunks, [&](std::uint32_t c) {
            Task& part = parts[c];
            for (std::uint32_t i = c * kChunkPrims, e = std::min(n, i + kChunkPrims); i < e; ++i) {
                Box b;
                for (int k = 0; k < 3; ++k) b.grow(toV4(tris.vertex(i, k)));
                part.box.grow(b);
                b.lo[3] = std::bit_cast<float>(i);
                b.hi[3] = 0.0f;
                prims[i] = PrimRef{b.lo, b.hi};
                part.cbox.grow(centroid2(prims[i]));
            }
        });
        Task root;
        root.end = n;
        for (const Task& part : parts) {
            root.box.grow(part.box);
            root.cbox.grow(part.cbox);
        }

        bvh.triIndices.reserve(n);
        adviseHugePages(bvh.triIndices.data(), std::size_t(n) * sizeof(std::uint32_t));
        bvh.triIndices.resize(n);
        NodeArena arena(2 * std::size_t(n));
        Builder builder(prims.get(), bvh.triIndices.data(), arena,
                        std::clamp(options.bins, kMinBins, kMaxBins),
                        std::uint32_t(std::max(options.maxLeafSize, 1)), options.traversalCost,
                        &pool);
        Subtree tree;
        builder.buildTask(root, tree);
        pool.drain();
        prims.reset();  // not read again; freed before the output nodes exist

        // Depth-first layout: the parallel top first, then the built
        // subtrees copied in parallel with their node indices offset.
        bvh.stats.maxDepth = measure(tree);
        bvh.nodes.reserve(tree.size);
        adviseHugePages(bvh.nodes.data(), std::size_t(tree.size) * sizeof(gpu::BvhNode));
        bvh.nodes.resize(tree.size);
        std::vector<std::pair<const Subtree*, std::uint32_t>> copies;
        double sum = 0.0;  // SAH terms of the nodes layout() writes
        layout(tree, 0, bvh.nodes, copies, options.traversalCost, sum);
        // SAH cost summed per copied subtree, then over them in node order
        // after the parallel top's nodes: independent of the thread count.
        const std::uint32_t jobs = std::uint32_t(copies.size());
        std::vector<double> jobSum(jobs);
        std::vector<std::uint32_t> jobLeaves(jobs);
        pool.parallelFor(jobs, [&](std::uint32_t j) {
            const auto [sub, base] = copies[j];
            gpu::BvhNode* dst = bvh.nodes.data() + base;
            double part = 0.0;
            std::uint32_t leaves = 0;
            for (std::uint32_t k = 0; k < sub->nodes.size; ++k) {
                gpu::BvhNode node = sub->nodes.data[k];
                if (node.count == 0) node.leftOrFirst += base;
                *dst++ = node;
                part += sahTerm(node, options.traversalCost);
                leaves += node.count > 0 ? 1u : 0u;
            }
            jobSum[j] = part;
            jobLeaves[j] = leaves;
        });
        for (std::uint32_t j = 0; j < jobs; ++j) {
            sum += jobSum[j];
            bvh.stats.leaves += jobLeaves[j];
        }
        const double rootArea = halfAreaD(toVec3(root.box.lo), toVec3(root.box.hi));
        bvh.stats.sahCost = rootArea > 0.0 ? sum / rootArea : 0.0;
    }
    bvh.stats.nodes = std::uint32_t(bvh.nodes.size());
    bvh.stats.bytes = std::uint64_t(bvh.nodes.size()) * sizeof(gpu::BvhNode);
    bvh.stats.buildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

}  // namespace strata
