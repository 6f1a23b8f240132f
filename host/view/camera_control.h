// The viewer's camera: orbit about a target, pan, zoom and fly, as the
// mouse and keys of `strata view` move it (view/viewer.cpp). Pure math on
// the host; tests drive it directly.
#pragma once
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata {

class CameraControl {
public:
    // Starts at `camera` (its motion over a shutter is kept until the
    // first move), orbiting `target`; `sceneRadius` sets the fly speed.
    CameraControl(const Camera& camera, glm::vec3 target, double sceneRadius);

    // A left-button drag of (dx, dy) pixels in a window `height` pixels
    // high: half a turn per height about the up axis and the side axis
    // (the elevation stops short of the poles).
    void orbit(double dx, double dy, int height);
    // A right-button drag: the point at the target's depth follows the cursor.
    void pan(double dx, double dy, int height);
    // Wheel steps: each brings the camera 15% nearer the target (negative: farther).
    void zoom(double steps);
    // Fly keys held for `seconds`: right, up, forward in -1..1; half the
    // scene's radius a second, the target moving along.
    void fly(const glm::vec3& move, double seconds);

    const Camera& camera() const { return camera_; }
    glm::vec3 target() const { return target_; }

private:
    void place(glm::vec3 position, glm::vec3 target);

    Camera camera_;
    glm::vec3 target_;
    glm::vec3 worldUp_;
    double radius_;
};

// The orbit target for a camera: along its view at the depth of the
// scene's centre (at least a tenth of the radius in front).
glm::vec3 orbitTarget(const Camera& camera, glm::vec3 sceneCenter, double sceneRadius);

}  // namespace strata
