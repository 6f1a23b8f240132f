// Morph targets (glTF 2.0 3.7.2.2): each target of a primitive holds
// displacements of POSITION, NORMAL and TANGENT; a node shows its mesh
// displaced by sum_i weight_i * target_i, the weights from node.weights,
// else mesh.weights, else zeros. Applied once at load (the static pose).
#include <cmath>
#include <sstream>

#include "scene/gltf_deform.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;

// Target storages: core glTF FLOAT VEC3; KHR_mesh_quantization's table
// ("Extending Morph Target Attributes") adds BYTE and SHORT, normalized or
// not for POSITION, normalized for NORMAL and TANGENT.
const AccessorFormat kCore{TINYGLTF_TYPE_VEC3, {kFloat}, false};
const AccessorFormat kQuantizedPosition{TINYGLTF_TYPE_VEC3, {kFloat, kByte, kShort}, false};
const AccessorFormat kQuantizedDirection{TINYGLTF_TYPE_VEC3, {kFloat, kByte, kShort}, true};

std::vector<glm::vec3> readDisplacements(const std::string& path, const tinygltf::Model& model, int accessor,
                                         const std::string& use, const AccessorFormat& quantized,
                                         bool quantization, std::size_t vertexCount) {
    std::vector<glm::vec3> out =
        readFloats<3>(path, model, accessor, use, quantization ? quantized : kCore, quantization ? nullptr : &quantized);
    if (out.size() != vertexCount) {
        fail(path, use + " has " + std::to_string(out.size()) + " elements but POSITION has " +
                       std::to_string(vertexCount));
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z)) {
            fail(path, use + ": element " + std::to_string(i) + " is NaN or Inf");
        }
    }
    return out;
}

}  // namespace

std::vector<MorphTarget> readMorphTargets(const std::string& path, const tinygltf::Model& model,
                                          const tinygltf::Primitive& prim, const std::string& label,
                                          std::size_t vertexCount, bool quantization) {
    std::vector<MorphTarget> out(prim.targets.size());
    for (std::size_t t = 0; t < prim.targets.size(); ++t) {
        const std::string where = label + " target " + std::to_string(t) + " ";
        for (const auto& [semantic, accessor] : prim.targets[t]) {
            if (semantic == "POSITION") {
                out[t].positions = readDisplacements(path, model, accessor, where + semantic, kQuantizedPosition,
                                                     quantization, vertexCount);
            } else if (semantic == "NORMAL") {
                out[t].normals = readDisplacements(path, model, accessor, where + semantic, kQuantizedDirection,
                                                   quantization, vertexCount);
            } else if (semantic == "TANGENT") {
                out[t].tangents = readDisplacements(path, model, accessor, where + semantic, kQuantizedDirection,
                                                    quantization, vertexCount);
            }
        }
    }
    return out;
}

std::vector<double> morphWeights(const std::string& path, const tinygltf::Model& model, int node,
                                 const std::string& nodeLabel, const LocalMesh& mesh) {
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
    const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(n.mesh)];
    // glTF 2.0 3.7.2.2: every primitive of a mesh has the same number of targets.
    std::size_t targets = 0;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        const std::size_t count = mesh.primitives[p].targets.size();
        if (p > 0 && count != targets) {
            fail(path, meshLabel(model, n.mesh) + ": primitive " + std::to_string(mesh.primitives[p].index) +
                           " has " + std::to_string(count) + " morph target(s) but primitive " +
                           std::to_string(mesh.primitives[0].index) + " has " + std::to_string(targets) +
                           "; the primitives of a mesh have the same number");
        }
        targets = count;
    }
    const bool own = !n.weights.empty();
    const std::vector<double>& weights = own ? n.weights : m.weights;
    if (weights.empty()) return std::vector<double>(targets, 0.0);
    const std::string where = own ? nodeLabel + " weights" : meshLabel(model, n.mesh) + " weights";
    if (weights.size() != targets) {
        fail(path, where + " has " + std::to_string(weights.size()) + " number(s) but the mesh has " +
                       std::to_string(targets) + " morph target(s)");
    }
    for (const double w : weights) {
        if (!std::isfinite(w)) fail(path, where + " has a weight that is NaN or Inf");
    }
    return weights;
}

void applyMorph(const std::vector<double>& weights, LocalPrimitive& prim) {
    // Accumulated in double per vertex, then rounded once.
    auto displace = [&](auto& values, auto member, int components) {
        if (values.empty()) return;
        for (std::size_t i = 0; i < values.size(); ++i) {
            glm::dvec3 sum(values[i].x, values[i].y, values[i].z);
            for (std::size_t t = 0; t < weights.size(); ++t) {
                const std::vector<glm::vec3>& d = prim.targets[t].*member;
                if (weights[t] != 0.0 && !d.empty()) sum += weights[t] * glm::dvec3(d[i]);
            }
            for (int c = 0; c < components; ++c) values[i][c] = static_cast<float>(sum[c]);
        }
    };
    displace(prim.positions, &MorphTarget::positions, 3);
    displace(prim.normals, &MorphTarget::normals, 3);
    displace(prim.tangents, &MorphTarget::tangents, 3);  // w, the handedness, stays
}

std::string nodeName(const tinygltf::Model& model, int node) {
    std::string label = "node " + std::to_string(node);
    const auto& name = model.nodes[static_cast<std::size_t>(node)].name;
    if (!name.empty()) label += " (" + quoted(name) + ")";
    return label;
}

}  // namespace strata::gltf
