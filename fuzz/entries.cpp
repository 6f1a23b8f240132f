#include "entries.h"

#include <cstring>
#include <functional>
#include <map>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

#include "cli/commands.h"
#include "pack/env_tables.h"
#include "image/image_io.h"
#include "render/state.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "stages/stages.h"
#include "util/error.h"

namespace strata::fuzz {
namespace {

// Runs `body`, taking strata::Error as a handled input.
void handled(const std::function<void()>& body) {
    try {
        body();
    } catch (const Error&) {
    }
}

// The host stages of `strata render` (stages/stages.h) over the bytes:
// load -> camera -> BVH -> pack, consuming as the command does.
void loadAndPack(const std::string& path, const std::vector<unsigned char>& bytes, const std::string& root) {
    SceneRequest request;
    request.file = path;
    request.bytes = bytes;
    request.load.restrictPaths = root;
    // A scene the budget lets through must load and build within libFuzzer's
    // -rss_limit_mb=4096 and -timeout=60 under the sanitizers: 2 million
    // emitters (1 GiB's worth) took 83 s there, 0.5 million (this) about 20.
    request.load.hostMemory = std::uint64_t(256) << 20;
    request.camera = CameraChoice{{}, 64, 48};
    request.build.threads = 1;  // libFuzzer wants one thread
    request.bvhWidth = 4;
    request.consume = Consume::All;
    (void)prepareScene(request);
}

void appendU32(std::vector<unsigned char>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

// A GLB of one textured triangle whose image is `image`.
std::vector<unsigned char> texturedTriangle(const std::uint8_t* image, std::size_t size) {
    std::vector<unsigned char> bin(image, image + size);
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t geometry = bin.size();
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    bin.insert(bin.end(), reinterpret_cast<const unsigned char*>(positions),
               reinterpret_cast<const unsigned char*>(positions) + sizeof positions);
    bin.insert(bin.end(), reinterpret_cast<const unsigned char*>(uvs),
               reinterpret_cast<const unsigned char*>(uvs) + sizeof uvs);
    const std::string n = std::to_string(size), g = std::to_string(geometry), u = std::to_string(geometry + 36);
    std::string json =
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],)"
        R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},"emissiveTexture":{"index":0},)"
        R"("emissiveFactor":[1,1,1]}],"textures":[{"source":0}],"images":[{"bufferView":0,"mimeType":"image/png"}],)"
        R"("accessors":[{"bufferView":1,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
        R"({"bufferView":2,"componentType":5126,"count":3,"type":"VEC2"}],)"
        R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" + n +
        R"(},{"buffer":0,"byteOffset":)" + g + R"(,"byteLength":36},{"buffer":0,"byteOffset":)" + u +
        R"(,"byteLength":24}],"buffers":[{"byteLength":)" + std::to_string(bin.size()) + "}]}";
    while (json.size() % 4) json.push_back(' ');
    std::vector<unsigned char> glb{'g', 'l', 'T', 'F'};
    appendU32(glb, 2);
    appendU32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    appendU32(glb, static_cast<std::uint32_t>(json.size()));
    appendU32(glb, 0x4E4F534Au);  // JSON
    glb.insert(glb.end(), json.begin(), json.end());
    appendU32(glb, static_cast<std::uint32_t>(bin.size()));
    appendU32(glb, 0x004E4942u);  // BIN
    glb.insert(glb.end(), bin.begin(), bin.end());
    return glb;
}

}  // namespace

void gltfInput(const std::uint8_t* data, std::size_t size, const std::string& root) {
    handled([&] { loadAndPack(root + "/input.gltf", std::vector<unsigned char>(data, data + size), root); });
}

void stateInput(const std::uint8_t* data, std::size_t size) {
    // readState reads a path: the bytes go to an anonymous file in memory.
    const int fd = memfd_create("strata-fuzz-state", 0);
    if (fd < 0) return;
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = write(fd, data + done, size - done);
        if (n <= 0) break;
        done += std::size_t(n);
    }
    handled([&] { (void)readState("/proc/self/fd/" + std::to_string(fd)); });
    close(fd);
}

void cliInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> words(1);
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == 0) words.emplace_back();
        else words.back().push_back(static_cast<char>(data[i]));
    }
    using Parser = std::function<void(const std::vector<std::string>&)>;
    static const std::map<std::string, Parser> parsers{
        {"render", [](const auto& a) { (void)cli::parseRender(a); }},
        {"reference", [](const auto& a) { (void)cli::parseReference(a); }},
        {"compare", [](const auto& a) { (void)cli::parseCompare(a); }},
        {"converge", [](const auto& a) { (void)cli::parseConverge(a); }},
        {"edges", [](const auto& a) { (void)cli::parseEdges(a); }},
        {"bench", [](const auto& a) { (void)cli::parseBench(a); }},
        {"denoise", [](const auto& a) { (void)cli::parseDenoise(a); }},
        {"merge", [](const auto& a) { (void)cli::parseMerge(a); }},
        {"shaders", [](const auto& a) { (void)cli::parseShaders(a); }},
    };
    const auto parser = parsers.find(words.front());
    if (parser == parsers.end()) return;
    const std::vector<std::string> args(words.begin() + 1, words.end());
    handled([&] { parser->second(args); });
    // The help text of every command is made from the same tables.
    if (const cli::CommandInfo* command = cli::findCommand(words.front())) (void)command->help();
}

void imageInput(const std::uint8_t* data, std::size_t size, const std::string& root) {
    if (size == 0) return;
    if ((data[0] & 1) == 0) {
        const std::vector<unsigned char> glb = texturedTriangle(data + 1, size - 1);
        handled([&] { loadAndPack(root + "/image.glb", glb, root); });
        return;
    }
    if (size < 3) return;
    RgbImage map;
    map.width = 1 + data[1] % 64;
    map.height = 1 + data[2] % 32;
    map.rgb.assign(std::size_t(map.width) * map.height * 3, 0.0f);
    std::memcpy(map.rgb.data(), data + 3, std::min(size - 3, map.rgb.size() * sizeof(float)));
    EnvironmentOptions options;
    options.file = "fuzz.exr";
    handled([&] {
        Scene scene;
        scene.environment = environmentFromImage(options, std::move(map));
        (void)buildEnvTables(scene.environment);
        (void)envTexels(scene.environment);
        (void)envMeanLuminance(scene.environment);
    });
}

}  // namespace strata::fuzz
