// Motion blur's input from a glTF animation: the nodes' world transforms at
// any time, and the MotionKeys (scene.h) of the placements and cameras that
// move within the shutter. Internal to the loader (host/scene/gltf*.cpp).
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf_animation.h"
#include "scene/scene.h"

namespace strata::gltf {

class NodeTimeline {
public:
    // `animation` may be null (no motion: every node static).
    NodeTimeline(const std::string& path, const tinygltf::Model& model, const Animation* animation,
                 const MotionOptions& motion);

    // The walk's hierarchy: `parent` is the node's parent, -1 for a root.
    // Parents are set before their children.
    void setParent(int node, int parent);
    // It or an ancestor is animated.
    bool animated(int node) const;
    // Whether the shutter is an interval (open < close): moving placements get keys.
    bool blurs() const { return animation_ != nullptr && motion_.close > motion_.open; }
    double open() const { return motion_.open; }

    // The node's local transform at the shutter's open (its static one when
    // it is not animated). `staticLocal` is the node's checked static matrix.
    glm::dmat4 localAtOpen(int node, const glm::dmat4& staticLocal) const;

    // The keys of a placement `placed` = world(node, t) * local over the
    // shutter: at open, close, every key time of the node's and its
    // ancestors' channels between (twice at a STEP key: before and after),
    // and in between where the motion is not interpolated exactly by T, R,
    // S (several animated nodes, or a CUBICSPLINE channel). Empty when the
    // placement does not move within the shutter. `label` names it in errors.
    std::vector<MotionKey> keys(int node, const glm::dmat4& local, const std::string& label) const;

    // The same for a camera: position and orientation only, at most
    // gpu::kMaxCameraKeys (a denser motion is resampled at that many evenly
    // spaced times).
    std::vector<MotionKey> cameraKeys(int node, const std::string& label) const;

    // The node's world transform at time t (leftLimit: just before t).
    glm::dmat4 world(int node, double t, bool leftLimit = false) const;

private:
    std::vector<std::pair<double, bool>> keyTimes(int node) const;  // (time, left limit)

    const std::string& path_;
    const tinygltf::Model& model_;
    const Animation* animation_;
    MotionOptions motion_;
    std::vector<int> parent_;
    std::vector<char> animated_;
};

// A camera's position, forward (its -Z) and up (its +Y made orthogonal to
// forward) from its node's world transform, in double; false when
// degenerate (a zero scale or not finite).
bool cameraFrame(const glm::dmat4& world, glm::dvec3& position, glm::dvec3& forward, glm::dvec3& up);
// The same into a Camera's pose.
bool cameraFromWorld(const glm::dmat4& world, Camera& camera);

// What the walk tells the poser (ScenePoser, --frames): the hierarchy in
// walk order (parents first), and each animated placement and camera.
struct PoseTargets {
    std::vector<std::pair<int, int>> hierarchy;  // (node, parent or -1)
    struct Placed {
        std::size_t instance;  // index into Scene::instances
        int node;
        glm::dmat4 local;      // its EXT_mesh_gpu_instancing transform under the node
        std::string label;
    };
    std::vector<Placed> placements;
    struct Viewer {
        std::size_t camera;    // index into Scene::cameras
        int node;
        std::string label;
    };
    std::vector<Viewer> cameras;
    // False when something animated cannot be posed again (a light, or a
    // mesh that emits, or one that stays flattened: skinned, morphed or degenerate):
    // then the loader sets no poser and each frame is loaded anew.
    bool complete = true;
};

// The poser of a scene loaded with MotionOptions::frames: it keeps the
// file's nodes (not its buffers) and the animation.
std::shared_ptr<const ScenePoser> makePoser(const std::string& path, const tinygltf::Model& model,
                                            Animation animation, PoseTargets targets);

// The pose of a world transform as translation, rotation and scale. A
// mirroring transform gets a negative x scale; `shear` is set when the
// linear part is not a rotation times a scale (its columns not orthogonal),
// and the rotation is then the nearest by Gram-Schmidt.
MotionKey decomposePose(double time, const glm::dmat4& m, bool& shear);

}  // namespace strata::gltf
