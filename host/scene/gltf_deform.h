// Morph targets (gltf_morph.cpp): a node's static pose of its mesh, applied
// at load. Shared by host/scene/gltf*.cpp only;
// every function throws strata::Error with one line naming the file.
#pragma once
#include <string>
#include <vector>

#include "scene/gltf_internal.h"

namespace strata::gltf {

// `node 2 ("Arm")`, or `node 2` for an unnamed node.
std::string nodeName(const tinygltf::Model& model, int node);

// Reads every target of `prim` (glTF 2.0 3.7.2.2): POSITION, NORMAL and
// TANGENT displacements, FLOAT VEC3 (with KHR_mesh_quantization also BYTE
// and SHORT, normalized or not), dense, zeros or sparse, one per vertex;
// other target attributes are ignored. `label` names the primitive.
std::vector<MorphTarget> readMorphTargets(const std::string& path, const tinygltf::Model& model,
                                          const tinygltf::Primitive& prim, const std::string& label,
                                          std::size_t vertexCount, bool quantization);

// The morph weights node `node` (labelled `nodeLabel`) shows its mesh with:
// node.weights, else mesh.weights, else zeros; as many as the mesh's targets
// (the same number in every primitive, else an error).
std::vector<double> morphWeights(const std::string& path, const tinygltf::Model& model, int node,
                                 const std::string& nodeLabel, const LocalMesh& mesh);

// prim's positions, normals and tangent xyz displaced by sum_i weights[i] *
// prim.targets[i] (accumulated in double).
void applyMorph(const std::vector<double>& weights, LocalPrimitive& prim);

// The pose of the mesh of node `node`: its morph weights (node.weights,
// else mesh.weights, else zeros; as many as the primitives' targets).
class NodePose {
public:
    NodePose(const std::string& path, const tinygltf::Model& model, int node, const LocalMesh& mesh);

    // `prim` morphed (p + sum w_i dp_i, likewise normals and tangent xyz)
    // into `scratch`; `prim` itself when every weight is 0.
    const LocalPrimitive& apply(const LocalPrimitive& prim, LocalPrimitive& scratch) const;

private:
    std::vector<double> weights_;  // morph weights
};

}  // namespace strata::gltf
