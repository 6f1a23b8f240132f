// glTF nodes (glTF 2.0 section 3.5): a node's own transform, checked, and the
// walk of a scene's hierarchy (disjoint trees, no cycle) with each node's
// world transform.
#include <cmath>

#include "scene/gltf_deform.h"
#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

NodeTrs nodeTrs(const std::string& path, const tinygltf::Model& model, int index) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(index)];
    auto checkSize = [&](const std::vector<double>& v, std::size_t n, const char* what) {
        if (!v.empty() && v.size() != n) {
            fail(path, nodeName(model, index) + ": " + what + " has " + std::to_string(v.size()) +
                           " numbers; expected " + std::to_string(n));
        }
    };
    checkSize(node.translation, 3, "translation");
    checkSize(node.rotation, 4, "rotation");
    checkSize(node.scale, 3, "scale");
    NodeTrs trs;
    if (!node.rotation.empty()) {
        trs.rotation = glm::dvec4(node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]);
        const double len = std::sqrt(glm::dot(trs.rotation, trs.rotation));
        if (!(len > 0.0) || !std::isfinite(len)) {
            fail(path, nodeName(model, index) + ": rotation is not a valid quaternion");
        }
    }
    if (!node.scale.empty()) trs.scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    if (!node.translation.empty())
        trs.translation = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    return trs;
}

glm::dmat4 nodeTransform(const std::string& path, const tinygltf::Model& model, int index) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(index)];
    if (node.matrix.empty()) {
        const NodeTrs n = nodeTrs(path, model, index);
        return trs(n.translation, n.rotation, n.scale);
    }
    if (node.matrix.size() != 16) {
        fail(path, nodeName(model, index) + ": matrix has " + std::to_string(node.matrix.size()) +
                       " numbers; expected 16");
    }
    glm::dmat4 m(1.0);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
    }
    return m;
}

// KHR_node_visibility's `visible` of a node (true without the extension).
bool nodeVisible(const std::string& path, const tinygltf::Model& model, int index) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(index)];
    const auto it = node.extensions.find("KHR_node_visibility");
    if (it == node.extensions.end() || !it->second.IsObject() || !it->second.Has("visible")) return true;
    const tinygltf::Value& v = it->second.Get("visible");
    if (!v.IsBool()) fail(path, nodeName(model, index) + ": KHR_node_visibility.visible is not a boolean");
    return v.Get<bool>();
}

std::vector<NodeVisit> walkNodes(const std::string& path, const tinygltf::Model& model, int sceneIndex,
                                 const std::function<glm::dmat4(int node, int parent)>& local) {
    const tinygltf::Scene& s = model.scenes[static_cast<std::size_t>(sceneIndex)];
    const std::size_t count = model.nodes.size();
    const auto valid = [&](int node) { return node >= 0 && static_cast<std::size_t>(node) < count; };
    std::vector<char> onPath(count, 0), entered(count, 0);
    struct Frame {
        int node;
        glm::dmat4 world;
        std::size_t nextChild;
        bool visible;
    };
    std::vector<Frame> stack;
    std::vector<NodeVisit> visits;
    auto enter = [&](int node, const glm::dmat4& parent, int parentNode, bool parentVisible) {
        if (onPath[static_cast<std::size_t>(node)]) {
            fail(path, nodeName(model, node) + " is its own ancestor (cycle in the node hierarchy)");
        }
        // The hierarchy is a set of disjoint trees: a node reached twice
        // has two parents (or is a root and a child), and such a graph can
        // multiply the instances exponentially.
        if (entered[static_cast<std::size_t>(node)]) {
            fail(path, nodeName(model, node) + " is reached twice from scene " + std::to_string(sceneIndex) +
                           " (a node may have one parent, and a root none)");
        }
        entered[static_cast<std::size_t>(node)] = 1;
        const glm::dmat4 world = parent * local(node, parentNode);
        const bool visible = parentVisible && nodeVisible(path, model, node);
        visits.push_back({node, world, visible});
        onPath[static_cast<std::size_t>(node)] = 1;
        stack.push_back({node, world, 0, visible});
    };
    for (const int root : s.nodes) {
        if (!valid(root)) {
            fail(path, "scene " + std::to_string(sceneIndex) + ": node " + std::to_string(root) + " does not exist (" +
                           std::to_string(count) + " nodes)");
        }
        enter(root, glm::dmat4(1.0), -1, true);
        while (!stack.empty()) {
            Frame& top = stack.back();
            const auto& children = model.nodes[static_cast<std::size_t>(top.node)].children;
            if (top.nextChild == children.size()) {
                onPath[static_cast<std::size_t>(top.node)] = 0;
                stack.pop_back();
                continue;
            }
            const int child = children[top.nextChild++];
            if (!valid(child)) {
                fail(path, nodeName(model, top.node) + ": child " + std::to_string(child) + " does not exist (" +
                               std::to_string(count) + " nodes)");
            }
            const glm::dmat4 parent = top.world;
            enter(child, parent, top.node, top.visible);
        }
    }
    return visits;
}

}  // namespace strata::gltf
