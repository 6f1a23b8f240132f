// KHR_materials_variants: the file's named variants (the root extension's
// `variants`) and, per primitive, the `mappings` from variants to materials.
// A chosen variant rewrites each mapped primitive's material before the
// scene is built; without one, primitives keep their own material.
#include <algorithm>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

constexpr const char* kExtension = "KHR_materials_variants";

// The integer at `value`, or fail with `what`.
int integerAt(const std::string& path, const tinygltf::Value& value, const std::string& what) {
    if (!value.IsInt()) fail(path, what + " is not an integer");
    return value.GetNumberAsInt();
}

}  // namespace

std::vector<std::string> readVariants(const std::string& path, const tinygltf::Model& model) {
    const auto it = model.extensions.find(kExtension);
    if (it == model.extensions.end()) return {};
    const std::string label = std::string(kExtension);
    if (!it->second.IsObject() || !it->second.Has("variants") || !it->second.Get("variants").IsArray())
        fail(path, label + " has no variants array");
    const tinygltf::Value& list = it->second.Get("variants");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
        const tinygltf::Value& v = list.Get(static_cast<int>(i));
        if (!v.IsObject() || !v.Has("name") || !v.Get("name").IsString())
            fail(path, label + " variant " + std::to_string(i) + " has no name");
        out.push_back(v.Get("name").Get<std::string>());
    }
    return out;
}

void applyVariant(const std::string& path, tinygltf::Model& model, const std::vector<std::string>& variants,
                  const std::string& name) {
    int chosen = -1;
    if (!name.empty()) {
        const auto it = std::find(variants.begin(), variants.end(), name);
        if (it == variants.end()) {
            std::string list;
            for (const std::string& v : variants) list += (list.empty() ? "" : ", ") + quoted(v);
            fail(path, "--variant " + quoted(name) + " is not a variant of the file; " +
                           (variants.empty() ? std::string("it has none (no ") + kExtension + ")"
                                             : "its variants: " + list));
        }
        chosen = static_cast<int>(it - variants.begin());
    }
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& prim = model.meshes[m].primitives[p];
            const auto ext = prim.extensions.find(kExtension);
            if (ext == prim.extensions.end()) continue;
            const std::string label = meshLabel(model, static_cast<int>(m)) + " primitive " + std::to_string(p) +
                                      " " + kExtension;
            if (!ext->second.IsObject() || !ext->second.Has("mappings") || !ext->second.Get("mappings").IsArray())
                fail(path, label + " has no mappings array");
            const tinygltf::Value& mappings = ext->second.Get("mappings");
            // Every mapping is checked, whichever variant is chosen.
            for (std::size_t k = 0; k < mappings.ArrayLen(); ++k) {
                const tinygltf::Value& mapping = mappings.Get(static_cast<int>(k));
                const std::string where = label + " mapping " + std::to_string(k);
                if (!mapping.IsObject() || !mapping.Has("material") || !mapping.Has("variants") ||
                    !mapping.Get("variants").IsArray())
                    fail(path, where + " needs a material and a variants array");
                const int material = integerAt(path, mapping.Get("material"), where + " material");
                if (material < 0 || static_cast<std::size_t>(material) >= model.materials.size()) {
                    fail(path, where + ": material " + std::to_string(material) + " does not exist (" +
                                   std::to_string(model.materials.size()) + " materials)");
                }
                const tinygltf::Value& list = mapping.Get("variants");
                for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
                    const int v = integerAt(path, list.Get(static_cast<int>(i)), where + " variant");
                    if (v < 0 || static_cast<std::size_t>(v) >= variants.size()) {
                        fail(path, where + ": variant " + std::to_string(v) + " does not exist (" +
                                       std::to_string(variants.size()) + " variants)");
                    }
                    if (v == chosen) prim.material = material;
                }
            }
        }
    }
}

}  // namespace strata::gltf
