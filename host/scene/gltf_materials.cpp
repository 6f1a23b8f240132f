// glTF material -> MaterialDesc: core pbrMetallicRoughness factors plus
// KHR_materials_emissive_strength, _ior, _transmission, _specular (factor,
// colour, textures), _unlit, _volume, _clearcoat, _sheen, _iridescence,
// _diffuse_transmission and _anisotropy, and the texture
// slots (occlusionTexture is not read: a path tracer computes occlusion).
// Factors outside their range are errors.
#include <array>
#include <cmath>
#include <set>
#include <sstream>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

std::string materialLabel(const tinygltf::Model& model, int index) {
    std::string label = "material " + std::to_string(index);
    const auto& name = model.materials[static_cast<std::size_t>(index)].name;
    if (!name.empty()) label += " (" + quoted(name) + ")";
    return label;
}

// The number `key` of extension object `extension` of `material`, or
// `fallback` when the extension or the key is absent.
double extensionNumber(const std::string& path, const std::string& label,
                       const tinygltf::Material& material, const char* extension, const char* key,
                       double fallback) {
    const auto it = material.extensions.find(extension);
    if (it == material.extensions.end() || !it->second.IsObject() || !it->second.Has(key)) {
        return fallback;
    }
    const tinygltf::Value& value = it->second.Get(key);
    if (!value.IsNumber()) fail(path, label + ": " + extension + "." + key + " is not a number");
    return value.GetNumberAsDouble();
}

// The colour `key` of extension object `extension`: three numbers in [0, 1]
// (in [0, inf) when not `unit`), or `fallback` when absent.
glm::vec3 extensionColor(const std::string& path, const std::string& label, const tinygltf::Material& material,
                         const char* extension, const char* key, glm::vec3 fallback, bool unit = true) {
    const auto it = material.extensions.find(extension);
    if (it == material.extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& c = it->second.Get(key);
    glm::vec3 color(0.0f);
    bool ok = c.IsArray() && c.ArrayLen() == 3;
    for (int k = 0; ok && k < 3; ++k) {
        const double v = c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : -1.0;
        ok = v >= 0.0 && (v <= 1.0 || (!unit && std::isfinite(v)));
        color[k] = static_cast<float>(v);
    }
    if (!ok)
        fail(path, label + ": " + extension + "." + key + " is not three numbers in " + (unit ? "[0, 1]" : "[0, inf)"));
    return color;
}

// The KHR_texture_transform object of a textureInfo's extensions, or nullptr.
const tinygltf::Value* textureTransform(const tinygltf::ExtensionMap& extensions) {
    const auto it = extensions.find("KHR_texture_transform");
    return it == extensions.end() ? nullptr : &it->second;
}

template <class Info>
TextureSlot slotOf(const std::string& path, const tinygltf::Model& model, const std::string& label,
                   const char* name, const Info& info) {
    return convertTextureSlot(path, model, label + " " + name, info.index, info.texCoord,
                              textureTransform(info.extensions));
}

// Texture `key` of extension object `extension` (a textureInfo kept as
// JSON), e.g. KHR_materials_transmission.transmissionTexture; an empty slot
// when absent. `scale`, when not null, receives a normalTextureInfo's scale
// (default 1).
TextureSlot extensionSlot(const std::string& path, const tinygltf::Model& model, const std::string& label,
                          const tinygltf::Material& material, const char* extension, const char* key,
                          float* scale = nullptr) {
    const auto it = material.extensions.find(extension);
    if (it == material.extensions.end() || !it->second.Has(key)) return {};
    const tinygltf::Value& info = it->second.Get(key);
    const std::string where = label + " " + key;
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) {
        fail(path, where + " has no integer index");
    }
    if (scale) {
        const tinygltf::Value* s = info.Has("scale") ? &info.Get("scale") : nullptr;
        if (s && !s->IsNumber()) fail(path, where + ".scale is not a number");
        *scale = s ? static_cast<float>(s->GetNumberAsDouble()) : 1.0f;
    }
    const int texCoord = info.Has("texCoord") && info.Get("texCoord").IsInt()
                             ? info.Get("texCoord").GetNumberAsInt()
                             : 0;
    const tinygltf::Value* transform = nullptr;
    if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform")) {
        transform = &info.Get("extensions").Get("KHR_texture_transform");
    }
    return convertTextureSlot(path, model, where, info.Get("index").GetNumberAsInt(), texCoord,
                              transform);
}

// MaterialDesc::uvSets of `m`: {0, 1}, or the distinct TEXCOORD sets its
// texture slots read when one is above 1; more than two is an error.
std::array<int, 2> uvSets(const std::string& path, const std::string& label, const MaterialDesc& m) {
    std::set<int> sets;
    for (const MaterialDesc::NamedSlot& named : m.textureSlots()) {
        const TextureSlot* slot = named.slot;
        if (slot->used()) sets.insert(slot->texCoord);
    }
    if (sets.empty() || *sets.rbegin() <= 1) return {0, 1};
    if (sets.size() > 2) {
        std::string names;
        for (const int s : sets) names += (names.empty() ? "" : ", ") + std::string("TEXCOORD_") + std::to_string(s);
        fail(path, label + ": its textures read " + std::to_string(sets.size()) + " texture coordinate sets (" +
                       names + "); strata interpolates at most two per material");
    }
    return {*sets.begin(), *sets.rbegin()};
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

void warnUnreadMaterialTextures(const std::string& path, const tinygltf::Model& model) {
    std::size_t count = 0;
    for (const tinygltf::Material& material : model.materials) {
        const auto it = material.extensions.find("KHR_materials_volume_scatter");
        count += it != material.extensions.end() && it->second.IsObject() && it->second.Has("multiscatterTexture");
    }
    if (count > 0) {
        warn(path, std::to_string(count) + " material(s) have KHR_materials_volume_scatter.multiscatterTexture, which "
                                           "strata does not read: their media scatter by multiscatterColor alone");
    }
}

MaterialDesc convertMaterial(const std::string& path, const tinygltf::Model& model, int index) {
    const tinygltf::Material& src = model.materials[static_cast<std::size_t>(index)];
    const std::string label = materialLabel(model, index);
    MaterialDesc m;
    m.name = src.name;

    const auto& pbr = src.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4) {
        fail(path, label + ": baseColorFactor has " + std::to_string(pbr.baseColorFactor.size()) +
                       " numbers; expected 4");
    }
    m.baseColor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                            pbr.baseColorFactor[3]);
    m.metallic = static_cast<float>(pbr.metallicFactor);
    m.roughness = static_cast<float>(pbr.roughnessFactor);

    if (!src.emissiveFactor.empty()) {
        if (src.emissiveFactor.size() != 3) {
            fail(path, label + ": emissiveFactor has " + std::to_string(src.emissiveFactor.size()) +
                           " numbers; expected 3");
        }
        m.emissiveFactor =
            glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
    }
    const double strength = extensionNumber(path, label, src, "KHR_materials_emissive_strength",
                                            "emissiveStrength", 1.0);
    if (!(strength >= 0.0) || !std::isfinite(strength)) {
        fail(path, label + ": KHR_materials_emissive_strength.emissiveStrength " +
                       formatNumber(strength) + " is not a finite number >= 0");
    }
    m.emissiveStrength = static_cast<float>(strength);

    // KHR_materials_ior allows 0 (no refraction) or >= 1.
    const double ior = extensionNumber(path, label, src, "KHR_materials_ior", "ior", 1.5);
    if (!std::isfinite(ior) || !(ior == 0.0 || ior >= 1.0)) {
        fail(path,
             label + ": KHR_materials_ior.ior " + formatNumber(ior) + " is neither 0 nor >= 1");
    }
    m.ior = static_cast<float>(ior);

    auto unitFactor = [&](const char* extension, const char* key, double fallback) {
        const double v = extensionNumber(path, label, src, extension, key, fallback);
        if (!(v >= 0.0 && v <= 1.0)) {
            fail(path, label + ": " + extension + "." + key + " " + formatNumber(v) +
                           " is not in [0, 1]");
        }
        return static_cast<float>(v);
    };
    m.transmission = unitFactor("KHR_materials_transmission", "transmissionFactor", 0.0);
    m.specular = unitFactor("KHR_materials_specular", "specularFactor", 1.0);
    m.specularColor =
        extensionColor(path, label, src, "KHR_materials_specular", "specularColorFactor", glm::vec3(1.0f), false);

    if (const auto unlit = src.extensions.find("KHR_materials_unlit"); unlit != src.extensions.end()) {
        if (!unlit->second.IsObject()) fail(path, label + ": KHR_materials_unlit is not a JSON object");
        m.unlit = true;
    }
    m.thickness = static_cast<float>(extensionNumber(path, label, src, "KHR_materials_volume", "thicknessFactor", 0.0));
    if (!(m.thickness >= 0.0f) || !std::isfinite(m.thickness))
        fail(path, label + ": KHR_materials_volume.thicknessFactor " + formatNumber(m.thickness) +
                       " is not a finite number >= 0");
    const double distance = extensionNumber(path, label, src, "KHR_materials_volume", "attenuationDistance",
                                            std::numeric_limits<double>::infinity());
    if (!(distance > 0.0))
        fail(path, label + ": KHR_materials_volume.attenuationDistance " + formatNumber(distance) + " is not > 0");
    m.attenuationDistance = static_cast<float>(distance);
    m.attenuationColor = extensionColor(path, label, src, "KHR_materials_volume", "attenuationColor", glm::vec3(1.0f));
    m.doubleSided = src.doubleSided;
    if (src.alphaMode == "OPAQUE") {
        m.alphaMode = MaterialDesc::AlphaMode::Opaque;
    } else if (src.alphaMode == "MASK") {
        m.alphaMode = MaterialDesc::AlphaMode::Mask;
    } else if (src.alphaMode == "BLEND") {
        m.alphaMode = MaterialDesc::AlphaMode::Blend;
    } else {
        fail(path,
             label + ": alphaMode " + quoted(src.alphaMode) + " is not OPAQUE, MASK or BLEND");
    }
    m.alphaCutoff = static_cast<float>(src.alphaCutoff);

    m.baseColorTexture = slotOf(path, model, label, "baseColorTexture", pbr.baseColorTexture);
    m.metallicRoughnessTexture =
        slotOf(path, model, label, "metallicRoughnessTexture", pbr.metallicRoughnessTexture);
    m.normalTexture = slotOf(path, model, label, "normalTexture", src.normalTexture);
    m.normalScale = static_cast<float>(src.normalTexture.scale);
    m.emissiveTexture = slotOf(path, model, label, "emissiveTexture", src.emissiveTexture);
    m.transmissionTexture =
        extensionSlot(path, model, label, src, "KHR_materials_transmission", "transmissionTexture");

    const char* coat = "KHR_materials_clearcoat";
    m.clearcoat = unitFactor(coat, "clearcoatFactor", 0.0);
    m.clearcoatRoughness = unitFactor(coat, "clearcoatRoughnessFactor", 0.0);
    m.clearcoatTexture = extensionSlot(path, model, label, src, coat, "clearcoatTexture");
    m.clearcoatRoughnessTexture = extensionSlot(path, model, label, src, coat, "clearcoatRoughnessTexture");
    m.clearcoatNormalTexture =
        extensionSlot(path, model, label, src, coat, "clearcoatNormalTexture", &m.clearcoatNormalScale);

    const char* sheen = "KHR_materials_sheen";
    m.sheenColor = extensionColor(path, label, src, sheen, "sheenColorFactor", glm::vec3(0.0f));
    m.sheenRoughness = unitFactor(sheen, "sheenRoughnessFactor", 0.0);
    m.sheenColorTexture = extensionSlot(path, model, label, src, sheen, "sheenColorTexture");
    m.sheenRoughnessTexture = extensionSlot(path, model, label, src, sheen, "sheenRoughnessTexture");
    m.specularTexture = extensionSlot(path, model, label, src, "KHR_materials_specular", "specularTexture");
    m.specularColorTexture = extensionSlot(path, model, label, src, "KHR_materials_specular", "specularColorTexture");
    const char* film = "KHR_materials_iridescence";
    m.iridescence = unitFactor(film, "iridescenceFactor", 0.0);
    auto nonNegative = [&](const char* key, double fallback) {
        const double v = extensionNumber(path, label, src, film, key, fallback);
        if (!(v >= 0.0) || !std::isfinite(v))
            fail(path, label + ": " + film + "." + key + " " + formatNumber(v) + " is not a finite number >= 0");
        return static_cast<float>(v);
    };
    m.iridescenceIor = nonNegative("iridescenceIor", 1.3);
    if (!(m.iridescenceIor >= 1.0f))
        fail(path, label + ": " + film + ".iridescenceIor " + formatNumber(m.iridescenceIor) + " is below 1");
    m.iridescenceThicknessMin = nonNegative("iridescenceThicknessMinimum", 100.0);
    m.iridescenceThicknessMax = nonNegative("iridescenceThicknessMaximum", 400.0);
    m.iridescenceTexture = extensionSlot(path, model, label, src, film, "iridescenceTexture");
    m.iridescenceThicknessTexture = extensionSlot(path, model, label, src, film, "iridescenceThicknessTexture");
    const char* diffuse = "KHR_materials_diffuse_transmission";
    m.diffuseTransmission = unitFactor(diffuse, "diffuseTransmissionFactor", 0.0);
    m.diffuseTransmissionColor =
        extensionColor(path, label, src, diffuse, "diffuseTransmissionColorFactor", glm::vec3(1.0f));
    m.diffuseTransmissionTexture = extensionSlot(path, model, label, src, diffuse, "diffuseTransmissionTexture");
    m.diffuseTransmissionColorTexture =
        extensionSlot(path, model, label, src, diffuse, "diffuseTransmissionColorTexture");
    const char* anisotropy = "KHR_materials_anisotropy";
    m.anisotropyStrength = unitFactor(anisotropy, "anisotropyStrength", 0.0);
    const double rotation = extensionNumber(path, label, src, anisotropy, "anisotropyRotation", 0.0);
    if (!std::isfinite(rotation))
        fail(path, label + ": " + anisotropy + ".anisotropyRotation " + formatNumber(rotation) + " is not finite");
    m.anisotropyRotation = static_cast<float>(rotation);
    m.anisotropyTexture = extensionSlot(path, model, label, src, anisotropy, "anisotropyTexture");
    // KHR_materials_volume_scatter (a draft): multiscatterColor, which some
    // exporters spell multiscatterColorFactor, and scatterAnisotropy in (-1, 1).
    const char* scatter = "KHR_materials_volume_scatter";
    m.multiscatterColor = extensionColor(path, label, src, scatter, "multiscatterColorFactor", glm::vec3(0.0f));
    m.multiscatterColor = extensionColor(path, label, src, scatter, "multiscatterColor", m.multiscatterColor);
    const double g = extensionNumber(path, label, src, scatter, "scatterAnisotropy", 0.0);
    if (!(g > -1.0 && g < 1.0))
        fail(path, label + ": " + scatter + ".scatterAnisotropy " + formatNumber(g) + " is not in (-1, 1)");
    m.scatterAnisotropy = static_cast<float>(g);
    const double dispersion = extensionNumber(path, label, src, "KHR_materials_dispersion", "dispersion", 0.0);
    if (!(dispersion >= 0.0) || !std::isfinite(dispersion))
        fail(path, label + ": KHR_materials_dispersion.dispersion " + formatNumber(dispersion) +
                       " is not a finite number >= 0");
    m.dispersion = static_cast<float>(dispersion);
    m.uvSets = uvSets(path, label, m);
    return m;
}

}  // namespace strata::gltf
