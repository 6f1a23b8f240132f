// The shader feature table (host/spirv/features.h), the run-time compiler
// and the persistent shader cache (host/spirv/cache.h): the modules the
// table allows, the choice of module for a render, spirv-val over a set of
// modules that turns every axis on and off, the compiler's words against
// glslangValidator's, the docs' copy of the table, and the cache's cold,
// warm, corrupt, foreign, unwritable and concurrent cases.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../shaders/shared/types.h"
#include "cli_util.h"
#include "spirv/cache.h"
#include "spirv/compile.h"
#include "spirv/features.h"

TEST_SUITE_BEGIN("unit");

namespace {

using namespace strata;
using namespace strata::spirv;
using strata::test::runShell;
using strata::test::TempDir;

std::string nameOf(KernelId k, const VariantInputs& in) { return variantName(chooseVariant(k, in)); }

void writeWords(const std::filesystem::path& path, const std::vector<std::uint32_t>& words) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(words.data()), std::streamsize(words.size() * 4));
}

std::vector<std::uint32_t> readWords(const std::filesystem::path& path) {
    std::ifstream f(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(f)), {});
    std::vector<std::uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), words.size() * 4);
    return words;
}

std::string readText(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("spirv: the table's modules are unique, allowed, and grow by the axes a kernel has") {
    const std::vector<Variant> all = allVariants();
    std::set<std::string> names;
    for (const Variant& v : all) {
        CHECK(allowed(v));
        CHECK(names.insert(variantName(v)).second);
    }
    // Every kernel without axes, and each of its axes alone, is a module.
    for (const KernelInfo& k : kernels()) CHECK(names.count(k.name) == 1);
    // An axis a kernel does not have, an excluded pair and a missing implied
    // axis are refused.
    const auto axis = [](const char* name) {
        for (std::size_t i = 0; i < axes().size(); ++i)
            if (std::string(axes()[i].name) == name) return 1u << i;
        FAIL("no axis " << name);
        return 0u;
    };
    CHECK_FALSE(allowed({KernelId::Trace, axis("layers")}));
    CHECK_FALSE(allowed({KernelId::Pathtrace, axis("bvh2") | axis("bvh4m")}));
    CHECK_FALSE(allowed({KernelId::Wavefront, axis("iridescence")}));
    CHECK(allowed({KernelId::Wavefront, axis("iridescence") | axis("layers")}));
    // The covering set is linear in the axes, and holds every axis on and off.
    const std::vector<Variant> cover = coveringVariants();
    CHECK(cover.size() <= kernels().size() * (axes().size() + 2));
    for (std::size_t i = 0; i < axes().size(); ++i) {
        bool on = false;
        for (const Variant& v : cover) on |= (v.axes & (1u << i)) != 0u;
        CHECK_MESSAGE(on, axes()[i].name);
    }
}

TEST_CASE("spirv: a render's module has exactly the axes its scene and settings need") {
    VariantInputs plain;  // four-wide registers, no features
    CHECK(nameOf(KernelId::Pathtrace, plain) == "pathtrace");
    CHECK(nameOf(KernelId::Trace, plain) == "trace");
    VariantInputs in = plain;
    in.wide = false;
    in.features = gpu::kFeatureSheen | gpu::kFeatureInstancing | gpu::kFeatureTextures;
    CHECK(nameOf(KernelId::Pathtrace, in) == "pathtrace_bvh2_layers_inst");
    CHECK(nameOf(KernelId::Trace, in) == "trace_bvh2_inst");  // the trace kernel has no layers
    CHECK(nameOf(KernelId::Wavefront, in) == "wavefront_layers_inst");
    in.wide = true;
    in.memoryStack = true;
    in.features = gpu::kFeatureIridescence;
    in.aov = true;
    in.cameraEffects = true;
    CHECK(nameOf(KernelId::Pathtrace, in) == "pathtrace_bvh4m_layers_iridescence_motion_aov");
    CHECK(nameOf(KernelId::Wavefront, in) == "wavefront_layers_iridescence");
    CHECK(variantDefines(chooseVariant(KernelId::Pathtrace, in)) ==
          std::vector<std::string>{"STRATA_BVH4_MEMSTACK", "STRATA_LAYERS", "STRATA_IRIDESCENCE", "STRATA_MOTION",
                                   "STRATA_AOV"});
    // Kernels without axes never change.
    CHECK(nameOf(KernelId::DenoiseNfor, in) == "denoise_nfor");
    // A memory stack means nothing without the four-wide tree.
    in.wide = false;
    CHECK(nameOf(KernelId::Trace, in) == "trace_bvh2");
}

TEST_CASE("spirv: every axis on and off compiles to SPIR-V that passes spirv-val") {
    TempDir dir;
    for (const Variant& v : coveringVariants()) {
        const std::string name = variantName(v);
        CAPTURE(name);
        const std::vector<std::uint32_t> words = compileGlsl(kernelInfo(v.kernel).source, variantDefines(v));
        REQUIRE(words.size() > 5);
        CHECK(words[0] == 0x07230203u);
        const auto path = dir.path / (name + ".spv");
        writeWords(path, words);
        const auto r = runShell(std::string(STRATA_SPIRV_VAL) + " --target-env vulkan1.1 " + path.string());
        CAPTURE(r.output);
        CHECK(r.status == 0);
    }
}

TEST_CASE("spirv: the run-time compiler makes glslangValidator's words") {
    // The modules once compiled at build time by glslangValidator
    // --target-env vulkan1.1 are the ones compiled now: same SPIR-V, same images.
    TempDir dir;
    const Variant v{KernelId::Pathtrace, chooseVariant(KernelId::Pathtrace,
                                                       {gpu::kFeatureIridescence | gpu::kFeatureInstancing, false,
                                                        false, true, true})
                                             .axes};
    std::string defines;
    for (const std::string& d : variantDefines(v)) defines += " -D" + d;
    const auto out = dir.path / "validator.spv";
    const std::string src = std::string(STRATA_SOURCE_DIR) + "/shaders";
    const auto r = runShell(std::string(STRATA_GLSLANG_VALIDATOR) + " --target-env vulkan1.1 -I" + src + " -I" +
                            STRATA_GENERATED_SHADERS_DIR + defines + " -o " + out.string() + " " + src +
                            "/pathtrace.comp");
    CAPTURE(r.output);
    REQUIRE(r.status == 0);
    CHECK(readWords(out) == compileGlsl("pathtrace.comp", variantDefines(v)));
}

TEST_CASE("spirv: docs/architecture.md holds the feature table as the code states it") {
    const std::string doc = readText(std::string(STRATA_SOURCE_DIR) + "/docs/architecture.md");
    const std::string table = featureTableMarkdown();
    CHECK_MESSAGE(doc.find(table) != std::string::npos, "docs/architecture.md should hold, verbatim:\n" << table);
}

TEST_CASE("shader cache: cold, warm, corrupt, foreign and unwritable entries") {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const Variant v{KernelId::Trace, chooseVariant(KernelId::Trace, {gpu::kFeatureInstancing}).axes};
    const std::vector<std::uint32_t> expected = compileGlsl("trace.comp", variantDefines(v));
    const std::filesystem::path file = cache + "/" + variantName(v) + "-" + moduleKey(v) + ".spv";

    ShaderCacheStats cold;
    CHECK(cachedModule(v, cache, cold) == expected);
    CHECK(cold.compiled == 1);
    CHECK(cold.loaded == 0);
    REQUIRE(std::filesystem::exists(file));

    ShaderCacheStats warm;
    CHECK(cachedModule(v, cache, warm) == expected);
    CHECK(warm.compiled == 0);
    CHECK(warm.loaded == 1);

    SUBCASE("a flipped byte is compiled again and the entry replaced") {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(200);
        f.put('\x5a');
        f.close();
        ShaderCacheStats s;
        CHECK(cachedModule(v, cache, s) == expected);
        CHECK(s.rejected == 1);
        CHECK(s.compiled == 1);
        ShaderCacheStats again;
        CHECK(cachedModule(v, cache, again) == expected);
        CHECK(again.loaded == 1);
    }
    SUBCASE("a truncated entry is compiled again") {
        std::filesystem::resize_file(file, 100);
        ShaderCacheStats s;
        CHECK(cachedModule(v, cache, s) == expected);
        CHECK(s.rejected == 1);
    }
    SUBCASE("another module's entry under this name (another key) is compiled again") {
        const Variant other{KernelId::Trace, 0};
        ShaderCacheStats o;
        cachedModule(other, cache, o);
        std::filesystem::copy_file(cache + "/" + variantName(other) + "-" + moduleKey(other) + ".spv", file,
                                   std::filesystem::copy_options::overwrite_existing);
        ShaderCacheStats s;
        CHECK(cachedModule(v, cache, s) == expected);
        CHECK(s.rejected == 1);
        CHECK(s.compiled == 1);
    }
    SUBCASE("a folder that cannot be made: compiled in memory, flagged") {
        const std::string blocked = (dir.path / "a-file").string();
        std::ofstream(blocked) << "x";
        ShaderCacheStats s;
        bool unwritable = false;
        CHECK(cachedModule(v, blocked + "/cache", s, &unwritable) == expected);
        CHECK(unwritable);
        CHECK(s.compiled == 1);
    }
    SUBCASE("no folder: compiled every time, nothing written") {
        ShaderCacheStats s;
        CHECK(cachedModule(v, "", s) == expected);
        CHECK(cachedModule(v, "", s) == expected);
        CHECK(s.compiled == 2);
    }
}

TEST_CASE("shader cache: writers at once leave whole entries") {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const Variant v{KernelId::Wavefront, 0};
    std::vector<std::thread> threads;
    std::vector<ShaderCacheStats> stats(4);
    std::vector<std::vector<std::uint32_t>> got(4);
    for (int i = 0; i < 4; ++i)
        threads.emplace_back([&, i] { got[i] = cachedModule(v, cache, stats[i]); });
    for (auto& t : threads) t.join();
    for (int i = 1; i < 4; ++i) CHECK(got[i] == got[0]);
    ShaderCacheStats after;
    CHECK(cachedModule(v, cache, after) == got[0]);
    CHECK(after.loaded == 1);
    // No temporary file is left behind.
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(cache)) {
        ++files;
        CHECK(e.path().extension() == ".spv");
    }
    CHECK(files == 1);
}

TEST_CASE("shader cache: 'strata shaders SCENE' fills the folder a later run finds whole, and off writes nothing") {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const std::string scene = std::string(STRATA_SOURCE_DIR) + "/scenes/cornell-box.gltf";
    const auto cold = strata::test::run("shaders " + scene + " --quiet --shader-cache " + cache);
    CAPTURE(cold.output);
    REQUIRE(cold.status == 0);
    CHECK(cold.output.find(" compiled, 0 from the cache") != std::string::npos);
    const auto warm = strata::test::run("shaders " + scene + " --quiet --shader-cache " + cache);
    CAPTURE(warm.output);
    CHECK(warm.status == 0);
    CHECK(warm.output.find(": 0 compiled, ") != std::string::npos);
    const TempDir empty;
    const auto off = strata::test::run("shaders " + scene + " --quiet --shader-cache off",
                                       "XDG_CACHE_HOME=" + empty.path.string());
    CHECK(off.status == 0);
    CHECK(off.output.find("0 from the cache (off)") != std::string::npos);
    CHECK(std::filesystem::is_empty(empty.path));
    // Without arguments: the feature table.
    const auto table = strata::test::run("shaders");
    CHECK(table.output == featureTableMarkdown());
}

TEST_SUITE_END();

TEST_CASE("shader cache: a render compiles its modules once, and the next render reads them" *
          doctest::test_suite("render")) {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const std::string args = "render " + std::string(STRATA_SOURCE_DIR) +
                             "/scenes/cornell-box.gltf --spp 1 --width 16 --height 16 --quiet --shader-cache " +
                             cache + " -o " + (dir.path / "a.exr").string() + " --stats-json ";
    const auto first = strata::test::run(args + (dir.path / "first.json").string());
    CAPTURE(first.output);
    REQUIRE(first.status == 0);
    const auto second = strata::test::run(args + (dir.path / "second.json").string());
    REQUIRE(second.status == 0);
    const auto startup = [](const std::filesystem::path& p) {
        return nlohmann::json::parse(readText(p.string()))["startup"];
    };
    const auto a = startup(dir.path / "first.json"), b = startup(dir.path / "second.json");
    CHECK(a["shaders_compiled"].get<int>() >= 1);
    CHECK(a["shaders_cached"].get<int>() == 0);
    CHECK(b["shaders_compiled"].get<int>() == 0);
    CHECK(b["shaders_cached"].get<int>() == a["shaders_compiled"].get<int>());
}
