#include "scene/gltf_motion.h"

#include <algorithm>
#include <cmath>

#include "../../shaders/shared/types.h"
#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {
namespace {

// Between two keys of a chain where more than one node is animated, or a
// channel curves, the pose is sampled this many times per key interval.
constexpr int kSubdivisions = 8;
// At most this many keys per placement (the shader scans them in order).
constexpr std::size_t kMaxKeys = 1024;

// Unit quaternion (xyzw) of a rotation matrix (Shoemake 1985).
glm::dvec4 quaternionOf(const glm::dmat3& r) {
    const double trace = r[0][0] + r[1][1] + r[2][2];
    glm::dvec4 q;
    if (trace > 0.0) {
        const double s = 0.5 / std::sqrt(trace + 1.0);
        q = {(r[1][2] - r[2][1]) * s, (r[2][0] - r[0][2]) * s, (r[0][1] - r[1][0]) * s, 0.25 / s};
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]);
        q = {0.25 * s, (r[1][0] + r[0][1]) / s, (r[2][0] + r[0][2]) / s, (r[1][2] - r[2][1]) / s};
    } else if (r[1][1] > r[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]);
        q = {(r[1][0] + r[0][1]) / s, 0.25 * s, (r[2][1] + r[1][2]) / s, (r[2][0] - r[0][2]) / s};
    } else {
        const double s = 2.0 * std::sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]);
        q = {(r[2][0] + r[0][2]) / s, (r[2][1] + r[1][2]) / s, 0.25 * s, (r[0][1] - r[1][0]) / s};
    }
    return q / std::sqrt(glm::dot(q, q));
}

bool samePose(const MotionKey& a, const MotionKey& b) {
    return a.translation == b.translation && (a.rotation == b.rotation || a.rotation == -b.rotation) &&
           a.scale == b.scale;
}

}  // namespace

MotionKey decomposePose(double time, const glm::dmat4& m, bool& shear) {
    glm::dmat3 a(m);
    glm::dvec3 s(glm::length(a[0]), glm::length(a[1]), glm::length(a[2]));
    if (glm::determinant(a) < 0.0) s.x = -s.x;
    glm::dmat3 r(a[0] / s.x, a[1] / s.y, a[2] / s.z);
    const double skew = std::max({std::abs(glm::dot(r[0], r[1])), std::abs(glm::dot(r[1], r[2])),
                                  std::abs(glm::dot(r[0], r[2]))});
    shear = skew > 1e-4;
    if (shear) {  // Gram-Schmidt: the nearest rotation keeping the first column
        r[0] = glm::normalize(r[0]);
        r[1] = glm::normalize(r[1] - glm::dot(r[1], r[0]) * r[0]);
        r[2] = glm::cross(r[0], r[1]);
    }
    MotionKey k;
    k.time = static_cast<float>(time);
    k.translation = glm::vec3(m[3]);
    k.rotation = glm::vec4(quaternionOf(r));
    k.scale = glm::vec3(s);
    return k;
}

NodeTimeline::NodeTimeline(const std::string& path, const tinygltf::Model& model, const Animation* animation,
                           const MotionOptions& motion)
    : path_(path), model_(model), animation_(animation), motion_(motion),
      parent_(model.nodes.size(), -1), animated_(model.nodes.size(), 0) {}

void NodeTimeline::setParent(int node, int parent) {
    parent_[std::size_t(node)] = parent;
    animated_[std::size_t(node)] =
        animation_ && (animation_->animates(node) || (parent >= 0 && animated_[std::size_t(parent)]));
}

bool NodeTimeline::animated(int node) const { return animated_[std::size_t(node)] != 0; }

glm::dmat4 NodeTimeline::localAtOpen(int node, const glm::dmat4& staticLocal) const {
    if (!animation_ || !animation_->animates(node)) return staticLocal;
    return animation_->local(model_, node, motion_.open);
}

glm::dmat4 NodeTimeline::world(int node, double t, bool leftLimit) const {
    glm::dmat4 m(1.0);
    for (int n = node; n >= 0; n = parent_[std::size_t(n)]) {
        const glm::dmat4 local = animation_ && animation_->animates(n) ? animation_->local(model_, n, t, leftLimit)
                                                                        : nodeTransform(path_, model_, n);
        m = local * m;
    }
    return m;
}

std::vector<std::pair<double, bool>> NodeTimeline::keyTimes(int node) const {
    std::vector<double> inside;
    bool steps = false, curves = false;
    int animatedNodes = 0;
    for (int n = node; n >= 0; n = parent_[std::size_t(n)]) {
        if (!animation_->animates(n)) continue;
        ++animatedNodes;
        animation_->keyTimes(n, motion_.open, motion_.close, inside);
        steps = steps || animation_->steps(n);
        curves = curves || animation_->curves(n);
    }
    inside.push_back(motion_.open);
    inside.push_back(motion_.close);
    std::sort(inside.begin(), inside.end());
    inside.erase(std::unique(inside.begin(), inside.end()), inside.end());
    const int sub = (curves || animatedNodes > 1) ? kSubdivisions : 1;
    std::vector<std::pair<double, bool>> out;
    for (std::size_t i = 0; i < inside.size(); ++i) {
        if (i > 0) {
            for (int k = 1; k < sub; ++k)
                out.push_back({inside[i - 1] + (inside[i] - inside[i - 1]) * k / sub, false});
            if (steps && i + 1 < inside.size()) out.push_back({inside[i], true});  // the pose before a jump
        }
        out.push_back({inside[i], false});
    }
    return out;
}

std::vector<MotionKey> NodeTimeline::keys(int node, const glm::dmat4& local, const std::string& label) const {
    if (!blurs() || !animated(node)) return {};
    const std::vector<std::pair<double, bool>> times = keyTimes(node);
    if (times.size() > kMaxKeys)
        fail(path_, label + ": moves through " + std::to_string(times.size()) + " poses within the shutter; at most " +
                        std::to_string(kMaxKeys) + " (shorten --shutter)");
    std::vector<MotionKey> out;
    bool sheared = false;
    for (const auto& [t, left] : times) {
        bool shear = false;
        out.push_back(decomposePose(t, world(node, t, left) * local, shear));
        sheared = sheared || shear;
        if ((out.back().scale.x < 0.0f) != (out.front().scale.x < 0.0f))
            fail(path_, label + ": its transform turns from mirroring to not (a scale through 0) within the "
                                "shutter; motion blur cannot interpolate that");
    }
    if (sheared)
        warn(path_, label + ": its moving transform has shear (a non-uniform scale above a rotation); motion "
                            "blur interpolates its nearest rotation and scale");
    bool moves = false;
    for (const MotionKey& k : out) moves = moves || !samePose(k, out.front());
    if (!moves) return {};
    return out;
}

std::vector<MotionKey> NodeTimeline::cameraKeys(int node, const std::string& label) const {
    if (!blurs() || !animated(node)) return {};
    std::vector<std::pair<double, bool>> times = keyTimes(node);
    if (times.size() > gpu::kMaxCameraKeys) {
        times.clear();
        for (std::uint32_t k = 0; k < gpu::kMaxCameraKeys; ++k)
            times.push_back({motion_.open + (motion_.close - motion_.open) * k / (gpu::kMaxCameraKeys - 1), false});
    }
    std::vector<MotionKey> out;
    for (const auto& [t, left] : times) {
        glm::dvec3 position, forward, up;
        if (!cameraFrame(world(node, t, left), position, forward, up))
            fail(path_, label + ": degenerate world transform at time " + std::to_string(t) + " of the shutter");
        MotionKey k;
        k.time = static_cast<float>(t);
        k.translation = glm::vec3(position);
        k.rotation = glm::vec4(quaternionOf(glm::dmat3(glm::cross(forward, up), up, -forward)));
        out.push_back(k);
    }
    bool moves = false;
    for (const MotionKey& k : out) moves = moves || !samePose(k, out.front());
    if (!moves) return {};
    return out;
}

bool cameraFrame(const glm::dmat4& world, glm::dvec3& position, glm::dvec3& forward, glm::dvec3& up) {
    const glm::dmat3 linear(world);
    position = glm::dvec3(world[3]);
    const glm::dvec3 f = linear * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 upRaw = linear * glm::dvec3(0.0, 1.0, 0.0);
    const double fl = glm::length(f);
    if (!(fl > 0.0) || !std::isfinite(fl)) return false;
    forward = f / fl;
    const glm::dvec3 u = upRaw - glm::dot(upRaw, forward) * forward;
    const double ul = glm::length(u);
    if (!(ul > 0.0) || !std::isfinite(ul)) return false;
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) return false;
    up = u / ul;
    return true;
}

bool cameraFromWorld(const glm::dmat4& world, Camera& camera) {
    glm::dvec3 position, forward, up;
    if (!cameraFrame(world, position, forward, up)) return false;
    camera.position = glm::vec3(position);
    camera.forward = glm::vec3(forward);
    camera.up = glm::vec3(up);
    return true;
}

namespace {

class AnimationPoser final : public ScenePoser {
public:
    AnimationPoser(const std::string& path, const tinygltf::Model& model, Animation animation, PoseTargets targets)
        : path_(path), animation_(std::move(animation)), targets_(std::move(targets)) {
        nodes_.nodes = model.nodes;
    }

    void pose(Scene& scene, double open, double close) const override {
        MotionOptions motion;
        motion.enabled = motion.frames = true;
        motion.open = open;
        motion.close = close;
        NodeTimeline timeline(path_, nodes_, &animation_, motion);
        for (const auto& [node, parent] : targets_.hierarchy) timeline.setParent(node, parent);
        for (const PoseTargets::Placed& p : targets_.placements) {
            MeshInstance& instance = scene.instances[p.instance];
            const glm::dmat4 world = timeline.world(p.node, open) * p.local;
            if ((glm::determinant(glm::dmat3(world)) < 0.0) != (glm::determinant(glm::mat3(instance.toWorld)) < 0.0f))
                fail(path_, p.label + ": its transform turns from mirroring to not (a scale through 0) between "
                                      "frames; strata cannot pose that");
            instance.toWorld = glm::mat4(world);
            instance.motion = timeline.keys(p.node, p.local, p.label);
        }
        for (const PoseTargets::Viewer& v : targets_.cameras) {
            Camera& camera = scene.cameras[v.camera];
            if (!cameraFromWorld(timeline.world(v.node, open), camera))
                fail(path_, v.label + ": degenerate world transform (zero scale or not finite) at time " +
                                std::to_string(open));
            camera.motion = timeline.cameraKeys(v.node, v.label);
        }
    }

private:
    std::string path_;
    tinygltf::Model nodes_;  // the file's nodes only
    Animation animation_;
    PoseTargets targets_;
};

}  // namespace

std::shared_ptr<const ScenePoser> makePoser(const std::string& path, const tinygltf::Model& model,
                                            Animation animation, PoseTargets targets) {
    return std::make_shared<AnimationPoser>(path, model, std::move(animation), std::move(targets));
}

}  // namespace strata::gltf
