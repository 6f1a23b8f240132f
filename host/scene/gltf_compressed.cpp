// The JSON that tinygltf 2.7 refuses where glTF 2.0 allows it (the
// compressed extensions' indices and fallback buffers, skins without
// inverseBindMatrices, KHR_animation_pointer channels, image data: URIs of
// newer media types), rewritten before it
// parses and restored after; and what the KHR_draco_mesh_compression and
// EXT_meshopt_compression decoders share: the range check of compressed
// bytes, the extension objects' integer fields, which decoders this build
// has.
#include <cstdio>
#include <cstring>
#include <limits>

#include <nlohmann/json.hpp>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

using Json = nlohmann::json;

constexpr std::string_view kDraco = "KHR_draco_mesh_compression";
constexpr std::string_view kMeshopt = "EXT_meshopt_compression";

// A one-byte buffer that tinygltf loads in place of a placeholder buffer
// (its data is emptied again after the parse): tinygltf refuses an empty
// data uri.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";

std::uint32_t readU32(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

void appendU32(std::vector<unsigned char>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

bool mentions(std::string_view json, std::string_view what) {
    return json.find(what) != std::string_view::npos;
}

const Json* member(const Json& object, const char* key) {
    if (!object.is_object()) return nullptr;
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

// Primitives whose `indices` accessor has no bufferView (glTF 2.0 allows one
// without; every Draco-compressed primitive has one): tinygltf 2.7 fails the
// whole file on them ("accessor[i] invalid bufferView"), so `indices` is
// removed before the parse and put back after it.
void hideIndicesWithoutView(Json& root, TinygltfFixups& fixups) {
    const Json* accessors = member(root, "accessors");
    Json* meshes = root.is_object() && root.contains("meshes") ? &root["meshes"] : nullptr;
    if (!accessors || !accessors->is_array() || !meshes || !meshes->is_array()) return;
    for (std::size_t m = 0; m < meshes->size(); ++m) {
        Json* primitives = (*meshes)[m].is_object() && (*meshes)[m].contains("primitives")
                               ? &(*meshes)[m]["primitives"]
                               : nullptr;
        if (!primitives || !primitives->is_array()) continue;
        for (std::size_t p = 0; p < primitives->size(); ++p) {
            Json& primitive = (*primitives)[p];
            const Json* indices = member(primitive, "indices");
            if (!indices || !indices->is_number_unsigned()) continue;
            const auto index = indices->get<std::uint64_t>();
            if (index >= accessors->size() || index > std::numeric_limits<int>::max()) continue;
            if (member((*accessors)[index], "bufferView")) continue;
            fixups.indices.push_back({m, p, static_cast<int>(index)});
            primitive.erase("indices");
        }
    }
}

// EXT_meshopt_compression's fallback buffers (spec, "Fallback buffers"): a
// buffer tagged {"fallback": true}, or one without uri (other than a GLB's
// first, which is the BIN chunk) that a compressed bufferView names as its
// own buffer. tinygltf 2.7 refuses a buffer without uri in a .gltf and gives
// one in a GLB the BIN chunk's bytes, so such a buffer becomes a placeholder.
// With the decoder a tagged buffer is never read and becomes one too.
void replaceFallbackBuffers(Json& root, bool binary, TinygltfFixups& fixups) {
    Json* buffers = root.is_object() && root.contains("buffers") ? &root["buffers"] : nullptr;
    if (!buffers || !buffers->is_array()) return;
    std::vector<bool> parentOfCompressed(buffers->size(), false);
    if (const Json* views = member(root, "bufferViews"); views && views->is_array()) {
        for (const Json& view : *views) {
            const Json* extensions = member(view, "extensions");
            const Json* buffer = member(view, "buffer");
            if (!extensions || !member(*extensions, kMeshopt.data()) || !buffer ||
                !buffer->is_number_unsigned()) {
                continue;
            }
            const auto b = buffer->get<std::uint64_t>();
            if (b < parentOfCompressed.size()) parentOfCompressed[b] = true;
        }
    }
    for (std::size_t b = 0; b < buffers->size(); ++b) {
        Json& buffer = (*buffers)[b];
        if (!buffer.is_object()) continue;
        const Json* extensions = member(buffer, "extensions");
        const Json* ext = extensions ? member(*extensions, kMeshopt.data()) : nullptr;
        const Json* tag = ext ? member(*ext, "fallback") : nullptr;
        const bool tagged = tag && tag->is_boolean() && tag->get<bool>();
        const bool hasUri = member(buffer, "uri") != nullptr;
        const bool binChunk = binary && b == 0 && !hasUri;
        const bool placeholder = (!hasUri && !binChunk && (tagged || parentOfCompressed[b])) ||
                                 (tagged && STRATA_MESHOPT);
        if (!placeholder) continue;
        buffer["uri"] = kPlaceholderUri;
        buffer["byteLength"] = 1;
        fixups.placeholders.push_back(b);
    }
}

// Skins without inverseBindMatrices (optional: identity matrices, glTF 2.0
// 3.7.3.1): tinygltf 2.7 requires the property, so it is given -1 (none),
// which the skinning reads as identity.
void markSkinsWithoutInverseBind(Json& root, TinygltfFixups& fixups) {
    Json* skins = root.is_object() && root.contains("skins") ? &root["skins"] : nullptr;
    if (!skins || !skins->is_array()) return;
    for (Json& skin : *skins)
        if (skin.is_object() && !skin.contains("inverseBindMatrices")) {
            skin["inverseBindMatrices"] = -1;
            fixups.changed = true;
        }
}

// KHR_animation_pointer channels (their target has a JSON pointer instead
// of a node, which tinygltf 2.7 requires): a pointer to a node's
// translation, rotation, scale or weights becomes that node's channel;
// every other target is dropped, counted in one warning.
void rewritePointerChannels(Json& root, TinygltfFixups& fixups) {
    Json* animations = root.is_object() && root.contains("animations") ? &root["animations"] : nullptr;
    if (!animations || !animations->is_array()) return;
    std::size_t dropped = 0;
    std::string firstDropped;
    for (Json& animation : *animations) {
        Json* channels = animation.is_object() && animation.contains("channels") ? &animation["channels"] : nullptr;
        if (!channels || !channels->is_array()) continue;
        Json kept = Json::array();
        for (Json& channel : *channels) {
            Json* target = channel.is_object() && channel.contains("target") ? &channel["target"] : nullptr;
            const Json* extensions = target ? member(*target, "extensions") : nullptr;
            const Json* ext = extensions ? member(*extensions, "KHR_animation_pointer") : nullptr;
            const Json* pointer = ext ? member(*ext, "pointer") : nullptr;
            if (!pointer || member(*target, "node")) {
                kept.push_back(std::move(channel));
                continue;
            }
            fixups.changed = true;
            const std::string p = pointer->is_string() ? pointer->get<std::string>() : std::string();
            unsigned node = 0;
            char property[16] = {};
            int used = 0;
            if (std::sscanf(p.c_str(), "/nodes/%u/%15[a-z]%n", &node, property, &used) == 2 &&
                std::size_t(used) == p.size() && node <= unsigned(std::numeric_limits<int>::max()) &&
                (std::strcmp(property, "translation") == 0 || std::strcmp(property, "rotation") == 0 ||
                 std::strcmp(property, "scale") == 0 || std::strcmp(property, "weights") == 0)) {
                (*target)["node"] = node;
                (*target)["path"] = property;
                kept.push_back(std::move(channel));
                continue;
            }
            if (dropped++ == 0) firstDropped = p;
        }
        *channels = std::move(kept);
    }
    if (dropped > 0)
        fixups.warnings.push_back("KHR_animation_pointer: " + std::to_string(dropped) +
                                  " channel(s) animating other than a node's transform or weights ignored (first: " +
                                  firstDropped + ")");
}

// Images embedded as data: URIs of a media type tinygltf 2.7 does not list
// (image/webp, image/ktx2, image/avif...: it then takes the uri for a file
// name): given as application/octet-stream, which it decodes; the image
// decoder tells the formats apart by their bytes.
void retypeImageDataUris(Json& root, TinygltfFixups& fixups) {
    Json* images = root.is_object() && root.contains("images") ? &root["images"] : nullptr;
    if (!images || !images->is_array()) return;
    for (Json& image : *images) {
        Json* uri = image.is_object() && image.contains("uri") ? &image["uri"] : nullptr;
        if (!uri || !uri->is_string()) continue;
        const std::string& text = uri->get_ref<const std::string&>();
        const std::size_t base64 = text.find(";base64,");
        if (text.rfind("data:image/", 0) != 0 || base64 == std::string::npos) continue;
        const std::string type = text.substr(11, base64 - 11);
        if (type == "png" || type == "jpeg" || type == "bmp" || type == "gif") continue;
        *uri = "data:application/octet-stream" + text.substr(base64);
        fixups.changed = true;
    }
}

// How often `what` occurs in `json`.
std::size_t occurrences(std::string_view json, std::string_view what) {
    std::size_t n = 0;
    for (std::size_t at = json.find(what); at != std::string_view::npos; at = json.find(what, at + what.size())) ++n;
    return n;
}

// A GLB with its JSON chunk replaced (padded with spaces to a 4-byte
// boundary, as glTF 2.0's "Binary glTF Layout" asks) and every later chunk
// kept; `jsonEnd` is where the old JSON chunk ends, `length` the header's
// total length.
std::vector<unsigned char> rebuildGlb(const std::vector<unsigned char>& glb, const std::string& json,
                                      std::size_t jsonEnd, std::size_t length) {
    std::string padded = json;
    padded.append((4 - padded.size() % 4) % 4, ' ');
    std::vector<unsigned char> out;
    out.reserve(20 + padded.size() + (length - jsonEnd));
    out.insert(out.end(), glb.begin(), glb.begin() + 8);  // magic, version
    appendU32(out, static_cast<std::uint32_t>(20 + padded.size() + (length - jsonEnd)));
    appendU32(out, static_cast<std::uint32_t>(padded.size()));
    appendU32(out, 0x4E4F534Au);  // "JSON"
    out.insert(out.end(), padded.begin(), padded.end());
    out.insert(out.end(), glb.begin() + static_cast<std::ptrdiff_t>(jsonEnd),
               glb.begin() + static_cast<std::ptrdiff_t>(length));
    return out;
}

}  // namespace

TinygltfFixups prepareForTinygltf(const std::vector<unsigned char>& bytes, bool binary) {
    TinygltfFixups fixups;
    std::size_t jsonBegin = 0, jsonEnd = bytes.size(), length = bytes.size();
    if (binary) {
        // Header (12 bytes), then the JSON chunk's length and type; anything
        // malformed is left to tinygltf's own messages.
        if (bytes.size() < 20) return fixups;
        length = readU32(bytes.data() + 8);
        jsonBegin = 20;
        jsonEnd = jsonBegin + readU32(bytes.data() + 12);
        if (length > bytes.size() || jsonEnd > length || readU32(bytes.data() + 16) != 0x4E4F534Au) {
            return fixups;
        }
    }
    std::string_view text(reinterpret_cast<const char*>(bytes.data()) + jsonBegin,
                          jsonEnd - jsonBegin);
    // Some writers pad the JSON chunk with NULs instead of spaces.
    while (!text.empty() && text.back() == '\0') text.remove_suffix(1);
    // Only files that may hold what tinygltf refuses are parsed twice: an
    // accessor without bufferView (fewer "bufferView" than accessors' one
    // "componentType" each, or Draco, sparse), a meshopt fallback buffer,
    // a skin, a pointer animation.
    const bool viewless = occurrences(text, "\"componentType\"") > occurrences(text, "\"bufferView\"");
    if (!viewless && !mentions(text, kDraco) && !mentions(text, kMeshopt) && !mentions(text, "\"sparse\"") &&
        !mentions(text, "\"skins\"") && !mentions(text, "KHR_animation_pointer") && !mentions(text, "data:image/webp") &&
        !mentions(text, "data:image/ktx2") && !mentions(text, "data:image/avif"))
        return fixups;
    Json root = Json::parse(text, nullptr, false);
    if (root.is_discarded()) return fixups;  // tinygltf reports the JSON error
    hideIndicesWithoutView(root, fixups);
    if (mentions(text, kMeshopt)) replaceFallbackBuffers(root, binary, fixups);
    markSkinsWithoutInverseBind(root, fixups);
    rewritePointerChannels(root, fixups);
    retypeImageDataUris(root, fixups);
    if (fixups.indices.empty() && fixups.placeholders.empty() && !fixups.changed) return fixups;

    const std::string json = root.dump();
    if (binary) {
        fixups.bytes = rebuildGlb(bytes, json, jsonEnd, length);
    } else {
        fixups.bytes.assign(json.begin(), json.end());
    }
    return fixups;
}

void restoreAfterTinygltf(const TinygltfFixups& fixups, tinygltf::Model& model) {
    for (const auto& hidden : fixups.indices) {
        if (hidden.mesh >= model.meshes.size()) continue;
        auto& primitives = model.meshes[hidden.mesh].primitives;
        if (hidden.primitive < primitives.size()) primitives[hidden.primitive].indices = hidden.accessor;
    }
    for (const std::size_t b : fixups.placeholders) {
        if (b >= model.buffers.size()) continue;
        model.buffers[b].data.clear();
        model.buffers[b].uri.clear();
    }
}

const unsigned char* bufferRange(const std::string& path, const tinygltf::Model& model, int buffer,
                                 std::size_t offset, std::size_t length, const std::string& label) {
    if (buffer < 0 || static_cast<std::size_t>(buffer) >= model.buffers.size()) {
        fail(path, label + ": buffer " + std::to_string(buffer) + " does not exist (" +
                       std::to_string(model.buffers.size()) + " buffers)");
    }
    const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(buffer)].data;
    std::size_t end = 0;
    if (__builtin_add_overflow(offset, length, &end) || end > data.size()) {
        fail(path, label + " is out of range of buffer " + std::to_string(buffer) +
                       ": byteOffset " + std::to_string(offset) + " + byteLength " +
                       std::to_string(length) + " > buffer size " + std::to_string(data.size()));
    }
    return data.data() + offset;
}

std::size_t extensionCount(const std::string& path, const tinygltf::Value& object,
                           const std::string& key, const std::string& label,
                           std::optional<std::size_t> fallback) {
    if (!object.Has(key)) {
        if (fallback) return *fallback;
        fail(path, label + " has no " + key);
    }
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsInt() || v.GetNumberAsInt() < 0) {
        fail(path, label + ": " + key + " is not an integer >= 0 below 2^31");
    }
    return static_cast<std::size_t>(v.GetNumberAsInt());
}

const char* missingDecoder(std::string_view extension) {
    if (extension == kDraco && !STRATA_DRACO) return "the Draco decoder (libdraco)";
    if (extension == kMeshopt && !STRATA_MESHOPT) return "the meshopt decoder (libmeshoptimizer)";
    if (extension == "EXT_texture_webp" && !STRATA_WEBP) return "the WebP decoder (libwebp)";
    if (extension == "EXT_texture_avif" && !STRATA_AVIF) return "the AVIF decoder (libavif)";
    if (extension == "KHR_texture_basisu") return "a Basis Universal decoder (Debian has none)";
    return nullptr;
}

}  // namespace strata::gltf
