// `strata bench`: traversal throughput of the shader BVH on the device, on
// the ray sets of the Embree peer benchmark (shared/peers/embree-rays), so
// the two can be run side by side: primary rays through pixel centres,
// one cosine-distributed diffuse bounce from each primary hit (the peer's
// PCG RXS-M-XS draws and frame), and occlusion rays from each primary hit to
// the top centre of the scene bounds.
#pragma once
#include <string>

namespace strata {

struct BenchCommand {
    std::string scene;
    int width = 1024, height = 768;   // the peer's defaults
    int reps = 5;                     // timed passes per ray set (median)
    int camera = 0;
    int device = -1;
    std::string json;
    bool validation = false;
};

int runBench(const BenchCommand& cmd);

}  // namespace strata
