// Memory for the BVH builder: large uninitialised arrays on huge pages and
// the node arena that subtree tasks share.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "../../shaders/shared/types.h"
#include "util/memory.h"  // adviseHugePages

namespace strata {

// Uninitialised storage for `count` elements of a trivial type, huge pages
// advised.
template <class T>
std::unique_ptr<T[]> allocateLarge(std::size_t count) {
    static_assert(std::is_trivially_default_constructible_v<T>);
    std::unique_ptr<T[]> p(new T[count]);
    adviseHugePages(p.get(), count * sizeof(T));
    return p;
}

// Node storage shared by all subtree tasks: a task with m triangles takes a
// range of 2m - 1 nodes (its bound: every leaf holds a triangle). Where a
// range lies depends on thread timing; only the copy into depth-first order
// places nodes in the output.
struct NodeArena {
    explicit NodeArena(std::size_t capacity)
        : nodes(allocateLarge<gpu::BvhNode>(capacity)), capacity(capacity) {}
    gpu::BvhNode* take(std::size_t count) {
        const std::size_t at = next.fetch_add(count);
        if (at + count > capacity) throw std::logic_error("buildBvh: node arena overflow");
        return nodes.get() + at;
    }
    std::unique_ptr<gpu::BvhNode[]> nodes;
    std::size_t capacity;
    std::atomic<std::size_t> next{0};
};

// Appends nodes to a range taken from the arena.
struct NodeList {
    gpu::BvhNode* data = nullptr;
    std::uint32_t size = 0;
    void push_back(const gpu::BvhNode& node) { data[size++] = node; }
    gpu::BvhNode& operator[](std::size_t i) { return data[i]; }
};

}  // namespace strata
