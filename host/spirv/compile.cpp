#include "spirv/compile.h"

#include <mutex>
#include <stdexcept>
#include <string_view>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>

#include "spirv/sources.h"

namespace strata::spirv {
namespace {

std::string parentOf(const std::string& path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

// #include "x" from the embedded files: beside the including file first,
// then from shaders/ (glslangValidator's -Ishaders and the generated folder).
class EmbeddedIncluder : public glslang::TShader::Includer {
public:
    IncludeResult* includeLocal(const char* header, const char* includer, std::size_t) override {
        for (const std::string& candidate : {parentOf(includer ? includer : "") + header, std::string(header)}) {
            if (const std::string_view* text = findSource(candidate))
                return new IncludeResult(candidate, text->data(), text->size(), nullptr);
        }
        return nullptr;
    }
    IncludeResult* includeSystem(const char* header, const char* includer, std::size_t depth) override {
        return includeLocal(header, includer, depth);
    }
    void releaseInclude(IncludeResult* result) override { delete result; }
};

std::mutex& compilerMutex() {
    static std::mutex m;
    return m;
}

}  // namespace

std::vector<std::uint32_t> compileGlsl(const std::string& source, const std::vector<std::string>& defines) {
    const std::string_view* text = findSource(source);
    if (text == nullptr) throw std::logic_error("spirv::compileGlsl: no embedded shader " + source);
    std::string preamble;
    for (const std::string& d : defines) preamble += "#define " + d + "\n";

    // glslang's process state and its pools are global: one compile at a time.
    const std::lock_guard<std::mutex> lock(compilerMutex());
    static const bool initialized = glslang::InitializeProcess();
    (void)initialized;

    glslang::TShader shader(EShLangCompute);
    const char* strings[] = {text->data()};
    const int lengths[] = {static_cast<int>(text->size())};
    const char* names[] = {source.c_str()};
    shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);
    shader.setPreamble(preamble.c_str());
    shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
    const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
    EmbeddedIncluder includer;
    if (!shader.parse(GetDefaultResources(), 100, false, messages, includer))
        throw std::logic_error("spirv::compileGlsl: " + source + ": " + shader.getInfoLog());
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages))
        throw std::logic_error("spirv::compileGlsl: " + source + " (link): " + program.getInfoLog());
    std::vector<unsigned int> words;
    spv::SpvBuildLogger logger;
    glslang::SpvOptions options;  // no debug information, no optimizer: glslangValidator's defaults
    glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), words, &logger, &options);
    if (words.empty()) throw std::logic_error("spirv::compileGlsl: " + source + ": " + logger.getAllMessages());
    return {words.begin(), words.end()};
}

std::string compilerVersion() {
    return "glslang " + std::to_string(GLSLANG_VERSION_MAJOR) + "." + std::to_string(GLSLANG_VERSION_MINOR) + "." +
           std::to_string(GLSLANG_VERSION_PATCH) + GLSLANG_VERSION_FLAVOR;
}

}  // namespace strata::spirv
