// Sampling tables of an equirectangular environment map (scene.h states the
// mapping): a piecewise-constant 2D distribution over the map's (u, v) in
// [0,1]^2 proportional to f(x, y) = luminance(texel) * sin(theta at the row
// centre), marginal over rows and conditional per row (the model is pbrt-v4's
// PiecewiseConstant2D; this is our own code). With dw = 2 pi^2 sin(theta)
// du dv, the solid-angle density is p(u, v) / (2 pi^2 sin theta), which is
// proportional to luminance up to sin(row centre) / sin(theta).
#pragma once
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata {

// The mapping of scene.h: world direction of map coordinates (u, v) in
// [0,1]^2 for an environment turned by `rotation` radians about +Y, and back.
glm::dvec3 envDirection(double u, double v, double rotation);
glm::dvec2 envUv(const glm::dvec3& dir, double rotation);

// Rec. 709 luminance of linear RGB.
inline double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Float layout for a W x H map (shaders/lib/environment.glsl reads it):
//   [0, H)                          p(v) per row: density of v, integrates to 1
//   [H, 2H + 1)                     CDF over rows, 0 ... 1
//   [2H + 1 + y W + x]              p(u | row y) per texel: density of u, integrates to 1
//   [2H + 1 + H W + y (W + 1) + x]  CDF of row y, x = 0 ... W, 0 ... 1
// A row whose texels are all black gets a uniform conditional.
std::vector<float> buildEnvTables(const Environment& env);

// The map's texels as RGBA32F (a = 0), row 0 at the top.
std::vector<glm::vec4> envTexels(const Environment& env);

// Solid-angle-weighted mean luminance of the environment's radiance
// (scale * map): (1 / 4 pi) * integral of luminance dw.
double envMeanLuminance(const Environment& env);

}  // namespace strata
