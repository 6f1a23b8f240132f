// The layering of host/: docs/architecture.md lists its folders lowest first
// ("Dependencies point down the flow"); a file includes headers of its own
// folder and of folders below it, never above. The order is read from the
// page itself, so the page and this check cannot disagree.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.h"

namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// The numbered list after the marker line, lowest layer first: "1. `util`",
// each name in backquotes, anything after it a comment. Empty without the
// marker.
std::vector<std::string> documentedLayers(const std::string& markdown) {
    const std::string marker = "<!-- host layers, lowest first";
    std::vector<std::string> layers;
    const std::size_t at = markdown.find(marker);
    if (at == std::string::npos) return layers;
    std::istringstream in(markdown.substr(markdown.find('\n', at) + 1));
    static const std::regex item(R"(^\s*\d+\.\s+`([^`]+)`.*$)");
    std::string line;
    std::smatch m;
    while (std::getline(in, line) && std::regex_match(line, m, item)) layers.push_back(m[1]);
    return layers;
}

// The layer of a file under `host`: its first folder, or its own name for a
// file directly in host/ (main.cpp).
std::string layerOf(const fs::path& relative) {
    return relative.has_parent_path() ? relative.begin()->string() : relative.filename().string();
}

// Every `#include "folder/..."` of a C++ file under `host` whose folder is a
// layer above the including file's, and every file or included folder of
// host/ that the order does not name: one line each, naming the file, the
// line and both folders. Includes of anything else ("../../shaders/...",
// generated headers with no folder) are not the order's business.
std::vector<std::string> layeringProblems(const fs::path& host, const std::vector<std::string>& layers) {
    std::vector<std::string> problems;
    const auto rank = [&](const std::string& layer) {
        return std::find(layers.begin(), layers.end(), layer) - layers.begin();
    };
    const auto listed = [&](const std::string& layer) { return rank(layer) < std::ptrdiff_t(layers.size()); };
    std::set<std::string> folders;
    for (const auto& e : fs::directory_iterator(host))
        if (e.is_directory()) folders.insert(e.path().filename().string());
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(host)) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".h" || ext == ".cpp" || ext == ".hpp")) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    static const std::regex include(R"re(^\s*#\s*include\s*"(([^"/]+)/[^"]*)".*$)re");
    for (const fs::path& file : files) {
        const fs::path relative = fs::relative(file, host);
        const std::string name = "host/" + relative.generic_string();
        const std::string from = layerOf(relative);
        if (!listed(from)) {
            problems.push_back(name + ": its layer '" + from + "' is not in the documented order");
            continue;
        }
        std::istringstream in(readText(file));
        std::string line;
        std::smatch m;
        for (int number = 1; std::getline(in, line); ++number) {
            if (!std::regex_match(line, m, include)) continue;
            const std::string path = m[1], to = m[2];
            if (to == from || !folders.count(to)) continue;
            const std::string where = name + ":" + std::to_string(number) + ": ";
            if (!listed(to))
                problems.push_back(where + from + "/ includes " + to + "/, which is not in the documented order");
            else if (rank(to) > rank(from))
                problems.push_back(where + from + "/ includes " + to + "/ (\"" + path + "\"), a layer above it: " +
                                   from + " is layer " + std::to_string(rank(from) + 1) + ", " + to + " layer " +
                                   std::to_string(rank(to) + 1) + " in docs/architecture.md's order");
        }
    }
    return problems;
}

void write(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

}  // namespace

TEST_SUITE_BEGIN("unit");

TEST_CASE("layering: every #include under host/ points down the layer order of docs/architecture.md") {
    const fs::path root = STRATA_SOURCE_DIR;
    const std::vector<std::string> layers = documentedLayers(readText(root / "docs/architecture.md"));
    REQUIRE_MESSAGE(layers.size() > 10, "docs/architecture.md should hold the numbered list of host/'s layers");
    // Each layer once, and every folder of host/ (and main.cpp) in the list.
    CHECK(std::set<std::string>(layers.begin(), layers.end()).size() == layers.size());
    for (const auto& e : fs::directory_iterator(root / "host")) {
        const std::string name = e.path().filename().string();
        if (e.is_directory() || name == "main.cpp")
            CHECK_MESSAGE(std::find(layers.begin(), layers.end(), name) != layers.end(),
                          "host/" << name << " is not in docs/architecture.md's layer order");
    }
    for (const std::string& problem : layeringProblems(root / "host", layers)) FAIL_CHECK(problem);
}

TEST_CASE("layering: a backwards include is reported with its file, its line and both folders") {
    strata::test::TempDir dir;
    const fs::path host = dir.path / "host";
    write(host / "low/a.h", "#pragma once\n// #include \"high/b.h\" in a comment is no include\n"
                            "#include \"low/c.h\"\n#include \"../../shaders/shared/types.h\"\n"
                            "  #  include \"high/b.h\"  // the backwards one\n");
    write(host / "low/c.h", "#pragma once\n");
    write(host / "high/b.h", "#pragma once\n#include \"low/a.h\"\n");
    write(host / "main.cpp", "#include \"high/b.h\"\n");
    write(host / "odd/d.h", "#pragma once\n");
    const std::string doc = "Layers:\n\n<!-- host layers, lowest first -->\n1. `low` the bottom\n2. `high`\n"
                            "3. `main.cpp`\n\nMore text.\n4. `not-a-layer`\n";
    const std::vector<std::string> layers = documentedLayers(doc);
    REQUIRE(layers == std::vector<std::string>{"low", "high", "main.cpp"});
    const std::vector<std::string> problems = layeringProblems(host, layers);
    REQUIRE(problems.size() == 2);
    CHECK(problems[0].find("host/low/a.h:5: low/ includes high/") == 0);
    CHECK(problems[0].find("(\"high/b.h\"), a layer above it: low is layer 1, high layer 2") != std::string::npos);
    CHECK(problems[1].find("host/odd/d.h: its layer 'odd' is not in the documented order") == 0);
    // Downwards, the same order holds no problem.
    write(host / "low/a.h", "#pragma once\n");
    fs::remove_all(host / "odd");
    CHECK(layeringProblems(host, layers).empty());
}

TEST_SUITE_END();
