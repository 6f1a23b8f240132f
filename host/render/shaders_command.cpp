#include "render/shaders_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "spirv/cache.h"
#include "spirv/features.h"
#include "stages/stages.h"
#include "util/error.h"

namespace strata {
namespace {

using spirv::KernelId;
using spirv::Variant;

void addOnce(std::vector<Variant>& list, const Variant& v) {
    for (const Variant& o : list)
        if (o == v) return;
    list.push_back(v);
}

// What a render of the scene (default load options) may use: any traversal,
// with and without the AOVs and the camera effects, either integrator, and
// the denoiser.
void addSceneModules(const std::string& file, std::vector<Variant>& list) {
    SceneRequest request;
    request.file = file;
    const HostScene host = prepareScene(request);
    const GpuScene& gpu = host.gpu;
    spirv::VariantInputs in;
    in.features = gpu.features.bits;
    for (const auto& [wide, memoryStack] : {std::pair{true, false}, {false, false}, {true, true}}) {
        in.wide = wide;
        in.memoryStack = memoryStack;
        for (const bool aov : {false, true})
            for (const bool effects : {false, true}) {
                in.aov = aov;
                in.cameraEffects = effects;
                addOnce(list, spirv::chooseVariant(KernelId::Pathtrace, in));
            }
        addOnce(list, spirv::chooseVariant(KernelId::Trace, in));
    }
    addOnce(list, spirv::chooseVariant(KernelId::Wavefront, in));
    for (KernelId k : {KernelId::DenoiseNfor, KernelId::DenoiseSelect, KernelId::DenoiseAtrous, KernelId::DenoiseFeatures})
        addOnce(list, {k, 0});
}

}  // namespace

int runShaders(const ShadersCommand& cmd) {
    if (!cmd.all && cmd.scenes.empty()) {
        std::fputs(spirv::featureTableMarkdown().c_str(), stdout);
        return 0;
    }
    if (!cmd.out.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(cmd.out, ec);
        if (ec || !std::filesystem::is_directory(cmd.out)) fail(cmd.out, "--out: cannot make the folder");
    }
    std::vector<Variant> list;
    if (cmd.all) list = spirv::allVariants();
    for (const std::string& scene : cmd.scenes) addSceneModules(scene, list);

    const auto t0 = std::chrono::steady_clock::now();
    for (const Variant& v : list) {
        const spirv::ShaderCacheStats before = spirv::shaderCacheStats();
        const auto words = spirv::moduleFor(v);
        const spirv::ShaderCacheStats after = spirv::shaderCacheStats();
        const std::string name = spirv::variantName(v);
        if (!cmd.quiet)
            std::printf("%-48s %s\n", name.c_str(),
                        after.compiled > before.compiled
                            ? ("compiled (" + std::to_string(int(after.compileMs - before.compileMs + 0.5)) + " ms)").c_str()
                            : "from the cache");
        if (!cmd.out.empty()) {
            const std::string path = cmd.out + "/" + name + ".spv";
            std::ofstream f(path, std::ios::binary);
            f.write(reinterpret_cast<const char*>(words.data()), std::streamsize(words.size_bytes()));
            if (!f) fail(path, "cannot write the file");
        }
    }
    const spirv::ShaderCacheStats s = spirv::shaderCacheStats();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string dir = spirv::shaderCacheDir();
    std::printf("strata: %zu modules in %.2f s: %u compiled, %u from the cache (%s)\n", list.size(), seconds,
                s.compiled, s.loaded, dir.empty() ? "off" : dir.c_str());
    return 0;
}

}  // namespace strata
