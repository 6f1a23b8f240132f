// Binned SAH BVH2 builder (Wald 2007, "On fast construction of SAH-based
// bounding volume hierarchies"), flattened depth-first into gpu::BvhNode.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include "bvh/bvh.h"

namespace strata {
namespace {

constexpr int kMinBins = 2;
constexpr int kMaxBins = 256;
// Nodes with at least this many triangles hand their left subtree to a second
// thread (root only); below it a thread costs more than it saves.
constexpr std::uint32_t kParallelMinPrims = 1u << 14;
constexpr float kInf = std::numeric_limits<float>::infinity();

// Four float lanes (GCC/Clang vector extension); lane 3 carries no geometry.
using V4 = float __attribute__((vector_size(16)));
using V4i = std::int32_t __attribute__((vector_size(16)));

// Per-lane min/max; a NaN in x keeps acc (x is the second comparison operand).
inline V4 vmin(V4 acc, V4 x) { return x < acc ? x : acc; }
inline V4 vmax(V4 acc, V4 x) { return x > acc ? x : acc; }

// Axis-aligned box in lanes 0..2; the default box is empty ([+inf, -inf]).
struct Box {
    V4 lo = {kInf, kInf, kInf, kInf};
    V4 hi = {-kInf, -kInf, -kInf, -kInf};

    void grow(V4 p) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    void grow(const Box& b) {
        lo = vmin(lo, b.lo);
        hi = vmax(hi, b.hi);
    }
    // Half the surface area; SAH costs only use ratios of areas.
    float halfArea() const {
        V4 e = hi - lo;
        return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
    }
};

double halfAreaD(const glm::vec3& lo, const glm::vec3& hi) {
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return 0.0;
    double ex = double(hi.x) - lo.x, ey = double(hi.y) - lo.y, ez = double(hi.z) - lo.z;
    return ex * ey + ey * ez + ez * ex;
}

inline V4 toV4(const glm::vec3& v) { return V4{v.x, v.y, v.z, 0.0f}; }
inline glm::vec3 toVec3(V4 v) { return glm::vec3(v[0], v[1], v[2]); }

// One triangle's bounds (32 bytes, partitioned in place). Lane 3 of `lo`
// holds the input index's bits, lane 3 of `hi` is 0.
struct PrimRef {
    V4 lo;
    V4 hi;
    std::uint32_t id() const { return std::bit_cast<std::uint32_t>(lo[3]); }
};

// Twice the box centroid (the factor 1/2 cancels in binning); lane 3 is 0.
inline V4 centroid2(const PrimRef& p) {
    constexpr V4i kXyz = {-1, -1, -1, 0};
    return V4(V4i(p.lo) & kXyz) + p.hi;
}

// Bin of doubled centroid coordinates; NaN maps to bin 0. The scalar and
// vector forms round identically.
inline int binOf(float c2, float cmin, float scale, int bins) {
    float f = (c2 - cmin) * scale;
    f = f > 0.0f ? f : 0.0f;
    f = f < float(bins - 1) ? f : float(bins - 1);
    return int(f);
}
inline V4i binOf(V4 c2, V4 cmin, V4 scale, V4 top) {
    V4 f = (c2 - cmin) * scale;
    const V4 zero = {0.0f, 0.0f, 0.0f, 0.0f};
    f = f > zero ? f : zero;
    f = f < top ? f : top;
    return __builtin_convertvector(f, V4i);
}

inline std::uint32_t ceilLog2(std::uint32_t n) {
    std::uint32_t l = 0;
    while ((std::uint64_t(1) << l) < n) ++l;
    return l;
}

// A node to build: prims [begin, end), their bounds and centroid bounds.
struct Task {
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
    Box box;
    Box cbox;  // bounds of doubled centroids
    std::uint32_t depth = 0;
};

struct Bin {
    Box box;
    std::uint32_t count = 0;
};

struct SahSplit {
    bool found = false;
    int axis = 0;
    int bin = 0;        // left side holds bins [0, bin]
    float cost = kInf;  // AL*NL + AR*NR (half areas)
    float scale = 0.0f; // bins per doubled-centroid unit on `axis`
    Box left, right;
};

class Builder {
public:
    Builder(std::vector<PrimRef>& prims, int bins, std::uint32_t maxLeaf, float traversalCost)
        : prims_(prims), bins_(bins), maxLeaf_(maxLeaf), traversalCost_(traversalCost),
          binScratch_(std::size_t(3 * bins)) {}

    // Appends the subtree of `task` to nodes_, node indices relative to
    // nodes_.front(). `parallel` lets the root split run on two threads.
    void build(const Task& task, bool parallel);

    std::vector<gpu::BvhNode> nodes_;
    std::uint32_t maxDepth_ = 0;

private:
    void makeLeaf(const Task& task);
    SahSplit findSah(const Task& task);
    std::uint32_t partitionSah(const Task& task, const SahSplit& split, Box& lc, Box& rc);
    std::uint32_t partitionMedian(const Task& task, Task& left, Task& right);
    void append(const Builder& sub);

    std::vector<PrimRef>& prims_;
    int bins_;
    std::uint32_t maxLeaf_;
    float traversalCost_;
    std::vector<Bin> binScratch_;  // 3 axes x bins_
};

void Builder::makeLeaf(const Task& task) {
    gpu::BvhNode node;
    node.bmin = toVec3(task.box.lo);
    node.bmax = toVec3(task.box.hi);
    node.leftOrFirst = task.begin;
    node.count = task.end - task.begin;
    nodes_.push_back(node);
    maxDepth_ = std::max(maxDepth_, task.depth);
}

SahSplit Builder::findSah(const Task& task) {
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

    std::fill(binScratch_.begin(), binScratch_.end(), Bin{});
    Bin* bins[3] = {&binScratch_[0], &binScratch_[std::size_t(bins_)],
                    &binScratch_[std::size_t(2 * bins_)]};
    const V4 cmin = task.cbox.lo;
    const float topf = float(bins_ - 1);
    const V4 top = {topf, topf, topf, topf};
    for (std::uint32_t i = task.begin; i < task.end; ++i) {
        const PrimRef& p = prims_[i];
        const V4i k = binOf(centroid2(p), cmin, scale, top);
        for (int a = 0; a < 3; ++a) {
            Bin& b = bins[a][k[a]];
            b.count++;
            b.box.lo = vmin(b.box.lo, p.lo);
            b.box.hi = vmax(b.box.hi, p.hi);
        }
    }

    // Right-to-left sweep stores the right side's area and count per split.
    float rightArea[kMaxBins];
    std::uint32_t rightCount[kMaxBins];
    for (int a = 0; a < 3; ++a) {
        if (!valid[a]) continue;
        Box acc;
        std::uint32_t n = 0;
        for (int i = bins_ - 1; i > 0; --i) {
            acc.grow(bins[a][i].box);
            n += bins[a][i].count;
            rightArea[i - 1] = acc.halfArea();
            rightCount[i - 1] = n;
        }
        acc = Box();
        n = 0;
        for (int i = 0; i < bins_ - 1; ++i) {
            acc.grow(bins[a][i].box);
            n += bins[a][i].count;
            if (n == 0 || rightCount[i] == 0) continue;
            float cost = acc.halfArea() * float(n) + rightArea[i] * float(rightCount[i]);
            if (cost < best.cost || !best.found) {
                best.found = true;
                best.axis = a;
                best.bin = i;
                best.cost = cost;
            }
        }
    }
    if (best.found) {
        best.scale = scale[best.axis];
        for (int i = 0; i < bins_; ++i) {
            (i <= best.bin ? best.left : best.right).grow(bins[best.axis][i].box);
        }
    }
    return best;
}

// Hoare partition by bin; returns the first index of the right side and the
// doubled-centroid bounds of both sides.
std::uint32_t Builder::partitionSah(const Task& task, const SahSplit& split, Box& lc, Box& rc) {
    const int a = split.axis;
    const float cmin = task.cbox.lo[a];
    auto isLeft = [&](const PrimRef& p) {
        return binOf(centroid2(p)[a], cmin, split.scale, bins_) <= split.bin;
    };
    std::uint32_t i = task.begin, j = task.end;
    for (;;) {
        while (i < j && isLeft(prims_[i])) lc.grow(centroid2(prims_[i++]));
        while (i < j && !isLeft(prims_[j - 1])) rc.grow(centroid2(prims_[--j]));
        if (i >= j) break;
        std::swap(prims_[i], prims_[j - 1]);
        lc.grow(centroid2(prims_[i++]));
        rc.grow(centroid2(prims_[--j]));
    }
    return i;
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
    std::nth_element(prims_.begin() + task.begin, prims_.begin() + mid, prims_.begin() + task.end,
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

void Builder::append(const Builder& sub) {
    const std::uint32_t offset = std::uint32_t(nodes_.size());
    for (gpu::BvhNode node : sub.nodes_) {
        if (node.count == 0) node.leftOrFirst += offset;
        nodes_.push_back(node);
    }
    maxDepth_ = std::max(maxDepth_, sub.maxDepth_);
}

void Builder::build(const Task& task, bool parallel) {
    const std::uint32_t n = task.end - task.begin;
    const V4 cext = task.cbox.hi - task.cbox.lo;
    const bool coincide = !(cext[0] > 0.0f || cext[1] > 0.0f || cext[2] > 0.0f);
    if (n <= 1 || coincide) {
        makeLeaf(task);
        return;
    }

    Task left, right;
    left.depth = right.depth = task.depth + 1;
    left.begin = task.begin;
    right.end = task.end;
    // Splitting by object median keeps depth + ceil(log2(count)) constant,
    // so switching to it here keeps every leaf at depth < kBvhStackSize.
    if (task.depth + ceilLog2(n) >= kBvhStackSize - 1) {
        left.end = right.begin = partitionMedian(task, left, right);
    } else {
        SahSplit split = findSah(task);
        if (split.found) {
            const float area = task.box.halfArea();
            const float splitCost = traversalCost_ * area + split.cost;
            const float leafCost = area * float(n);
            if (n <= maxLeaf_ && !(splitCost < leafCost)) {
                makeLeaf(task);
                return;
            }
            left.box = split.left;
            right.box = split.right;
            left.end = right.begin = partitionSah(task, split, left.cbox, right.cbox);
        } else if (n <= maxLeaf_) {
            makeLeaf(task);
            return;
        } else {
            left.end = right.begin = partitionMedian(task, left, right);
        }
    }

    const std::uint32_t index = std::uint32_t(nodes_.size());
    gpu::BvhNode node;
    node.bmin = toVec3(task.box.lo);
    node.bmax = toVec3(task.box.hi);
    node.leftOrFirst = 0;
    node.count = 0;
    nodes_.push_back(node);

    if (parallel && n >= kParallelMinPrims) {
        // Both subtrees build into their own node arrays and are appended in
        // order, so the output equals the single-threaded one.
        Builder subLeft(prims_, bins_, maxLeaf_, traversalCost_);
        Builder subRight(prims_, bins_, maxLeaf_, traversalCost_);
        std::exception_ptr error;
        std::thread worker;
        try {
            worker = std::thread([&] {
                try {
                    subLeft.build(left, false);
                } catch (...) {
                    error = std::current_exception();
                }
            });
        } catch (const std::system_error&) {
            subLeft.build(left, false);  // no thread available
        }
        try {
            subRight.build(right, false);
        } catch (...) {
            if (worker.joinable()) worker.join();
            throw;
        }
        if (worker.joinable()) worker.join();
        if (error) std::rethrow_exception(error);
        append(subLeft);
        nodes_[index].leftOrFirst = std::uint32_t(nodes_.size());
        append(subRight);
        return;
    }
    build(left, false);
    nodes_[index].leftOrFirst = std::uint32_t(nodes_.size());
    build(right, false);
}

}  // namespace

Bvh buildBvh(const std::vector<glm::vec3>& v0, const std::vector<glm::vec3>& v1,
             const std::vector<glm::vec3>& v2, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    if (v0.size() != v1.size() || v0.size() != v2.size()) {
        throw std::invalid_argument("buildBvh: vertex arrays differ in length");
    }
    if (v0.size() >= std::size_t(gpu::kNoHit)) {
        throw std::invalid_argument("buildBvh: too many triangles");
    }
    const std::uint32_t n = std::uint32_t(v0.size());

    Bvh bvh;
    if (n == 0) {
        gpu::BvhNode empty;
        empty.bmin = glm::vec3(kInf);
        empty.bmax = glm::vec3(-kInf);
        empty.leftOrFirst = 0;
        empty.count = 0;
        bvh.nodes.push_back(empty);
    } else {
        std::vector<PrimRef> prims(n);
        Task root;
        root.end = n;
        for (std::uint32_t i = 0; i < n; ++i) {
            Box b;
            b.grow(toV4(v0[i]));
            b.grow(toV4(v1[i]));
            b.grow(toV4(v2[i]));
            root.box.grow(b);
            b.lo[3] = std::bit_cast<float>(i);
            b.hi[3] = 0.0f;
            prims[i] = PrimRef{b.lo, b.hi};
            root.cbox.grow(centroid2(prims[i]));
        }
        Builder builder(prims, std::clamp(options.bins, kMinBins, kMaxBins),
                        std::uint32_t(std::max(options.maxLeafSize, 1)), options.traversalCost);
        builder.build(root, std::thread::hardware_concurrency() > 1);

        bvh.nodes = std::move(builder.nodes_);
        bvh.triIndices.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) bvh.triIndices[i] = prims[i].id();
        // SAH cost in node order, so it does not depend on the thread split.
        double sum = 0.0;
        for (const gpu::BvhNode& node : bvh.nodes) {
            const double area = halfAreaD(node.bmin, node.bmax);
            sum += area * (node.count > 0 ? double(node.count) : double(options.traversalCost));
            bvh.stats.leaves += node.count > 0 ? 1u : 0u;
        }
        bvh.stats.maxDepth = builder.maxDepth_;
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
