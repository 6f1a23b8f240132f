// `strata shaders`: the shader feature table, and the shader cache
// (spirv/cache.h) filled ahead of renders, e.g. before a farm's jobs start
// on a shared cache folder.
#pragma once
#include <string>
#include <vector>

namespace strata {

struct ShadersCommand {
    std::vector<std::string> scenes;  // the modules a render of each may use
    bool all = false;                 // --all: every module the table allows
    std::string out;                  // --out DIR: each module also as DIR/NAME.spv
    bool quiet = false;
};

// Without scenes or --all: prints the feature table. Otherwise compiles (or
// finds in the cache) the modules and prints one line per module and a
// summary. Returns the exit status; bad input throws strata::Error.
int runShaders(const ShadersCommand& cmd);

}  // namespace strata
