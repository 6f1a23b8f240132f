// Every input the fuzzers once crashed on (tests/data/fuzz/TARGET/, named
// after what it found) goes through its target's body (fuzz/entries.h) in
// the normal build: it must be loaded or refused with strata::Error, and
// nothing else may escape. `make test-sanitize` runs these under the
// sanitizers as the fuzzers did.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "cli_util.h"
#include "entries.h"
#include "gltf_util.h"

namespace strata::test {
namespace {

std::vector<std::filesystem::path> inputs(const std::string& target) {
    std::vector<std::filesystem::path> files;
    const std::filesystem::path dir = std::filesystem::path(STRATA_SOURCE_DIR) / "tests/data/fuzz" / target;
    if (std::filesystem::is_directory(dir))
        for (const auto& e : std::filesystem::directory_iterator(dir))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::uint8_t> bytesOf(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("fuzz regressions: every input a fuzzer found is handled") {
    TempDir root;  // the folder uris resolve against: empty, as a fuzz run's may be
    std::size_t total = 0;
    for (const std::string target : {"gltf", "state", "cli", "image"}) {
        for (const auto& file : inputs(target)) {
            CAPTURE(file.string());
            const std::vector<std::uint8_t> bytes = bytesOf(file);
            CerrCapture quiet;
            if (target == "gltf") CHECK_NOTHROW(fuzz::gltfInput(bytes.data(), bytes.size(), root.path.string()));
            if (target == "state") CHECK_NOTHROW(fuzz::stateInput(bytes.data(), bytes.size()));
            if (target == "cli") CHECK_NOTHROW(fuzz::cliInput(bytes.data(), bytes.size()));
            if (target == "image") CHECK_NOTHROW(fuzz::imageInput(bytes.data(), bytes.size(), root.path.string()));
            ++total;
        }
    }
    MESSAGE(total << " regression inputs");
    CHECK(total > 0);
}

TEST_SUITE_END();

}  // namespace strata::test
