// Writes the EXT_texture_webp files of tests/test_texture_formats.cpp into
// DIR with libwebp's own encoder (tests/CMakeLists.txt runs it at build
// time):
//   make_webp DIR
// checker.webp: kChecker (our own 4 x 4 RGBA pattern), lossless.
// webp.gltf: a triangle whose emissive texture is checker.webp through
//   EXT_texture_webp (used, not required), with a 1 x 1 black PNG fallback
//   `source`.
// webp-required.gltf: the same texture with no fallback; the extension
//   required.
// webp-corrupt.gltf: webp.gltf with the WebP file cut to its first 40 bytes
//   (corrupt.webp).
#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <webp/encode.h>

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// RGBA rows top to bottom, alpha 255 (tests/test_texture_formats.cpp mirrors it).
constexpr int kSize = 4;
std::vector<std::uint8_t> checker() {
    std::vector<std::uint8_t> out;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const bool odd = (x + y) % 2 != 0;
            out.insert(out.end(), {static_cast<std::uint8_t>(odd ? 255 : 16 * x), static_cast<std::uint8_t>(64 * y),
                                   static_cast<std::uint8_t>(odd ? 32 : 200), 255});
        }
    }
    return out;
}

// A 1 x 1 black RGB PNG (scripts/make_texture_scenes.py's png() writes it so).
constexpr const char* kBlackPng =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR42mNgYGAAAAAEAAHI6uv5AAAAAElFTkSuQmCC";

void writeBytes(const fs::path& path, const std::uint8_t* data, std::size_t size) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!f) throw std::runtime_error("cannot write " + path.string());
}

// A triangle with TEXCOORD_0 in a data-URI buffer, a camera, one emissive
// material reading texture 0, and `texture` / `images` as given.
Json document(Json texture, Json images, bool required) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float uvs[6] = {0, 1, 1, 1, 0, 0};
    std::string raw(reinterpret_cast<const char*>(positions), sizeof positions);
    raw.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
    static constexpr char kB64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string b64;
    for (std::size_t i = 0; i < raw.size(); i += 3) {
        std::uint32_t n = static_cast<std::uint8_t>(raw[i]) << 16;
        if (i + 1 < raw.size()) n |= static_cast<std::uint8_t>(raw[i + 1]) << 8;
        if (i + 2 < raw.size()) n |= static_cast<std::uint8_t>(raw[i + 2]);
        b64 += kB64[n >> 18 & 63];
        b64 += kB64[n >> 12 & 63];
        b64 += i + 1 < raw.size() ? kB64[n >> 6 & 63] : '=';
        b64 += i + 2 < raw.size() ? kB64[n & 63] : '=';
    }
    Json j = {
        {"asset", {{"version", "2.0"}, {"generator", "strata tests/data/make_webp.cpp"}}},
        {"extensionsUsed", {"EXT_texture_webp"}},
        {"buffers", {{{"byteLength", raw.size()}, {"uri", "data:application/octet-stream;base64," + b64}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                         {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                        {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
        {"images", std::move(images)},
        {"samplers", {{{"magFilter", 9728}, {"minFilter", 9728}}}},
        {"textures", {std::move(texture)}},
        {"materials", {{{"name", "Checker"}, {"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 0}}}}}},
        {"meshes", {{{"name", "Tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}},
                                                       {"material", 0}}}}}}},
        {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}}},
        {"nodes", {{{"name", "Tri"}, {"mesh", 0}}, {{"name", "Camera"}, {"camera", 0}, {"translation", {0.3, 0.3, 3}}}}},
        {"scenes", {{{"nodes", {0, 1}}}}},
        {"scene", 0},
    };
    if (required) j["extensionsRequired"] = {"EXT_texture_webp"};
    return j;
}

void writeJson(const fs::path& path, const Json& j) {
    std::ofstream out(path);
    out << j.dump(1) << "\n";
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_webp DIR\n");
        return 2;
    }
    try {
        const fs::path dir = argv[1];
        fs::create_directories(dir);
        const std::vector<std::uint8_t> pixels = checker();
        std::uint8_t* webp = nullptr;
        const std::size_t size = WebPEncodeLosslessRGBA(pixels.data(), kSize, kSize, kSize * 4, &webp);
        if (size == 0) throw std::runtime_error("libwebp: encoding failed");
        writeBytes(dir / "checker.webp", webp, size);
        writeBytes(dir / "corrupt.webp", webp, std::min<std::size_t>(size, 40));
        WebPFree(webp);

        const Json webpTexture = {{"source", 0}, {"sampler", 0},
                                  {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}};
        writeJson(dir / "webp.gltf", document(webpTexture, {{{"uri", kBlackPng}}, {{"uri", "checker.webp"}}}, false));
        writeJson(dir / "webp-corrupt.gltf",
                  document(webpTexture, {{{"uri", kBlackPng}}, {{"uri", "corrupt.webp"}}}, false));
        const Json onlyWebp = {{"sampler", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}};
        writeJson(dir / "webp-required.gltf", document(onlyWebp, {{{"uri", "checker.webp"}}}, true));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_webp: %s\n", e.what());
        return 1;
    }
    return 0;
}
