// One libFuzzer target of fuzz/entries.h, chosen by STRATA_FUZZ_TARGET
// (fuzz/CMakeLists.txt builds one executable for each). The glTF targets
// resolve uris against STRATA_FUZZ_ROOT (scripts/fuzz.sh makes it: a few
// small files for uris to find), and refuse paths outside it.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "entries.h"

namespace {
std::string root;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // Without STRATA_FUZZ_ROOT, an empty folder of its own.
    std::string dir = std::getenv("STRATA_FUZZ_ROOT") ? std::getenv("STRATA_FUZZ_ROOT") : "";
    if (dir.empty()) {
        std::string name = (std::filesystem::temp_directory_path() / "strata-fuzz-XXXXXX").string();
        if (mkdtemp(name.data()) == nullptr) std::abort();
        dir = name;
    }
    root = std::filesystem::canonical(dir).string();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
#if STRATA_FUZZ_TARGET == 1
    strata::fuzz::gltfInput(data, size, root);
#elif STRATA_FUZZ_TARGET == 2
    strata::fuzz::stateInput(data, size);
#elif STRATA_FUZZ_TARGET == 3
    strata::fuzz::cliInput(data, size);
#elif STRATA_FUZZ_TARGET == 4
    strata::fuzz::imageInput(data, size, root);
#else
#error "STRATA_FUZZ_TARGET: 1 gltf, 2 state, 3 cli, 4 image"
#endif
    return 0;
}
