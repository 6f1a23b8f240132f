// Morph targets (gltf_morph.cpp) and skins (gltf_skin.cpp): a node's static
// pose of its mesh, applied at load. Shared by host/scene/gltf*.cpp only;
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

// JOINTS_n and WEIGHTS_n of `prim`, n = 0, 1, ... while either is present:
// JOINTS UNSIGNED_BYTE/UNSIGNED_SHORT VEC4 (not normalized), WEIGHTS FLOAT
// or normalized UNSIGNED_BYTE/UNSIGNED_SHORT VEC4, finite and >= 0, one per
// vertex. A JOINTS_n without its WEIGHTS_n (or the reverse) is an error. An
// attribute named in `inStream` comes from `decoded` (a Draco stream's, by
// set), the others from their accessors.
std::vector<SkinInfluences> readSkinInfluences(const std::string& path, const tinygltf::Model& model,
                                               const tinygltf::Primitive& prim, const std::string& label,
                                               std::size_t vertexCount, const std::vector<std::string>& inStream,
                                               const std::vector<SkinInfluences>& decoded);

// The world transform of any node from the node hierarchy (its parents'
// transforms times its own), as the scene walk computes it.
glm::dmat4 nodeWorld(const std::string& path, const tinygltf::Model& model, int node);

// The pose of the mesh of node `node`: its morph weights (node.weights,
// else mesh.weights, else zeros; as many as the primitives' targets) and,
// with node.skin, the skin's joint matrices jointWorld_i * inverseBind_i
// (inverseBindMatrices MAT4 FLOAT, at least one per joint, each invertible;
// identity without them, though tinygltf 2.7 refuses a skin without them).
class NodePose {
public:
    NodePose(const std::string& path, const tinygltf::Model& model, int node, const LocalMesh& mesh);

    // A skinned mesh is placed by its joints: the node's own transform (and
    // its parents') is ignored (glTF 2.0 3.7.3.2).
    bool skinned() const { return !joints_.empty(); }

    // `prim` morphed (p + sum w_i dp_i, likewise normals and tangent xyz),
    // then skinned: sum_i w_i M_i p over the vertex's influences, with the
    // weights divided by their sum (a sum off 1 by more than the
    // glTF-Validator's 2e-7 per weight is one warning), normals by the
    // inverse transposes of the M_i, tangents by the M_i; into `scratch`.
    // `prim` itself when the node has no skin and every weight is 0.
    // Tangents the loader generates (no TANGENT) are made from the unposed
    // mesh, then posed like given ones; a skin that mirrors (det < 0) does not
    // reverse the winding as a mirroring node transform does. A joint
    // index out of the skin's range, or a vertex without a weight above 0,
    // is an error.
    const LocalPrimitive& apply(const LocalPrimitive& prim, LocalPrimitive& scratch) const;

private:
    const std::string& path_;
    std::string label_;                     // the node (and its skin), for messages
    std::vector<double> weights_;           // morph weights
    std::vector<glm::dmat4> joints_;        // jointWorld_i * inverseBind_i
    std::vector<glm::dmat3> normalJoints_;  // their inverse transposes (linear part)
};

}  // namespace strata::gltf
