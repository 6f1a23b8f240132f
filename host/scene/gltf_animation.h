// glTF animations (glTF 2.0 section 3.11): one animation's node channels,
// checked once, and the nodes' local transforms at any time of its timeline.
// Internal to the loader (host/scene/gltf*.cpp); errors are strata::Error
// lines naming the file ("<path>: error: animation 0 ("Walk") channel 2: ...").
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

namespace strata::gltf {

enum class Interpolation { Linear, Step, CubicSpline };

// One channel that moves a node: its target path and its sampler's keys.
struct NodeChannel {
    int node = -1;
    enum class Path { Translation, Rotation, Scale } path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;         // strictly increasing, finite
    // LINEAR and STEP: one value per key; CUBICSPLINE: three per key (in-tangent,
    // value, out-tangent, as the file stores them). xyz for translation and
    // scale (w = 0), xyzw for rotation (unit quaternions for LINEAR and STEP
    // keys, normalised on load).
    std::vector<glm::dvec4> values;
};

class Animation {
public:
    // The animation `select` names (its name, or its index as digits; empty:
    // the first) from the file's animations, checked: every channel's sampler
    // and target node exist, input times are finite and strictly increasing,
    // the output count matches (x3 for CUBICSPLINE), accessor types fit the
    // path (rotation: VEC4 float or normalized integers), no value is NaN or
    // infinite, no LINEAR/STEP rotation key is a quaternion of zero length,
    // a node with `matrix` is not targeted. A "weights" channel is ignored
    // with one warning (morph-weight animation is not rendered). Throws
    // when the file has no animation, or none of that name or index.
    static Animation load(const std::string& path, const tinygltf::Model& model, const std::string& select);

    std::string label;   // `animation 0 ("Walk")` for messages
    double start = 0.0;  // the first key time over all channels
    double end = 0.0;    // the last one
    std::vector<NodeChannel> channels;

    // Whether some channel targets `node` itself.
    bool animates(int node) const;

    // The node's local matrix at time t: its static TRS (the node's
    // translation/rotation/scale, glTF defaults where absent) with each
    // animated property replaced by its channel's value at t. Before the
    // first key a channel holds its first value, after the last its last
    // (as glTF viewers do). LINEAR: lerp (translation, scale), slerp on the
    // shorter arc (rotation); STEP: the value of the last key at or before t;
    // CUBICSPLINE: the spec's Hermite spline with tangents scaled by the key
    // interval (rotation normalised after). `leftLimit`: at a key time, the
    // limit from before it (where a STEP key jumps, the pose just before).
    glm::dmat4 local(const tinygltf::Model& model, int node, double t, bool leftLimit = false) const;

    // Appends the key times of the channels targeting `node` that lie
    // strictly inside (a, b).
    void keyTimes(int node, double a, double b, std::vector<double>& out) const;

    // Whether a channel of `node` jumps at key times (STEP), and whether one
    // curves between keys (CUBICSPLINE): the caller samples between keys then.
    bool steps(int node) const;
    bool curves(int node) const;
};

}  // namespace strata::gltf
