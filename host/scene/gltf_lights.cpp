// KHR_lights_punctual: lights referenced by nodes, placed in world space.
// Spec: github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_lights_punctual
#include <cmath>
#include <numbers>
#include <sstream>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

std::string lightLabel(const tinygltf::Model& model, int index) {
    std::string label = "light " + std::to_string(index);
    const auto& name = model.lights[static_cast<std::size_t>(index)].name;
    if (!name.empty()) label += " (" + quoted(name) + ")";
    return label;
}

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

int nodeLight(const std::string& path, const tinygltf::Model& model, int node,
              const std::string& nodeLabel) {
    const auto& ext = model.nodes[static_cast<std::size_t>(node)].extensions;
    const auto it = ext.find("KHR_lights_punctual");
    if (it == ext.end()) return -1;
    if (!it->second.IsObject() || !it->second.Has("light") || !it->second.Get("light").IsInt())
        fail(path, nodeLabel + ": KHR_lights_punctual.light is not an integer");
    const int light = it->second.Get("light").GetNumberAsInt();
    if (light < 0 || static_cast<std::size_t>(light) >= model.lights.size())
        fail(path, nodeLabel + ": light " + std::to_string(light) + " does not exist (" +
                       std::to_string(model.lights.size()) + " lights)");
    return light;
}

PunctualLight convertLight(const std::string& path, const tinygltf::Model& model, int index,
                           const glm::dmat4& world, const std::string& nodeLabel) {
    const tinygltf::Light& src = model.lights[static_cast<std::size_t>(index)];
    const std::string label = lightLabel(model, index);
    PunctualLight l;
    l.name = src.name;
    if (src.type == "point") l.type = PunctualLight::Type::Point;
    else if (src.type == "spot") l.type = PunctualLight::Type::Spot;
    else if (src.type == "directional") l.type = PunctualLight::Type::Directional;
    else fail(path, label + ": type " + quoted(src.type) + " is not point, spot or directional");

    if (!src.color.empty()) {
        if (src.color.size() != 3)
            fail(path, label + ": color has " + std::to_string(src.color.size()) + " numbers; expected 3");
        for (double c : src.color)
            if (!(c >= 0.0) || !std::isfinite(c))
                fail(path, label + ": color component " + number(c) + " is not a finite number >= 0");
        l.color = glm::vec3(src.color[0], src.color[1], src.color[2]);
    }
    if (!(src.intensity >= 0.0) || !std::isfinite(src.intensity))
        fail(path, label + ": intensity " + number(src.intensity) + " is not a finite number >= 0");
    l.intensity = static_cast<float>(src.intensity);

    if (l.type == PunctualLight::Type::Spot) {
        const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
        if (!(outer > 0.0 && outer <= std::numbers::pi / 2))
            fail(path, label + ": spot.outerConeAngle " + number(outer) + " is outside (0, pi/2]");
        if (!(inner >= 0.0 && inner < outer))
            fail(path, label + ": spot.innerConeAngle " + number(inner) + " is outside [0, outerConeAngle " +
                           number(outer) + ")");
        l.innerConeAngle = static_cast<float>(inner);
        l.outerConeAngle = static_cast<float>(outer);
    }

    // The light sits at the node's origin and points down its local -Z; scale is ignored.
    const glm::dvec3 position(world[3]);
    const glm::dvec3 dir = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double len = glm::length(dir);
    if (!(len > 0.0) || !std::isfinite(len) || !std::isfinite(position.x) || !std::isfinite(position.y) ||
        !std::isfinite(position.z))
        fail(path, label + " on " + nodeLabel + ": degenerate world transform (zero scale or not finite)");
    l.position = glm::vec3(position);
    l.direction = glm::vec3(dir / len);
    return l;
}

}  // namespace strata::gltf
