// What the image-format test file writers share (make_webp.cpp,
// make_avif.cpp): the 4 x 4 checker they encode, a black PNG fallback, and
// the glTF document of a triangle whose emissive texture reads them.
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace format_files {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// RGBA rows top to bottom, alpha 255 (tests/test_texture_formats.cpp mirrors it).
constexpr int kSize = 4;
inline std::vector<std::uint8_t> checker() {
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

inline void writeBytes(const fs::path& path, const std::uint8_t* data, std::size_t size) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!f) throw std::runtime_error("cannot write " + path.string());
}

// A triangle with TEXCOORD_0 in a data-URI buffer, a camera, one emissive
// material reading texture 0, and `texture` / `images` as given; the image
// format's `extension` used (and required), by `generator`.
inline Json document(Json texture, Json images, const std::string& extension, bool required,
                     const std::string& generator) {
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
        {"asset", {{"version", "2.0"}, {"generator", generator}}},
        {"extensionsUsed", {extension}},
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
    if (required) j["extensionsRequired"] = {extension};
    return j;
}

inline void writeJson(const fs::path& path, const Json& j) {
    std::ofstream out(path);
    out << j.dump(1) << "\n";
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The three files of `extension` whose encoded checker is `encoded`
// (`name`.EXT): NAME.gltf (the image through the extension, the black PNG
// as fallback `source`), NAME-required.gltf (no fallback, the extension
// required), NAME-corrupt.gltf (the file cut to its first 40 bytes).
inline void writeSet(const fs::path& dir, const std::string& name, const std::string& ext,
                     const std::string& extension, const std::vector<std::uint8_t>& encoded,
                     const std::string& generator) {
    writeBytes(dir / ("checker." + ext), encoded.data(), encoded.size());
    writeBytes(dir / ("corrupt." + ext), encoded.data(), std::min<std::size_t>(encoded.size(), 40));
    const Json texture = {{"source", 0}, {"sampler", 0}, {"extensions", {{extension, {{"source", 1}}}}}};
    writeJson(dir / (name + ".gltf"),
              document(texture, {{{"uri", kBlackPng}}, {{"uri", "checker." + ext}}}, extension, false, generator));
    writeJson(dir / (name + "-corrupt.gltf"),
              document(texture, {{{"uri", kBlackPng}}, {{"uri", "corrupt." + ext}}}, extension, false, generator));
    const Json only = {{"sampler", 0}, {"extensions", {{extension, {{"source", 0}}}}}};
    writeJson(dir / (name + "-required.gltf"), document(only, {{{"uri", "checker." + ext}}}, extension, true, generator));
}

}  // namespace format_files
