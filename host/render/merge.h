// `strata merge`: shard states (render/state.h) summed into one image or
// state. Fixed-point sums add exactly, so shards rendered on one device
// merge to the bits a single render would have made.
#pragma once
#include <string>
#include <vector>

namespace strata {

struct MergeCommand {
    std::vector<std::string> inputs;   // .state files, in any order
    std::vector<std::string> outputs;  // .exr, .png
    std::vector<std::string> states;   // .state
    bool variance = false;             // EXR outputs get variance.R/G/B (states with AOVs get the AOV layers)
    bool quiet = false;
    bool dryRun = false;
};

// Throws strata::Error (one line naming the file) for unreadable,
// mismatched, overlapping or missing ranges; writes nothing then.
// `cmd` as the command line parsed and checked it (cli/checks.h): what
// the flags alone decide is not checked again.
int runMerge(const MergeCommand& cmd);

}  // namespace strata
