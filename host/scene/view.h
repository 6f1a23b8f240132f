// The camera a render looks through: the scene's glTF camera (--camera), a
// view given on the command line (--look-from, --look-at, --up, --fov), or,
// for a file without a camera, a default view that frames the whole scene.
#pragma once
#include <optional>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata {

// The default view of a scene without a camera: from the front (+Z, the
// side a glTF asset faces) and kFrameElevationDegrees above, towards the
// centre of the geometry's bounds, with a vertical field of view of
// kFrameYfovDegrees.
inline constexpr float kFrameYfovDegrees = 40.0f;
inline constexpr float kFrameElevationDegrees = 20.0f;

struct ViewOptions {
    int camera = 0;                     // --camera: index into Scene::cameras
    std::optional<glm::vec3> lookFrom;  // --look-from
    std::optional<glm::vec3> lookAt;    // --look-at
    std::optional<glm::vec3> up;        // --up (default +Y)
    std::optional<float> fovDegrees;    // --fov: vertical field of view, in (0, 180)
    bool lookGiven() const { return lookFrom.has_value(); }
};

// The default view: every triangle vertex of `scene` lies inside the view
// frustum of an image of the given aspect (width / height), since the
// bounding sphere about the bounds' centre does. `yfov` in radians.
Camera frameScene(const Scene& scene, float aspect, float yfov);

// A camera at `from` looking at `at` with `up` (made orthogonal to the view
// direction) and vertical field of view `yfov` (radians). Throws
// strata::Error naming `file` when from == at or up is parallel to the view.
Camera lookAtCamera(const std::string& file, glm::vec3 from, glm::vec3 at, glm::vec3 up, float yfov);

// The camera of a render of `scene` at width x height:
// - with --look-from/--look-at: that view; its field of view is --fov, else
//   that of the scene's camera --camera when the scene has one, else
//   kFrameYfovDegrees;
// - else the scene's camera --camera (an error when it does not exist), its
//   field of view replaced by --fov when given;
// - else, when the scene has no camera, frameScene with one warning line.
Camera chooseCamera(const Scene& scene, const ViewOptions& view, int width, int height);

}  // namespace strata
