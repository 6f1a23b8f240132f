// SAH cost and build time of Embree's binned-SAH BVH builder (rtcBuildBVH at
// RTC_BUILD_QUALITY_MEDIUM) over a glTF scene's triangles, built as a binary
// BVH with strata's leaf cap and costs (at most 8 triangles a leaf, traversal
// and intersection cost 1), so that its SAH cost compares with the one
// `strata bench` reports for strata's BVH2 ("BVH: ... SAH cost C"). The
// cost is strata's definition (host/bvh/build.cpp, sahTerm): the sum over
// interior nodes of half-area x 1 and over leaves of half-area x triangles,
// divided by the root's half-area.
//
// Scene loading is the peer tool's (../shared/peers/embree-rays/scene.h),
// so both Embree programs see the same triangles. Build with build.sh.
//
//   embree-sah SCENE.gltf|.glb [--threads T] [--reps R] [--leaf N]
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "scene.h"

namespace {

struct Box {
    float lo[3], hi[3];
};

// A node of the BVH Embree builds through the callbacks: a leaf holds its
// triangle count, an interior node its two children and their boxes.
struct Node {
    bool leaf;
    unsigned count;
    Node* child[2];
    Box box[2];
};

double halfArea(const Box& b) {
    const double x = double(b.hi[0]) - b.lo[0], y = double(b.hi[1]) - b.lo[1], z = double(b.hi[2]) - b.lo[2];
    return x * y + y * z + z * x;
}

void* createNode(RTCThreadLocalAllocator alloc, unsigned int childCount, void*) {
    if (childCount != 2) std::abort();  // maxBranchingFactor is 2
    Node* n = static_cast<Node*>(rtcThreadLocalAlloc(alloc, sizeof(Node), 16));
    n->leaf = false;
    n->count = 0;
    return n;
}

void setNodeChildren(void* node, void** children, unsigned int childCount, void*) {
    for (unsigned i = 0; i < childCount; ++i) static_cast<Node*>(node)->child[i] = static_cast<Node*>(children[i]);
}

void setNodeBounds(void* node, const RTCBounds** bounds, unsigned int childCount, void*) {
    for (unsigned i = 0; i < childCount; ++i) {
        Box& b = static_cast<Node*>(node)->box[i];
        b = {{bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z},
             {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z}};
    }
}

void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive*, size_t count, void*) {
    Node* n = static_cast<Node*>(rtcThreadLocalAlloc(alloc, sizeof(Node), 16));
    n->leaf = true;
    n->count = unsigned(count);
    return n;
}

struct Walk {
    double sum = 0.0;
    unsigned nodes = 0, leaves = 0, depth = 0;
};

void walk(const Node* n, const Box& box, unsigned depth, Walk& w) {
    ++w.nodes;
    w.depth = std::max(w.depth, depth);
    if (n->leaf) {
        ++w.leaves;
        w.sum += halfArea(box) * double(n->count);
        return;
    }
    w.sum += halfArea(box);
    for (int i = 0; i < 2; ++i) walk(n->child[i], n->box[i], depth + 1, w);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: embree-sah SCENE.gltf|.glb [--threads T] [--reps R] [--leaf N]\n");
        return 2;
    }
    const std::string path = argv[1];
    int threads = 2, reps = 5, leaf = 8;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) {
            std::fprintf(stderr, "embree-sah: error: %s needs a value\n", a.c_str());
            return 2;
        }
        const int v = std::atoi(argv[++i]);
        if (v < 1) {
            std::fprintf(stderr, "embree-sah: error: bad value for %s\n", a.c_str());
            return 2;
        }
        if (a == "--threads") threads = v;
        else if (a == "--reps") reps = v;
        else if (a == "--leaf") leaf = v;
        else {
            std::fprintf(stderr, "embree-sah: error: unknown option '%s'\n", a.c_str());
            return 2;
        }
    }
    GltfScene scene;
    std::string err;
    if (!loadGltf(path, scene, err)) {
        std::fprintf(stderr, "%s: error: %s\n", path.c_str(), err.c_str());
        return 1;
    }
    const Mesh& m = scene.mesh;
    const size_t n = m.idx.size() / 3;
    if (n == 0) {
        std::fprintf(stderr, "%s: error: no triangles\n", path.c_str());
        return 1;
    }
    std::vector<RTCBuildPrimitive> prims(n);
    Box root{{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
              std::numeric_limits<float>::infinity()},
             {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
              -std::numeric_limits<float>::infinity()}};
    for (size_t i = 0; i < n; ++i) {
        V3 lo = m.v[m.idx[3 * i]], hi = lo;
        for (int k = 1; k < 3; ++k) {
            lo = vmin(lo, m.v[m.idx[3 * i + k]]);
            hi = vmax(hi, m.v[m.idx[3 * i + k]]);
        }
        prims[i] = {lo.x, lo.y, lo.z, 0u, hi.x, hi.y, hi.z, unsigned(i)};
        const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
        for (int k = 0; k < 3; ++k) root.lo[k] = std::min(root.lo[k], l[k]), root.hi[k] = std::max(root.hi[k], h[k]);
    }

    char cfg[32];
    std::snprintf(cfg, sizeof cfg, "threads=%d", threads);
    RTCDevice dev = rtcNewDevice(cfg);
    if (!dev) {
        std::fprintf(stderr, "embree-sah: error: rtcNewDevice failed\n");
        return 1;
    }
    std::vector<double> ms;
    Walk w;
    std::vector<RTCBuildPrimitive> work(n);
    for (int r = 0; r < reps + 1; ++r) {  // the first build is a warm-up, not timed
        RTCBVH bvh = rtcNewBVH(dev);
        work = prims;  // the builder reorders the array
        RTCBuildArguments args = rtcDefaultBuildArguments();
        args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
        args.maxBranchingFactor = 2;
        args.maxDepth = 64;
        args.sahBlockSize = 1;
        args.minLeafSize = 1;
        args.maxLeafSize = unsigned(leaf);
        args.traversalCost = 1.0f;
        args.intersectionCost = 1.0f;
        args.bvh = bvh;
        args.primitives = work.data();
        args.primitiveCount = n;
        args.primitiveArrayCapacity = n;
        args.createNode = createNode;
        args.setNodeChildren = setNodeChildren;
        args.setNodeBounds = setNodeBounds;
        args.createLeaf = createLeaf;
        const auto t0 = std::chrono::steady_clock::now();
        const Node* top = static_cast<const Node*>(rtcBuildBVH(&args));
        const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (!top) {
            std::fprintf(stderr, "embree-sah: error: rtcBuildBVH failed (%d)\n", int(rtcGetDeviceError(dev)));
            return 1;
        }
        if (r > 0) ms.push_back(t);
        w = Walk{};
        walk(top, root, 0, w);
        rtcReleaseBVH(bvh);
    }
    rtcReleaseDevice(dev);
    std::sort(ms.begin(), ms.end());
    std::printf("%s: %zu triangles; Embree binary BVH (rtcBuildBVH, MEDIUM, leaves <= %d, %d threads): "
                "SAH cost %.2f, %u nodes, %u leaves, depth %u; build %.1f ms (median of %d; %.1f-%.1f)\n",
                path.c_str(), n, leaf, threads, w.sum / halfArea(root), w.nodes, w.leaves, w.depth,
                ms[ms.size() / 2], reps, ms.front(), ms.back());
    return 0;
}
