// Rigid poses as translation, rotation (unit quaternion, xyzw) and scale:
// the matrix of a pose, the slerp between two rotations, and a moving
// placement's transform between two MotionKeys. Shared by the glTF loader
// (node transforms, animations) and the BVH stage (a moving placement's
// box); lib/motion.glsl interpolates the same way on the device.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata {

// T * R * S from a translation, a quaternion (x, y, z, w) of any non-zero
// length (normalised here) and a scale.
glm::dmat4 trs(const glm::dvec3& t, glm::dvec4 q, const glm::dvec3& s);

// Unit quaternions a to b at s in [0, 1] on the shorter arc (q and -q are the
// same rotation); a normalised lerp where they are nearly parallel.
glm::dvec4 slerp(const glm::dvec4& a, glm::dvec4 b, double s);

// The object-to-world transform between two MotionKeys at fraction w: T and
// S lerped, R slerped.
glm::dmat4 interpolatePose(const MotionKey& a, const MotionKey& b, double w);

}  // namespace strata
