// Skins (glTF 2.0 3.7.3): a skinned vertex is sum_i w_i (jointWorld_i *
// inverseBind_i) v over its JOINTS_n/WEIGHTS_n influences, normals by the
// inverse transposes of those matrices, tangents by the matrices; the
// skinned node's own transform is ignored. With morph targets (applied
// first), the node's static pose at load.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene/gltf_deform.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;

// glTF 2.0 3.7.2.1: JOINTS_n unsigned byte/short, WEIGHTS_n float or
// normalized unsigned byte/short, both VEC4.
const AccessorFormat kJoints{TINYGLTF_TYPE_VEC4, {kUByte, kUShort}, false};
const AccessorFormat kWeights{TINYGLTF_TYPE_VEC4, {kFloat, kUByte, kUShort}, true};

// glTF-Validator's tolerance for a vertex's weight sum: 2e-7 per non-zero
// weight (float32 rounding of each term).
constexpr double kWeightSumTolerancePerWeight = 2e-7;

std::string skinName(const tinygltf::Model& model, int skin) {
    std::string label = "skin " + std::to_string(skin);
    const auto& name = model.skins[static_cast<std::size_t>(skin)].name;
    if (!name.empty()) label += " (" + quoted(name) + ")";
    return label;
}

// (m^-1)^T of the linear part; the cofactor matrix (det * m^-T, signed like
// it) where m is singular, as for a node's normals.
glm::dmat3 normalMatrix(const glm::dmat4& m) {
    const glm::dmat3 linear(m);
    const double det = glm::determinant(linear);
    if (det != 0.0 && std::isfinite(det)) return glm::transpose(glm::inverse(linear));
    return glm::dmat3(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                      glm::cross(linear[0], linear[1]));
}

}  // namespace

std::vector<SkinInfluences> readSkinInfluences(const std::string& path, const tinygltf::Model& model,
                                               const tinygltf::Primitive& prim, const std::string& label,
                                               std::size_t vertexCount, const std::vector<std::string>& inStream,
                                               const std::vector<SkinInfluences>& decoded) {
    const auto streamed = [&](const std::string& name) {
        return std::find(inStream.begin(), inStream.end(), name) != inStream.end();
    };
    std::vector<SkinInfluences> out;
    for (int set = 0;; ++set) {
        const std::string joints = "JOINTS_" + std::to_string(set), weights = "WEIGHTS_" + std::to_string(set);
        const auto j = prim.attributes.find(joints), w = prim.attributes.find(weights);
        if (j == prim.attributes.end() && w == prim.attributes.end()) break;
        if (j == prim.attributes.end() || w == prim.attributes.end()) {
            fail(path, label + ": has " + (j == prim.attributes.end() ? weights : joints) + " without " +
                           (j == prim.attributes.end() ? joints : weights));
        }
        const std::string jointsUse = label + " " + joints, weightsUse = label + " " + weights;
        SkinInfluences s;
        if (streamed(joints)) {
            s.joints = decoded.at(static_cast<std::size_t>(set)).joints;
        } else {
            if (j->second >= 0 && static_cast<std::size_t>(j->second) < model.accessors.size() &&
                model.accessors[static_cast<std::size_t>(j->second)].normalized) {
                fail(path, "accessor " + std::to_string(j->second) + " (" + jointsUse +
                               ") is normalized; joint indices are integers");
            }
            for (const glm::vec4& x : readFloats<4>(path, model, j->second, jointsUse, kJoints, nullptr))
                s.joints.push_back(glm::uvec4(x));
        }
        s.weights = streamed(weights) ? decoded.at(static_cast<std::size_t>(set)).weights
                                      : readFloats<4>(path, model, w->second, weightsUse, kWeights, nullptr);
        for (const auto& [n, name] : {std::pair{s.joints.size(), joints}, std::pair{s.weights.size(), weights}}) {
            if (n != vertexCount) {
                fail(path, label + ": " + name + " has " + std::to_string(n) + " elements but POSITION has " +
                               std::to_string(vertexCount));
            }
        }
        for (std::size_t v = 0; v < vertexCount; ++v) {
            for (int k = 0; k < 4; ++k) {
                const float x = s.weights[v][k];
                if (!(x >= 0.0f) || !std::isfinite(x)) {
                    std::ostringstream msg;
                    msg << weightsUse << ": vertex " << v << " has weight " << x
                        << "; weights are finite and not negative";
                    fail(path, msg.str());
                }
            }
        }
        out.push_back(std::move(s));
    }
    return out;
}

glm::dmat4 nodeWorld(const std::string& path, const tinygltf::Model& model, int node) {
    const std::size_t count = model.nodes.size();
    std::vector<int> parent(count, -1);
    for (std::size_t p = 0; p < count; ++p) {
        for (const int c : model.nodes[p].children) {
            if (c >= 0 && static_cast<std::size_t>(c) < count && parent[static_cast<std::size_t>(c)] < 0)
                parent[static_cast<std::size_t>(c)] = static_cast<int>(p);
        }
    }
    std::vector<int> chain;  // node, its parent, ..., a root
    for (int n = node; n >= 0; n = parent[static_cast<std::size_t>(n)]) {
        if (chain.size() == count) fail(path, nodeName(model, node) + " is its own ancestor (cycle in the node hierarchy)");
        chain.push_back(n);
    }
    glm::dmat4 world(1.0);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) world = world * nodeTransform(path, model, *it);
    return world;
}

NodePose::NodePose(const std::string& path, const tinygltf::Model& model, int node, const LocalMesh& mesh)
    : path_(path), label_(nodeName(model, node)) {
    weights_ = morphWeights(path, model, node, label_, mesh);
    const int skin = model.nodes[static_cast<std::size_t>(node)].skin;
    if (skin < 0) return;
    if (static_cast<std::size_t>(skin) >= model.skins.size()) {
        fail(path, label_ + ": skin " + std::to_string(skin) + " does not exist (" +
                       std::to_string(model.skins.size()) + " skins)");
    }
    const tinygltf::Skin& s = model.skins[static_cast<std::size_t>(skin)];
    const std::string label = skinName(model, skin);
    label_ += " with " + label;
    if (s.joints.empty()) fail(path, label + " has no joints");
    std::vector<glm::mat4> inverseBind;
    if (s.inverseBindMatrices >= 0) {
        inverseBind = readMatrices(path, model, s.inverseBindMatrices, label + " inverseBindMatrices");
        if (inverseBind.size() < s.joints.size()) {
            fail(path, label + ": inverseBindMatrices has " + std::to_string(inverseBind.size()) +
                           " matrices for " + std::to_string(s.joints.size()) + " joints");
        }
    }
    for (std::size_t i = 0; i < s.joints.size(); ++i) {
        const int joint = s.joints[i];
        if (joint < 0 || static_cast<std::size_t>(joint) >= model.nodes.size()) {
            fail(path, label + ": joint " + std::to_string(i) + " is node " + std::to_string(joint) +
                           ", which does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
        }
        glm::dmat4 bind(1.0);
        if (!inverseBind.empty()) {
            bind = glm::dmat4(inverseBind[i]);
            const double det = glm::determinant(bind);
            if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
                std::ostringstream msg;
                msg << label << ": inverseBindMatrices[" << i << "] is not invertible (determinant " << det << ")";
                fail(path, msg.str());
            }
        }
        joints_.push_back(nodeWorld(path, model, joint) * bind);
        normalJoints_.push_back(normalMatrix(joints_.back()));
    }
}

const LocalPrimitive& NodePose::apply(const LocalPrimitive& prim, LocalPrimitive& scratch) const {
    bool morph = false;
    for (const double w : weights_) morph = morph || w != 0.0;
    if (!morph && !skinned()) return prim;
    scratch = prim;
    if (morph) applyMorph(weights_, scratch);
    if (!skinned()) return scratch;
    const std::string where = label_ + ", primitive " + std::to_string(prim.index);
    if (prim.skin.empty()) fail(path_, where + ": has no JOINTS_0 and WEIGHTS_0");
    std::size_t offOne = 0;
    for (std::size_t v = 0; v < scratch.positions.size(); ++v) {
        glm::dvec3 p(0.0), n(0.0), t(0.0);
        double sum = 0.0;
        int nonZero = 0;
        for (std::size_t set = 0; set < prim.skin.size(); ++set) {
            for (int k = 0; k < 4; ++k) {
                const double w = prim.skin[set].weights[v][k];
                if (w == 0.0) continue;
                const std::uint32_t j = prim.skin[set].joints[v][k];
                if (j >= joints_.size()) {
                    fail(path_, where + ": vertex " + std::to_string(v) + " has joint index " + std::to_string(j) +
                                    " (JOINTS_" + std::to_string(set) + "), out of range: the skin has " +
                                    std::to_string(joints_.size()) + " joints");
                }
                sum += w;
                ++nonZero;
                p += w * glm::dvec3(joints_[j] * glm::dvec4(glm::dvec3(scratch.positions[v]), 1.0));
                if (!scratch.normals.empty()) n += w * (normalJoints_[j] * glm::dvec3(scratch.normals[v]));
                if (!scratch.tangents.empty()) t += w * (glm::dmat3(joints_[j]) * glm::dvec3(scratch.tangents[v]));
            }
        }
        if (!(sum > 0.0)) fail(path_, where + ": vertex " + std::to_string(v) + " has no joint weight above 0");
        offOne += std::abs(sum - 1.0) > kWeightSumTolerancePerWeight * nonZero;
        scratch.positions[v] = glm::vec3(p / sum);
        if (!scratch.normals.empty()) scratch.normals[v] = glm::vec3(n / sum);
        if (!scratch.tangents.empty()) scratch.tangents[v] = glm::vec4(glm::vec3(t / sum), scratch.tangents[v].w);
    }
    if (offOne > 0) {
        warn(path_, where + ": " + std::to_string(offOne) +
                        " vertices have joint weights whose sum is off 1 by more than 2e-7 per weight; renormalized");
    }
    return scratch;
}

}  // namespace strata::gltf
