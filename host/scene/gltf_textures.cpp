// glTF images, samplers, textures and texture references (textureInfo with
// KHR_texture_transform) -> Scene::images / Scene::textures / TextureSlot.
// Pixels are decoded by tinygltf's stb_image loader (Debian links the shared
// libstb): PNG 8/16-bit and JPEG (8-bit), always expanded to RGBA.
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

}  // namespace

void convertTextures(const std::string& path, const tinygltf::Model& model, Scene& scene) {
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const tinygltf::Image& src = model.images[i];
        const std::size_t bytesPerTexel = src.bits == 16 ? 8 : 4;
        if (src.image.empty() || src.width < 1 || src.height < 1 || src.component != 4 ||
            (src.bits != 8 && src.bits != 16) ||
            src.image.size() != static_cast<std::size_t>(src.width) * src.height * bytesPerTexel) {
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
    for (std::size_t i = 0; i < model.textures.size(); ++i) {
        const tinygltf::Texture& src = model.textures[i];
        const std::string label = "texture " + std::to_string(i);
        if (src.source < 0 || static_cast<std::size_t>(src.source) >= model.images.size()) {
            fail(path, label + ": source image " + std::to_string(src.source) + " does not exist (" +
                           std::to_string(model.images.size()) +
                           " images; image extensions such as KHR_texture_basisu are not supported)");
        }
        Texture texture;
        texture.image = src.source;
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
