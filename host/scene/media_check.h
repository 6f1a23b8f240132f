// What strata's media (KHR_materials_volume, KHR_materials_volume_scatter)
// cannot render, found at load so that it is said in one warning line:
// a path is inside a medium from a back face of its mesh to the next hit,
// so media do not nest and a surface inside a medium ends it early.
#pragma once

#include <string>

namespace strata {

struct Scene;

// Triangles (of any other material: surfaces, emitters, other media) whose
// centroid lies inside the closed volume of a material with a medium
// (MaterialDesc::hasVolume), by the parity of a ray's crossings with that
// material's triangles. Returns the warning's text, or "" when there are
// none or the scene has no medium (then it costs a loop over the
// materials). Points on a medium's boundary count as outside. Instanced
// meshes are tested at each placement's pose at the shutter's open; the
// check gives up (returns "") past kMediaCheckWork ray-triangle tests.
std::string surfacesInsideMedia(const Scene& scene);

inline constexpr double kMediaCheckWork = 2.0e8;

}  // namespace strata
