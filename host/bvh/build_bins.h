// The binned-SAH builder's primitives (host/bvh/build.cpp): four-lane boxes,
// the per-triangle references partitioned in place, bins and the sweep's
// best split. Internal to the builder; build.cpp is its only includer.
#pragma once
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

namespace strata::bvhbuild {

constexpr int kMinBins = 2;
constexpr int kMaxBins = 256;
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

inline double halfAreaD(const glm::vec3& lo, const glm::vec3& hi) {
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

// A bin's box, with its triangle count in lane 3 of `box.hi` as integer bits
// (a non-negative float's bits, denormal or +0): the max against the +0 in
// lane 3 of every PrimRef's hi keeps it, as +0 is never greater, also with
// denormals flushed. Empty: an empty box, count 0.
struct Bin {
    Box box = {{kInf, kInf, kInf, kInf}, {-kInf, -kInf, -kInf, 0.0f}};
    std::uint32_t count() const { return std::bit_cast<std::uint32_t>(box.hi[3]); }
    void add(const PrimRef& p) {
        constexpr V4i kOne = {0, 0, 0, 1};
        box.lo = vmin(box.lo, p.lo);
        box.hi = V4(V4i(vmax(box.hi, p.hi)) + kOne);
    }
    void merge(const Bin& b) {
        const std::uint32_t n = count() + b.count();
        box.grow(b.box);
        box.hi[3] = std::bit_cast<float>(n);
    }
};

struct SahSplit {
    bool found = false;
    int axis = 0;
    int bin = 0;        // left side holds bins [0, bin]
    float cost = kInf;  // AL*NL + AR*NR (half areas)
    float scale = 0.0f; // bins per doubled-centroid unit on `axis`
    Box left, right;
};

// Takes the candidate if it is the first or strictly cheaper than the best so
// far; branch-free, as the outcome is unpredictable.
inline void takeIfCheaper(SahSplit& best, float cost, int axis, int bin) {
    const bool take = (cost < best.cost) | !best.found;
    best.cost = take ? cost : best.cost;
    best.axis = take ? axis : best.axis;
    best.bin = take ? bin : best.bin;
    best.found = true;
}

// Bins of the three axes and which of them are occupied. The sweep visits
// occupied bins only: a split next to an empty bin divides the triangles as
// the split at the previous occupied bin does, at the same cost, so the
// chosen split equals the one of a sweep over all bins.
struct BinSet {
    explicit BinSet(int bins) : bins(bins), bin(std::size_t(3 * bins)) {}
    int bins;
    std::vector<Bin> bin;  // 3 axes x bins, all empty between uses
    std::uint64_t used[3][kMaxBins / 64] = {};
    Bin* axis(int a) { return &bin[std::size_t(a * bins)]; }

    std::uint16_t occupied[3][kMaxBins] = {};  // filled by collect(), ascending
    int occupiedCount[3] = {};

    void mark(int a, int k) { used[a][k >> 6] |= std::uint64_t(1) << (k & 63); }
    // Lists the occupied bins of each axis and resets `used`.
    void collect() {
        const int words = (bins + 63) / 64;
        for (int a = 0; a < 3; ++a) {
            int m = 0;
            for (int w = 0; w < words; ++w) {
                for (std::uint64_t bits = used[a][w]; bits != 0; bits &= bits - 1) {
                    occupied[a][m++] = std::uint16_t(w * 64 + std::countr_zero(bits));
                }
                used[a][w] = 0;
            }
            occupiedCount[a] = m;
        }
    }
    // Empties the bins listed by collect().
    void clear() {
        for (int a = 0; a < 3; ++a) {
            for (int j = 0; j < occupiedCount[a]; ++j) axis(a)[occupied[a][j]] = Bin{};
        }
    }
};

}  // namespace strata::bvhbuild
