// EXT_mesh_gpu_instancing: a node's mesh placed once per instance, each by
// the node's world transform times the instance's T * R * S.
// Spec: github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_mesh_gpu_instancing
#include <algorithm>
#include <cmath>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

glm::dmat4 GpuInstances::local(std::size_t i) const {
    return trs(translation.empty() ? glm::dvec3(0.0) : glm::dvec3(translation[i]),
               rotation.empty() ? glm::dvec4(0.0, 0.0, 0.0, 1.0) : glm::dvec4(rotation[i]),
               scale.empty() ? glm::dvec3(1.0) : glm::dvec3(scale[i]));
}

std::size_t gpuInstanceCount(const tinygltf::Model& model, int node) {
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
    const auto it = n.extensions.find("EXT_mesh_gpu_instancing");
    if (it == n.extensions.end() || !it->second.IsObject() || !it->second.Has("attributes")) return 0;
    const tinygltf::Value& attributes = it->second.Get("attributes");
    std::size_t count = 0;
    for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"}) {
        if (!attributes.IsObject() || !attributes.Has(name) || !attributes.Get(name).IsInt()) continue;
        const int a = attributes.Get(name).GetNumberAsInt();
        if (a >= 0 && std::size_t(a) < model.accessors.size()) count = std::max(count, model.accessors[std::size_t(a)].count);
    }
    return count;
}

GpuInstances readGpuInstances(const std::string& path, const tinygltf::Model& model, int node,
                              const std::string& nodeLabel) {
    GpuInstances out;
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
    const auto it = n.extensions.find("EXT_mesh_gpu_instancing");
    if (it == n.extensions.end()) return out;
    const std::string where = nodeLabel + ": EXT_mesh_gpu_instancing";
    if (n.mesh < 0) fail(path, where + " on a node without a mesh");
    // A missing or empty attributes object names no attribute (the check below).
    const tinygltf::Value none;
    const bool hasAttributes = it->second.IsObject() && it->second.Has("attributes");
    const tinygltf::Value& attributes = hasAttributes ? it->second.Get("attributes") : none;
    // TRANSLATION and SCALE FLOAT VEC3; ROTATION a FLOAT or normalized
    // BYTE/SHORT VEC4 quaternion (the extension's table).
    static const AccessorFormat kVec3{TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, false};
    static const AccessorFormat kQuat{TINYGLTF_TYPE_VEC4, {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT}, true};
    auto accessor = [&](const char* name) -> int {
        if (!attributes.IsObject() || !attributes.Has(name)) return -1;
        const tinygltf::Value& v = attributes.Get(name);
        if (!v.IsInt()) fail(path, where + " " + name + " is not an accessor index");
        return v.GetNumberAsInt();
    };
    const int t = accessor("TRANSLATION"), r = accessor("ROTATION"), s = accessor("SCALE");
    if (t < 0 && r < 0 && s < 0) fail(path, where + " has none of TRANSLATION, ROTATION and SCALE");
    if (t >= 0) out.translation = readFloats<3>(path, model, t, where + " TRANSLATION", kVec3, nullptr);
    if (r >= 0) out.rotation = readFloats<4>(path, model, r, where + " ROTATION", kQuat, nullptr);
    if (s >= 0) out.scale = readFloats<3>(path, model, s, where + " SCALE", kVec3, nullptr);
    out.count = std::max({out.translation.size(), out.rotation.size(), out.scale.size()});
    auto checkCount = [&](std::size_t size, int index, const char* name) {
        if (index >= 0 && size != out.count)
            fail(path, where + " " + name + " has " + std::to_string(size) + " instances where another attribute has " +
                           std::to_string(out.count) + " (all must have the same count)");
    };
    checkCount(out.translation.size(), t, "TRANSLATION");
    checkCount(out.rotation.size(), r, "ROTATION");
    checkCount(out.scale.size(), s, "SCALE");
    auto finite = [](const auto& v) {
        for (int k = 0; k < v.length(); ++k)
            if (!std::isfinite(v[k])) return false;
        return true;
    };
    for (std::size_t i = 0; i < out.count; ++i) {
        const bool bad = (!out.translation.empty() && !finite(out.translation[i])) ||
                         (!out.scale.empty() && !finite(out.scale[i])) ||
                         (!out.rotation.empty() && (!finite(out.rotation[i]) || glm::dot(out.rotation[i], out.rotation[i]) == 0.0f));
        if (bad)
            fail(path, where + " instance " + std::to_string(i) +
                           ": not finite, or a rotation that is not a quaternion (length 0)");
    }
    return out;
}

}  // namespace strata::gltf
