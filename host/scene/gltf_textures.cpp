// glTF images, samplers, textures and texture references (textureInfo with
// KHR_texture_transform) -> Scene::images / Scene::textures / TextureSlot.
// Pixels are decoded by tinygltf's stb_image loader (Debian links the shared
// libstb): PNG 8/16-bit and JPEG (8-bit), always expanded to RGBA; WebP
// (EXT_texture_webp) by libwebp and AVIF (EXT_texture_avif) by libavif
// where strata has them (gltf_parse.cpp).
// KHR_texture_basisu images are never decoded: their texture's fallback
// `source` is used.
#include <cmath>
#include <sstream>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

// glTF 2.0 sampler enums (5.26).
constexpr int kNearest = 9728;
constexpr int kLinear = 9729;
constexpr int kClampToEdge = 33071;
constexpr int kMirroredRepeat = 33648;
constexpr int kRepeat = 10497;

std::string imageLabel(const tinygltf::Model& model, std::size_t index) {
    const tinygltf::Image& image = model.images[index];
    std::string label = "image " + std::to_string(index);
    if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
        label += " (" + quoted(image.uri) + ")";
    } else if (!image.name.empty()) {
        label += " (" + quoted(image.name) + ")";
    }
    return label;
}

Wrap convertWrap(const std::string& path, const std::string& label, const char* key, int mode) {
    switch (mode) {
        case kRepeat: return Wrap::Repeat;
        case kClampToEdge: return Wrap::ClampToEdge;
        case kMirroredRepeat: return Wrap::MirroredRepeat;
        default:
            fail(path, label + ": " + key + " " + std::to_string(mode) +
                           " is not REPEAT (10497), CLAMP_TO_EDGE (33071) or MIRRORED_REPEAT (33648)");
    }
}

// Number `key` of the JSON object `object`, or `fallback` when absent.
double numberOr(const std::string& path, const std::string& label, const tinygltf::Value& object,
                const char* key, double fallback) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) {
        fail(path, label + ": KHR_texture_transform." + key + " is not a finite number");
    }
    return v.GetNumberAsDouble();
}

// Array of two numbers `key` of `object`, or `fallback`.
glm::vec2 vec2Or(const std::string& path, const std::string& label, const tinygltf::Value& object,
                 const char* key, glm::vec2 fallback) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber()) {
        fail(path, label + ": KHR_texture_transform." + key + " is not an array of 2 numbers");
    }
    const glm::vec2 out(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
    if (!std::isfinite(out.x) || !std::isfinite(out.y)) {
        fail(path, label + ": KHR_texture_transform." + key + " is not finite");
    }
    return out;
}

// The `source` of extension `name` of texture `texture`, or -1 without one.
int extensionSource(const tinygltf::Texture& texture, const char* name) {
    const auto it = texture.extensions.find(name);
    if (it == texture.extensions.end() || !it->second.IsObject() || !it->second.Has("source") ||
        !it->second.Get("source").IsInt())
        return -1;
    return it->second.Get("source").GetNumberAsInt();
}

// A texture with neither a source nor an extension's (glTF 2.0 leaves it
// to other means): its slots read as absent.
bool sourceless(const tinygltf::Texture& texture) {
    return texture.source < 0 && extensionSource(texture, "EXT_texture_webp") < 0 &&
           extensionSource(texture, "EXT_texture_avif") < 0 && extensionSource(texture, "KHR_texture_basisu") < 0;
}

}  // namespace

int textureImage(const tinygltf::Model& model, int index, std::string& why) {
    const tinygltf::Texture& texture = model.textures[static_cast<std::size_t>(index)];
    const auto valid = [&](int image) { return image >= 0 && static_cast<std::size_t>(image) < model.images.size(); };
    const bool webp = texture.extensions.count("EXT_texture_webp") != 0;
    const bool avif = texture.extensions.count("EXT_texture_avif") != 0;
    const bool basisu = texture.extensions.count("KHR_texture_basisu") != 0;
    int image = texture.source;
    if (webp && STRATA_WEBP && valid(extensionSource(texture, "EXT_texture_webp"))) {
        image = extensionSource(texture, "EXT_texture_webp");
    } else if (avif && STRATA_AVIF && valid(extensionSource(texture, "EXT_texture_avif"))) {
        image = extensionSource(texture, "EXT_texture_avif");
    } else if (!valid(texture.source) && (webp || avif || basisu)) {
        why = webp   ? "its image is EXT_texture_webp, strata was built without the WebP decoder (libwebp), and it "
                       "has no fallback source"
              : avif ? "its image is EXT_texture_avif, strata was built without the AVIF decoder (libavif), and it "
                       "has no fallback source"
                     : "its image is KHR_texture_basisu, which strata cannot decode (Debian has no Basis Universal "
                       "decoder), and it has no fallback source";
        return -1;
    }
    if (!valid(image)) {
        why = "source image " + std::to_string(image) + " does not exist (" + std::to_string(model.images.size()) +
              " images)";
        return -1;
    }
    if (model.images[static_cast<std::size_t>(image)].image.empty()) {
        const tinygltf::Value& extras = model.images[static_cast<std::size_t>(image)].extras;
        why = extras.IsObject() && extras.Has(kUndecodable) && extras.Get(kUndecodable).IsString()
                  ? extras.Get(kUndecodable).Get<std::string>()
                  : "image " + std::to_string(image) + " has no decoded pixels (a WebP image needs libwebp, an AVIF "
                    "image libavif; KTX2 is not decoded)";
        return -1;
    }
    return image;
}

void warnTextureFallbacks(const std::string& path, const tinygltf::Model& model,
                          const std::vector<MaterialDesc>& materials) {
    std::vector<char> read(model.textures.size(), 0);
    for (const MaterialDesc& m : materials) {
        for (const MaterialDesc::NamedSlot& named : m.textureSlots()) {
            const TextureSlot* slot = named.slot;
            if (slot->used()) read[static_cast<std::size_t>(slot->texture)] = 1;
        }
    }
    std::size_t count = 0;
    for (std::size_t i = 0; i < model.textures.size(); ++i)
        count += read[i] && model.textures[i].extensions.count("KHR_texture_basisu") != 0;
    if (count > 0) {
        warn(path, std::to_string(count) + " texture(s) that materials read are KHR_texture_basisu, which strata "
                                           "cannot decode (Debian has no Basis Universal decoder): showing their "
                                           "fallback images");
    }
}

void convertTextures(const std::string& path, const tinygltf::Model& model, Scene& scene) {
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const tinygltf::Image& src = model.images[i];
        const std::size_t bytesPerTexel = src.bits == 16 ? 8 : 4;
        // Images left undecoded (KTX2, WebP without libwebp) stay empty; a
        // texture that needs one is refused where a material uses it.
        if (!src.image.empty() && (src.width < 1 || src.height < 1 || src.component != 4 ||
                                   (src.bits != 8 && src.bits != 16) ||
                                   src.image.size() != static_cast<std::size_t>(src.width) * src.height * bytesPerTexel)) {
            fail(path, imageLabel(model, i) + ": no decoded pixels (the file could not be read or decoded)");
        }
        TextureImage image;
        image.name = src.uri.empty() || src.uri.rfind("data:", 0) == 0 ? src.name : src.uri;
        image.width = src.width;
        image.height = src.height;
        image.bits = src.bits;
        image.data = src.image;
        scene.images.push_back(std::move(image));
    }
    std::size_t sourceless = 0;
    for (std::size_t i = 0; i < model.textures.size(); ++i) sourceless += gltf::sourceless(model.textures[i]);
    if (sourceless > 0)
        warn(path, std::to_string(sourceless) + " texture(s) without a source image: the materials read them as absent");
    for (std::size_t i = 0; i < model.textures.size(); ++i) {
        const tinygltf::Texture& src = model.textures[i];
        const std::string label = "texture " + std::to_string(i);
        Texture texture;
        std::string why;
        texture.image = textureImage(model, static_cast<int>(i), why);  // -1: refused where a material uses it
        if (src.sampler >= 0) {
            if (static_cast<std::size_t>(src.sampler) >= model.samplers.size()) {
                fail(path, label + ": sampler " + std::to_string(src.sampler) + " does not exist (" +
                               std::to_string(model.samplers.size()) + " samplers)");
            }
            const tinygltf::Sampler& s = model.samplers[static_cast<std::size_t>(src.sampler)];
            const std::string samplerLabel = "sampler " + std::to_string(src.sampler);
            texture.wrapS = convertWrap(path, samplerLabel, "wrapS", s.wrapS);
            texture.wrapT = convertWrap(path, samplerLabel, "wrapT", s.wrapT);
            if (s.magFilter != -1 && s.magFilter != kNearest && s.magFilter != kLinear) {
                fail(path, samplerLabel + ": magFilter " + std::to_string(s.magFilter) +
                               " is not NEAREST (9728) or LINEAR (9729)");
            }
            texture.nearest = s.magFilter == kNearest;
        }
        scene.textures.push_back(texture);
    }
}

TextureSlot convertTextureSlot(const std::string& path, const tinygltf::Model& model,
                               const std::string& label, int index, int texCoord,
                               const tinygltf::Value* transform) {
    TextureSlot slot;
    if (index == -1) return slot;  // tinygltf's value for an absent textureInfo
    if (index < 0 || static_cast<std::size_t>(index) >= model.textures.size()) {
        fail(path, label + ": texture " + std::to_string(index) + " does not exist (" +
                       std::to_string(model.textures.size()) + " textures)");
    }
    if (sourceless(model.textures[static_cast<std::size_t>(index)])) return slot;  // warned in convertTextures
    std::string why;
    if (textureImage(model, index, why) < 0) fail(path, label + ": texture " + std::to_string(index) + ": " + why);
    slot.texture = index;
    slot.texCoord = texCoord;
    if (transform && transform->IsObject()) {
        const std::string where = label + " texture " + std::to_string(index);
        slot.transform.offset = vec2Or(path, where, *transform, "offset", glm::vec2(0.0f));
        slot.transform.rotation =
            static_cast<float>(numberOr(path, where, *transform, "rotation", 0.0));
        slot.transform.scale = vec2Or(path, where, *transform, "scale", glm::vec2(1.0f));
        slot.texCoord = static_cast<int>(numberOr(path, where, *transform, "texCoord", texCoord));
    }
    if (slot.texCoord < 0) {
        fail(path, label + ": texCoord " + std::to_string(slot.texCoord) + " is not a TEXCOORD set (>= 0)");
    }
    return slot;
}

}  // namespace strata::gltf
