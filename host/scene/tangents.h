// Tangent frames for normal mapping, computed on the CPU at load time.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace strata {

// Per-vertex tangents of an indexed triangle list (3 indices per triangle)
// from its texture coordinates, for primitives with a normalTexture and no
// TANGENT (glTF 2.0 3.7.2.1 asks for MikkTSpace; this is the simpler
// accumulation of Lengyel 2001, "Computing Tangent Space Basis Vectors").
// Per triangle, dP/du and dP/dv follow from the edges and the uv deltas;
// each vertex sums them over its triangles; the sum of dP/du is then
// orthogonalised against the vertex normal (Gram-Schmidt) and normalised.
// Handedness w follows glTF: the bitangent w * cross(n, t) is the normal
// map's +Y, which points to decreasing v (v = 0 is the image's top row), so
// w = +1 when cross(n, t) points along -dP/dv and -1 otherwise (a mirrored
// uv mapping). A triangle with zero uv area adds nothing; a vertex with no
// usable uv derivative gets any unit tangent orthogonal to its normal, w = +1.
// `normals` may be empty: each vertex then uses the sum of the geometric
// normals of its triangles.
std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals,
                                        const std::vector<glm::vec2>& uvs,
                                        const std::vector<std::uint32_t>& indices);

// A unit vector orthogonal to the unit vector n (Duff et al. 2017, "Building
// an Orthonormal Basis, Revisited", JCGT 6(1)).
glm::vec3 anyOrthogonal(const glm::vec3& n);

}  // namespace strata
