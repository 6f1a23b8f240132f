#include "pack/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/glm.hpp>

namespace strata {

bool useLightTree(LightSampler sampler, std::size_t clusters) {
    if (clusters == 0) return false;
    if (sampler == LightSampler::Tree) return true;
    return sampler == LightSampler::Auto && clusters >= kLightTreeMinClusters;
}

std::size_t lightClusters(const LightTree& tree, double size) {
    if (tree.nodes.empty()) return 0;
    const double limit = size * double(tree.nodes[0].radius);
    std::size_t clusters = 0;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const gpu::LightNode& n = tree.nodes[stack.back()];
        const std::uint32_t i = stack.back();
        stack.pop_back();
        if ((n.link & gpu::kLightNodeLeaf) != 0u || double(n.radius) <= limit) {
            ++clusters;
            continue;
        }
        stack.push_back(i + 1);
        stack.push_back(n.link & gpu::kLightNodeIndex);
    }
    return clusters;
}

namespace {

constexpr double kPi = std::numbers::pi;

// A cone of directions: every direction within theta of `axis`
// (cosTheta -1: all of them).
struct Cone {
    glm::dvec3 axis{0.0, 0.0, 1.0};
    double cosTheta = 1.0;
};

double angleOf(double cosTheta) { return std::acos(std::clamp(cosTheta, -1.0, 1.0)); }

// The smallest cone (of this construction) holding both.
Cone unite(const Cone& a, const Cone& b) {
    if (a.cosTheta <= -1.0 || b.cosTheta <= -1.0) return {a.axis, -1.0};
    const double ta = angleOf(a.cosTheta), tb = angleOf(b.cosTheta);
    const double td = angleOf(glm::dot(a.axis, b.axis));
    if (std::min(td + tb, kPi) <= ta) return a;
    if (std::min(td + ta, kPi) <= tb) return b;
    const double to = 0.5 * (ta + td + tb);
    if (to >= kPi) return {a.axis, -1.0};
    // Turn a's axis towards b's by to - ta.
    const double turn = to - ta;
    const glm::dvec3 perp = b.axis - glm::dot(a.axis, b.axis) * a.axis;
    const double len = glm::length(perp);
    if (!(len > 1e-12)) return {a.axis, -1.0};  // opposite axes
    const glm::dvec3 axis = std::cos(turn) * a.axis + std::sin(turn) * (perp / len);
    // A little slack against rounding: the cone must hold both.
    return {glm::normalize(axis), std::cos(std::min(to + 1e-6, kPi))};
}

struct Bounds {
    glm::dvec3 lo{std::numeric_limits<double>::max()};
    glm::dvec3 hi{-std::numeric_limits<double>::max()};
    double power = 0.0;
    Cone cone;
    double cosThetaE = 1.0;  // emission spread beyond the cone
    bool twoSided = false;
    bool empty = true;

    void add(const Bounds& o) {
        if (o.empty) return;
        if (empty) {
            *this = o;
            return;
        }
        lo = glm::min(lo, o.lo);
        hi = glm::max(hi, o.hi);
        power += o.power;
        cone = unite(cone, o.cone);
        cosThetaE = std::min(cosThetaE, o.cosThetaE);
        twoSided = twoSided || o.twoSided;
    }
    glm::dvec3 centroid() const { return 0.5 * (lo + hi); }
    double area() const {
        const glm::dvec3 d = hi - lo;
        return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
};

// What a light bounds: its points, power and orientation.
Bounds lightBounds(const gpu::Emitter& e, double power) {
    Bounds b;
    b.empty = false;
    b.power = power;
    const glm::dvec3 v0(e.v0);
    if (e.kind == gpu::kLightTriangle) {
        const glm::dvec3 v1 = v0 + glm::dvec3(e.e1), v2 = v0 + glm::dvec3(e.e2);
        b.lo = glm::min(v0, glm::min(v1, v2));
        b.hi = glm::max(v0, glm::max(v1, v2));
        const glm::dvec3 n = glm::cross(glm::dvec3(e.e1), glm::dvec3(e.e2));
        const double len = glm::length(n);
        b.cone = len > 0.0 ? Cone{n / len, 1.0} : Cone{{0.0, 0.0, 1.0}, -1.0};
        b.cosThetaE = 0.0;  // a surface emits over its hemisphere
        b.twoSided = (e.flags & gpu::kMaterialDoubleSided) != 0u;
        return b;
    }
    b.lo = b.hi = v0;
    if (e.kind == gpu::kLightSpot) {
        // e2 = (scale, offset) of the falloff clamp(cos * scale + offset, 0, 1)^2:
        // 0 from the outer cone's cosine out, 1 inside cos = cosOuter + 1 / scale.
        const double scale = e.e2.x, cosOuter = -double(e.e2.y) / scale;
        const double cosInner = std::min(1.0, cosOuter + 1.0 / scale);
        b.cone = {glm::normalize(glm::dvec3(e.e1)), cosInner};
        b.cosThetaE = std::cos(std::max(0.0, angleOf(cosOuter) - angleOf(cosInner)));
        return b;
    }
    b.cone = {{0.0, 0.0, 1.0}, -1.0};  // a point light: every direction
    b.cosThetaE = 0.0;
    return b;
}

// Solid-angle measure of the orientation bounds (Conty Estevez & Kulla,
// eq. 1): the cone, and the band theta_e beyond it weighted by the cosine.
double orientationMeasure(const Bounds& b) {
    const double to = angleOf(b.cone.cosTheta), te = angleOf(b.cosThetaE);
    const double tw = std::min(to + te, kPi);
    const double so = std::sin(to), co = std::cos(to);
    return 2.0 * kPi * (1.0 - co) +
           0.5 * kPi * (2.0 * tw * so - std::cos(to - 2.0 * tw) - 2.0 * to * so + co);
}

double splitCost(const Bounds& b, double regulariser) {
    if (b.empty) return 0.0;
    return b.power * orientationMeasure(b) * b.area() * regulariser;
}

struct Item {
    std::uint32_t emitter;
    Bounds bounds;
};

struct Builder {
    std::vector<gpu::Emitter>& emitters;
    std::vector<gpu::LightNode> nodes;
    std::uint32_t depth = 0;

    // The node of these bounds, linked to `link` (kLightNodeIndex bits).
    static gpu::LightNode node(const Bounds& b, std::uint32_t link) {
        gpu::LightNode n{};
        const glm::dvec3 half = 0.5 * (b.hi - b.lo);
        n.centre = glm::vec3(b.centroid());
        // Rounded up, with the centre's rounding: the sphere holds the box.
        const double r = std::sqrt(glm::dot(half, half)) + glm::length(glm::dvec3(n.centre) - b.centroid());
        n.radius = static_cast<float>(r * (1.0 + 1e-6));
        n.axis = glm::vec3(b.cone.axis);
        n.power = static_cast<float>(b.power);
        // Widened by 1e-3 radians: a float cosine near 1 holds the angle to
        // 3e-4 only, and a light must never be bounded out by rounding.
        const double thetaO = b.cone.cosTheta <= -1.0 ? kPi : std::min(kPi, angleOf(b.cone.cosTheta) + 1e-3);
        n.cosTheta_o = static_cast<float>(std::cos(thetaO));
        n.sinTheta_o = static_cast<float>(std::sin(thetaO));
        n.cosTheta_e = static_cast<float>(b.cosThetaE);
        n.link = link | (b.twoSided ? gpu::kLightNodeTwoSided : 0u);
        return n;
    }

    static constexpr int kBuckets = 12;

    // The bucket of an item's centroid along `dim` (0 for what is not a
    // number: lights at the float range's end).
    static int bucket(const Item& it, int dim, double lo, double extent) {
        const double t = (it.bounds.centroid()[dim] - lo) / extent * kBuckets;
        return t >= 1.0 ? std::min(kBuckets - 1, static_cast<int>(std::min(t, double(kBuckets)))) : 0;
    }

    // The split of [first, last) into [first, mid) and [mid, last).
    static std::size_t split(std::vector<Item>& items, std::size_t first, std::size_t last) {
        Bounds centroids;
        for (std::size_t i = first; i < last; ++i) {
            const glm::dvec3 c = items[i].bounds.centroid();
            centroids.lo = glm::min(centroids.lo, c);
            centroids.hi = glm::max(centroids.hi, c);
        }
        const glm::dvec3 extent = centroids.hi - centroids.lo;
        const double longest = std::max(extent.x, std::max(extent.y, extent.z));
        double best = std::numeric_limits<double>::infinity();
        int bestDim = -1, bestBucket = 0;
        for (int dim = 0; dim < 3; ++dim) {
            if (!(extent[dim] > 0.0)) continue;
            auto bucketOf = [&](const Item& it) { return bucket(it, dim, centroids.lo[dim], extent[dim]); };
            std::array<Bounds, kBuckets> buckets;
            for (std::size_t i = first; i < last; ++i) buckets[static_cast<std::size_t>(bucketOf(items[i]))].add(items[i].bounds);
            const double regulariser = longest / extent[dim];
            for (int s = 1; s < kBuckets; ++s) {
                Bounds below, above;
                for (int k = 0; k < s; ++k) below.add(buckets[static_cast<std::size_t>(k)]);
                for (int k = s; k < kBuckets; ++k) above.add(buckets[static_cast<std::size_t>(k)]);
                if (below.empty || above.empty) continue;
                const double cost = splitCost(below, regulariser) + splitCost(above, regulariser);
                if (cost < best) best = cost, bestDim = dim, bestBucket = s;
            }
        }
        if (bestDim < 0) return first + (last - first) / 2;  // every centroid at one point
        const int dim = bestDim;
        auto it = std::partition(items.begin() + static_cast<std::ptrdiff_t>(first),
                                 items.begin() + static_cast<std::ptrdiff_t>(last), [&](const Item& item) {
                                     return bucket(item, dim, centroids.lo[dim], extent[dim]) < bestBucket;
                                 });
        return static_cast<std::size_t>(it - items.begin());
    }

    // Builds the subtree of [first, last) at `level` on the path `trail`;
    // returns its bounds.
    Bounds build(std::vector<Item>& items, std::size_t first, std::size_t last, std::uint32_t level, std::uint32_t trail) {
        const std::size_t index = nodes.size();
        nodes.emplace_back();
        depth = std::max(depth, level);
        if (last - first == 1) {
            const Item& it = items[first];
            nodes[index] = node(it.bounds, it.emitter | gpu::kLightNodeLeaf);
            emitters[it.emitter].trail = trail;
            return it.bounds;
        }
        Bounds all;
        for (std::size_t i = first; i < last; ++i) all.add(items[i].bounds);
        std::size_t mid = split(items, first, last);
        // Below `level` each child may hold at most 2^(max depth - level - 1)
        // lights, so that every leaf's trail fits: halve by count otherwise.
        const std::uint32_t room = kLightTreeMaxDepth - level - 1;
        const std::size_t cap = room >= 63 ? std::numeric_limits<std::size_t>::max() : std::size_t(1) << room;
        if (mid - first > cap || last - mid > cap || mid == first || mid == last) {
            mid = first + (last - first) / 2;
            std::nth_element(items.begin() + static_cast<std::ptrdiff_t>(first),
                             items.begin() + static_cast<std::ptrdiff_t>(mid),
                             items.begin() + static_cast<std::ptrdiff_t>(last), [](const Item& a, const Item& b) {
                                 // A strict weak order even for centroids that are not numbers.
                                 auto key = [](const Item& it) {
                                     glm::dvec3 c = it.bounds.centroid();
                                     for (int k = 0; k < 3; ++k)
                                         if (std::isnan(c[k])) c[k] = std::numeric_limits<double>::infinity();
                                     return std::array<double, 3>{c.x, c.y, c.z};
                                 };
                                 return key(a) < key(b);
                             });
        }
        build(items, first, mid, level + 1, trail);
        const auto second = static_cast<std::uint32_t>(nodes.size());
        build(items, mid, last, level + 1, trail | (1u << level));
        nodes[index] = node(all, second);
        return all;
    }
};

}  // namespace

LightTree buildLightTree(std::vector<gpu::Emitter>& emitters, const std::vector<double>& weights,
                         const std::vector<SweptLight>& swept) {
    if (weights.size() != emitters.size()) throw std::invalid_argument("buildLightTree: one weight per emitter");
    std::vector<Item> items;
    std::vector<std::size_t> itemOf(emitters.size(), SIZE_MAX);
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        if (isInfiniteLight(emitters[i])) continue;
        itemOf[i] = items.size();
        items.push_back({static_cast<std::uint32_t>(i), lightBounds(emitters[i], weights[i])});
    }
    for (const SweptLight& s : swept) {
        if (s.emitter >= emitters.size() || itemOf[s.emitter] == SIZE_MAX)
            throw std::invalid_argument("buildLightTree: a swept light that is not a bounded emitter");
        Bounds& b = items[itemOf[s.emitter]].bounds;
        b.lo = glm::min(b.lo, s.lo);
        b.hi = glm::max(b.hi, s.hi);
        if (s.turns) b.cone.cosTheta = -1.0;
    }
    if (items.empty()) throw std::invalid_argument("buildLightTree: no bounded light");
    // 2n - 1 nodes, each index within kLightNodeIndex.
    if (items.size() > gpu::kLightNodeIndex / 2 || emitters.size() > gpu::kLightNodeIndex)
        throw std::invalid_argument("buildLightTree: more lights than a node's link addresses");
    Builder b{emitters, {}, 0};
    b.nodes.reserve(2 * items.size() - 1);
    b.build(items, 0, items.size(), 0, 0u);
    return {std::move(b.nodes), b.depth};
}

}  // namespace strata
