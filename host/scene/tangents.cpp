#include "scene/tangents.h"

#include <cmath>

namespace strata {

glm::vec3 anyOrthogonal(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals,
                                        const std::vector<glm::vec2>& uvs,
                                        const std::vector<std::uint32_t>& indices) {
    const std::size_t n = positions.size();
    std::vector<glm::dvec3> dPdu(n, glm::dvec3(0.0)), dPdv(n, glm::dvec3(0.0));
    std::vector<glm::dvec3> faceNormals(normals.empty() ? n : 0, glm::dvec3(0.0));
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
        const glm::dvec3 e1 = glm::dvec3(positions[i1]) - glm::dvec3(positions[i0]);
        const glm::dvec3 e2 = glm::dvec3(positions[i2]) - glm::dvec3(positions[i0]);
        if (normals.empty()) {
            const glm::dvec3 g = glm::cross(e1, e2);
            for (std::uint32_t i : {i0, i1, i2}) faceNormals[i] += g;
        }
        const glm::dvec2 d1 = glm::dvec2(uvs[i1]) - glm::dvec2(uvs[i0]);
        const glm::dvec2 d2 = glm::dvec2(uvs[i2]) - glm::dvec2(uvs[i0]);
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (det == 0.0 || !std::isfinite(det)) continue;
        // [e1 e2] = [dP/du dP/dv] [d1 d2]  =>  solve the 2x2 system.
        const glm::dvec3 su = (e1 * d2.y - e2 * d1.y) / det;
        const glm::dvec3 sv = (e2 * d1.x - e1 * d2.x) / det;
        for (std::uint32_t i : {i0, i1, i2}) dPdu[i] += su, dPdv[i] += sv;
    }
    std::vector<glm::vec4> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 nv = normals.empty() ? faceNormals[i] : glm::dvec3(normals[i]);
        const double len = glm::length(nv);
        nv = len > 0.0 && std::isfinite(len) ? nv / len : glm::dvec3(0.0, 0.0, 1.0);
        const glm::dvec3 t = dPdu[i] - nv * glm::dot(nv, dPdu[i]);
        const double tl = glm::length(t);
        if (!(tl > 1e-20) || !std::isfinite(tl)) {
            out[i] = glm::vec4(anyOrthogonal(glm::vec3(nv)), 1.0f);
            continue;
        }
        const glm::dvec3 tu = t / tl;
        const double w = glm::dot(glm::cross(nv, tu), dPdv[i]) > 0.0 ? -1.0 : 1.0;
        out[i] = glm::vec4(glm::vec3(tu), static_cast<float>(w));
    }
    return out;
}

}  // namespace strata
