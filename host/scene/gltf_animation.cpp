// glTF animations (glTF 2.0 section 3.11, appendix C): one animation's node
// channels read and checked once, then sampled at any time.
#include "scene/gltf_animation.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include <glm/ext/vector_float1.hpp>

#include "scene/gltf_deform.h"
#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

// Accessor types per target path (3.11, the channel.path table): translation
// and scale FLOAT VEC3; rotation FLOAT VEC4, or normalized BYTE,
// UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT VEC4; input FLOAT SCALAR.
const AccessorFormat kTimes{TINYGLTF_TYPE_SCALAR, {TINYGLTF_COMPONENT_TYPE_FLOAT}, false};
const AccessorFormat kVec3{TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, false};
const AccessorFormat kRotation{TINYGLTF_TYPE_VEC4,
                               {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                               true};

constexpr glm::dvec4 kIdentityRotation{0.0, 0.0, 0.0, 1.0};

std::string animationLabel(const tinygltf::Model& model, std::size_t index) {
    std::string label = "animation " + std::to_string(index);
    const std::string& name = model.animations[index].name;
    if (!name.empty()) label += " (" + quoted(name) + ")";
    return label;
}

// The animation `select` names (see Animation::load), or an error listing
// the first few animations.
std::size_t selectAnimation(const std::string& path, const tinygltf::Model& model, const std::string& select) {
    const std::size_t count = model.animations.size();
    if (count == 0) fail(path, "no animations in the file");
    if (select.empty()) return 0;
    std::size_t index = count;
    const char* end = select.data() + select.size();
    const bool digits = std::all_of(select.begin(), select.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (digits) {
        if (std::from_chars(select.data(), end, index).ptr != end) index = count;  // too large
    } else {
        for (std::size_t i = 0; i < count && index == count; ++i) {
            if (model.animations[i].name == select) index = i;
        }
    }
    if (index < count) return index;
    constexpr std::size_t kListed = 4;
    std::string list;
    for (std::size_t i = 0; i < std::min(count, kListed); ++i) {
        list += (i == 0 ? "" : ", ") + animationLabel(model, i);
    }
    if (count > kListed) list += " and " + std::to_string(count - kListed) + " more";
    fail(path, (digits ? "animation " + select + " does not exist" : "no animation named " + quoted(select)) +
                   " (the file has " + list + ")");
}

std::string number(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

// The sampler's key times: finite and strictly increasing (3.11: "input
// values MUST be strictly increasing"), at least one key.
std::vector<double> readTimes(const std::string& path, const tinygltf::Model& model, int accessor,
                              const std::string& use) {
    const std::vector<glm::vec1> raw = readFloats<1>(path, model, accessor, use, kTimes, nullptr);
    if (raw.empty()) fail(path, use + " has no key times");
    std::vector<double> times(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) {
        times[k] = raw[k].x;
        const std::string key = "key " + std::to_string(k) + " time " + number(times[k]);
        if (!std::isfinite(times[k])) fail(path, use + ": " + key + " is not finite");
        if (k > 0 && !(times[k] > times[k - 1])) {
            fail(path, use + ": " + key + " is not greater than key " + std::to_string(k - 1) + " time " +
                           number(times[k - 1]) + "; key times must be strictly increasing");
        }
    }
    return times;
}

// The sampler's output values as dvec4 (w = 0 for VEC3), all finite.
std::vector<glm::dvec4> readValues(const std::string& path, const tinygltf::Model& model, int accessor,
                                   const std::string& use, NodeChannel::Path target) {
    std::vector<glm::dvec4> values;
    if (target == NodeChannel::Path::Rotation) {
        const std::vector<glm::vec4> raw = readFloats<4>(path, model, accessor, use, kRotation, nullptr);
        values.assign(raw.begin(), raw.end());
    } else {
        for (const glm::vec3& v : readFloats<3>(path, model, accessor, use, kVec3, nullptr)) {
            values.emplace_back(v, 0.0);
        }
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
        const glm::dvec4& v = values[i];
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w)) {
            fail(path, use + ": value " + std::to_string(i) + " is not finite");
        }
    }
    return values;
}

Interpolation readInterpolation(const std::string& path, const std::string& name, const std::string& use) {
    if (name.empty() || name == "LINEAR") return Interpolation::Linear;  // the schema's default
    if (name == "STEP") return Interpolation::Step;
    if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
    fail(path, use + ": interpolation " + quoted(name) + " is not LINEAR, STEP or CUBICSPLINE");
}

// One channel of animation `label`, checked; false for a "weights" channel.
bool readChannel(const std::string& path, const tinygltf::Model& model, const tinygltf::Animation& animation,
                 std::size_t index, const std::string& label, NodeChannel& out) {
    const tinygltf::AnimationChannel& channel = animation.channels[index];
    const std::string where = label + " channel " + std::to_string(index);
    const std::size_t samplers = animation.samplers.size(), nodes = model.nodes.size();
    if (channel.sampler < 0 || static_cast<std::size_t>(channel.sampler) >= samplers) {
        fail(path, where + ": sampler " + std::to_string(channel.sampler) + " does not exist (" +
                       std::to_string(samplers) + " samplers)");
    }
    if (channel.target_node < 0) fail(path, where + " has no target node");
    if (static_cast<std::size_t>(channel.target_node) >= nodes) {
        fail(path, where + ": target node " + std::to_string(channel.target_node) + " does not exist (" +
                       std::to_string(nodes) + " nodes)");
    }
    const std::string& target = channel.target_path;
    if (target == "weights") return false;
    if (target == "translation") {
        out.path = NodeChannel::Path::Translation;
    } else if (target == "rotation") {
        out.path = NodeChannel::Path::Rotation;
    } else if (target == "scale") {
        out.path = NodeChannel::Path::Scale;
    } else {
        fail(path, where + ": target path " + quoted(target) + " is not translation, rotation, scale or weights");
    }
    out.node = channel.target_node;
    if (!model.nodes[static_cast<std::size_t>(out.node)].matrix.empty()) {
        fail(path, where + " targets " + nodeName(model, out.node) +
                       ", which has a matrix; an animated node must use translation, rotation and scale");
    }
    const tinygltf::AnimationSampler& sampler = animation.samplers[static_cast<std::size_t>(channel.sampler)];
    const std::string use = label + " sampler " + std::to_string(channel.sampler);
    out.interpolation = readInterpolation(path, sampler.interpolation, use);
    out.times = readTimes(path, model, sampler.input, use + " input");
    out.values = readValues(path, model, sampler.output, use + " output", out.path);
    const bool cubic = out.interpolation == Interpolation::CubicSpline;
    const std::size_t expected = out.times.size() * (cubic ? 3 : 1);
    if (out.values.size() != expected) {
        fail(path, use + ": output has " + std::to_string(out.values.size()) + " values for " +
                       std::to_string(out.times.size()) + " key times; expected " + std::to_string(expected) +
                       (cubic ? " (in-tangent, value, out-tangent per key)" : ""));
    }
    if (out.path == NodeChannel::Path::Rotation && !cubic) {
        for (std::size_t k = 0; k < out.values.size(); ++k) {
            const double length = glm::length(out.values[k]);
            if (!(length > 0.0)) fail(path, use + " output: rotation key " + std::to_string(k) + " has length 0");
            out.values[k] /= length;
        }
    }
    return true;
}

// The channel's value at t (see Animation::local).
glm::dvec4 sample(const NodeChannel& c, double t, bool leftLimit) {
    const bool cubic = c.interpolation == Interpolation::CubicSpline;
    const auto value = [&](std::size_t k) { return c.values[cubic ? 3 * k + 1 : k]; };
    const std::size_t last = c.times.size() - 1;
    // k: the last key with times[k] <= t (0 before the first key).
    const auto after = std::upper_bound(c.times.begin(), c.times.end(), t);
    const std::size_t k = after == c.times.begin() ? 0 : static_cast<std::size_t>(after - c.times.begin()) - 1;
    if (c.interpolation == Interpolation::Step) {
        // Only a STEP key jumps: the limit from before its time is key k - 1.
        return value(leftLimit && k > 0 && t == c.times[k] ? k - 1 : k);
    }
    if (t <= c.times[0] || k == last) return value(k);  // held before the first key, after the last
    const double span = c.times[k + 1] - c.times[k], s = (t - c.times[k]) / span;
    if (!cubic) {
        if (c.path == NodeChannel::Path::Rotation) return slerp(value(k), value(k + 1), s);
        return glm::mix(value(k), value(k + 1), s);
    }
    // Appendix C: p(s) = (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) td b_k
    //                    + (-2s^3 + 3s^2) v_k+1 + (s^3 - s^2) td a_k+1,
    // td = t_k+1 - t_k, b_k the out-tangent of key k, a_k+1 the in-tangent of key k+1.
    const double s2 = s * s, s3 = s2 * s;
    const glm::dvec4 p = (2 * s3 - 3 * s2 + 1) * value(k) + (s3 - 2 * s2 + s) * span * c.values[3 * k + 2] +
                         (-2 * s3 + 3 * s2) * value(k + 1) + (s3 - s2) * span * c.values[3 * (k + 1)];
    if (c.path != NodeChannel::Path::Rotation) return p;
    const double length = glm::length(p);
    // A spline through length 0 defines no rotation there: the identity.
    return length > 0.0 && std::isfinite(length) ? p / length : kIdentityRotation;
}

}  // namespace

Animation Animation::load(const std::string& path, const tinygltf::Model& model, const std::string& select) {
    const std::size_t index = selectAnimation(path, model, select);
    const tinygltf::Animation& source = model.animations[index];
    Animation out;
    out.label = animationLabel(model, index);
    bool weights = false;
    for (std::size_t c = 0; c < source.channels.size(); ++c) {
        NodeChannel channel;
        if (!readChannel(path, model, source, c, out.label, channel)) {
            weights = true;
            continue;
        }
        // 3.11: within one animation, a target (node and path) is used at most once.
        for (std::size_t other = 0; other < out.channels.size(); ++other) {
            if (out.channels[other].node == channel.node && out.channels[other].path == channel.path) {
                fail(path, out.label + " channel " + std::to_string(c) + ": " + nodeName(model, channel.node) + " " +
                               source.channels[c].target_path + " is animated by an earlier channel too");
            }
        }
        out.start = out.channels.empty() ? channel.times.front() : std::min(out.start, channel.times.front());
        out.end = out.channels.empty() ? channel.times.back() : std::max(out.end, channel.times.back());
        out.channels.push_back(std::move(channel));
    }
    // Every node's own transform checked (matrix or TRS sizes, rotation length), so local() cannot fail.
    for (std::size_t n = 0; n < model.nodes.size(); ++n) nodeTransform(path, model, static_cast<int>(n));
    if (weights) warn(path, out.label + ": morph-target weight animation is not rendered; the weights stay static");
    return out;
}

bool Animation::animates(int node) const {
    return std::any_of(channels.begin(), channels.end(), [&](const NodeChannel& c) { return c.node == node; });
}

glm::dmat4 Animation::local(const tinygltf::Model& model, int node, double t, bool leftLimit) const {
    // A node no channel targets keeps its own transform (its matrix, or T * R * S);
    // load() has checked every node's (nodeTransform).
    if (!animates(node)) return nodeTransform(label, model, node);
    auto [translation, rotation, scale] = nodeTrs(label, model, node);  // no matrix: load() checked it
    for (const NodeChannel& c : channels) {
        if (c.node != node) continue;
        const glm::dvec4 v = sample(c, t, leftLimit);
        switch (c.path) {
            case NodeChannel::Path::Translation: translation = glm::dvec3(v); break;
            case NodeChannel::Path::Rotation: rotation = v; break;
            case NodeChannel::Path::Scale: scale = glm::dvec3(v); break;
        }
    }
    return trs(translation, rotation, scale);
}

void Animation::keyTimes(int node, double a, double b, std::vector<double>& out) const {
    for (const NodeChannel& c : channels) {
        if (c.node != node) continue;
        for (const double t : c.times) {
            if (t > a && t < b) out.push_back(t);
        }
    }
}

bool Animation::steps(int node) const {
    return std::any_of(channels.begin(), channels.end(), [&](const NodeChannel& c) {
        return c.node == node && c.interpolation == Interpolation::Step;
    });
}

bool Animation::curves(int node) const {
    return std::any_of(channels.begin(), channels.end(), [&](const NodeChannel& c) {
        return c.node == node && c.interpolation == Interpolation::CubicSpline;
    });
}

}  // namespace strata::gltf
