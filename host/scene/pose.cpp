#include "scene/pose.h"

#include <cmath>

namespace strata {

glm::dmat4 trs(const glm::dvec3& t, glm::dvec4 q, const glm::dvec3& s) {
    const double len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    q /= len;
    const double x = q.x, y = q.y, z = q.z, w = q.w;
    // Unit quaternion (x, y, z, w) -> rotation matrix; m[column][row].
    const glm::dmat3 r(glm::dvec3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)),
                       glm::dvec3(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)),
                       glm::dvec3(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)));
    glm::dmat4 m(1.0);
    for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(r[c] * s[c], 0.0);
    m[3] = glm::dvec4(t, 1.0);
    return m;
}

glm::dvec4 slerp(const glm::dvec4& a, glm::dvec4 b, double s) {
    double cosine = glm::dot(a, b);
    if (cosine < 0.0) {
        b = -b;
        cosine = -cosine;
    }
    if (cosine > 0.9995) return glm::normalize(a + s * (b - a));
    const double angle = std::acos(cosine);
    return (std::sin((1.0 - s) * angle) * a + std::sin(s * angle) * b) / std::sin(angle);
}

glm::dmat4 interpolatePose(const MotionKey& a, const MotionKey& b, double w) {
    return trs(glm::mix(glm::dvec3(a.translation), glm::dvec3(b.translation), w),
               slerp(glm::dvec4(a.rotation), glm::dvec4(b.rotation), w),
               glm::mix(glm::dvec3(a.scale), glm::dvec3(b.scale), w));
}

}  // namespace strata
