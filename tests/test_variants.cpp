// KHR_materials_variants: --variant NAME gives each mapped primitive its
// variant's material (render, reference, converge and bench load through
// LoadOptions::variant), an unknown name is one error line listing the
// variants, and --stats / --stats-json list them. Data:
// tests/data/geometry/variants.gltf (tests/data/make_geometry.py).
#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "gltf_util.h"
#include "scene/scene.h"

TEST_SUITE_BEGIN("unit");

namespace {

using namespace strata;
using namespace strata::test;

const std::string kFile = dataPath("geometry/variants.gltf");

// The materials of triangles A and B when loading with `variant`.
std::pair<std::uint32_t, std::uint32_t> materialsFor(const std::string& variant) {
    LoadOptions options{false, false};
    options.variant = variant;
    const Scene scene = loadGltf(kFile, options);
    REQUIRE(scene.triangles.size() == 2);
    CHECK(scene.variant == variant);
    return {scene.triangles[0].material, scene.triangles[1].material};
}

}  // namespace

TEST_CASE("variants: each primitive gets its mapping's material for the chosen variant, its own otherwise") {
    // Materials 1 Red, 2 Green, 3 Blue; A is Red (Christmas: Green, Ocean:
    // Blue), B is Green (Christmas and Ocean: Red); Plain maps nothing.
    const Scene scene = loadGltf(kFile, LoadOptions{false, false});
    CHECK(scene.variants == std::vector<std::string>{"Christmas", "Ocean", "Plain"});
    using Pair = std::pair<std::uint32_t, std::uint32_t>;
    CHECK(materialsFor("") == Pair{1, 2});
    CHECK(materialsFor("Christmas") == Pair{2, 1});
    CHECK(materialsFor("Ocean") == Pair{3, 1});
    CHECK(materialsFor("Plain") == Pair{1, 2});
}

TEST_CASE("variants: an unknown --variant is one error line listing the file's variants, exit 2, no output") {
    const std::string expected = kFile + ": error: --variant \"Nope\" is not a variant of the file; its variants: "
                                         "\"Christmas\", \"Ocean\", \"Plain\"";
    CHECK(loadError(kFile) == "");
    for (const char* command : {"render", "reference"}) {
        CAPTURE(command);
        expectError(std::string(command) + " " + kFile + " --variant Nope", expected);
    }
    const Run bench = run("bench " + kFile + " --variant Nope --quick");
    CAPTURE(bench.output);
    CHECK(bench.status == 2);
    CHECK(lines(bench.output) == 1);
    CHECK(bench.output.rfind(expected, 0) == 0);
    // A file without the extension has none to choose.
    const std::string plain = dataPath("geometry/strip.gltf");
    expectError("render " + plain + " --variant Nope",
                plain + ": error: --variant \"Nope\" is not a variant of the file; it has none (no "
                        "KHR_materials_variants)");
}

TEST_CASE("variants: --stats and --stats-json list the file's variants and the one rendered" *
          doctest::test_suite("render")) {
    TempDir out;
    const Run r = run("render " + kFile + " --variant Ocean --stats --stats-json " + out / "s.json" + " -o " +
                      out / "a.exr" + " --spp 1 --width 8 --height 8 --quiet");
    CAPTURE(r.output);
    CHECK(r.status == 0);
    CHECK(r.output.find("variants   Christmas, Ocean, Plain (rendering Ocean)\n") != std::string::npos);
    std::ifstream in(out / "s.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    CHECK(j["scene"]["variants"] == nlohmann::json({"Christmas", "Ocean", "Plain"}));
    CHECK(j["scene"]["variant"] == "Ocean");
}

TEST_SUITE_END();
