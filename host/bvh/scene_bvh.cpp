#include "bvh/scene_bvh.h"

#include <algorithm>

namespace strata {

SceneBvh buildSceneBvh(const Scene& scene, const BvhBuildOptions& options) {
    const std::size_t n = scene.triangles.size();
    TriangleVertices view;
    if (n > 0)
        for (int k = 0; k < 3; ++k) view.base[k] = reinterpret_cast<const std::byte*>(&scene.triangles[0].v[k]);
    view.stride = sizeof(Triangle);
    view.count = n;
    SceneBvh out;
    out.binary = buildBvh(view, options);
    out.wide = collapseBvh4(out.binary.nodes, unsigned(std::max(options.threads, 0)));
    return out;
}

}  // namespace strata
