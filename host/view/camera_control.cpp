#include "view/camera_control.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/quaternion.hpp>

namespace strata {

CameraControl::CameraControl(const Camera& camera, glm::vec3 target, double sceneRadius)
    : camera_(camera), target_(target), worldUp_(camera.up), radius_(sceneRadius > 0.0 ? sceneRadius : 1.0) {}

void CameraControl::place(glm::vec3 position, glm::vec3 target) {
    const glm::vec3 forward = glm::normalize(target - position);
    glm::vec3 side = glm::cross(forward, worldUp_);
    if (glm::length(side) < 1e-6f) side = glm::cross(forward, camera_.up);  // looking along the up axis
    camera_.position = position;
    camera_.forward = forward;
    camera_.up = glm::normalize(glm::cross(glm::normalize(side), forward));
    camera_.motion.clear();  // a moved camera is still over the shutter
    target_ = target;
}

void CameraControl::orbit(double dx, double dy, int height) {
    const double perPixel = std::numbers::pi / std::max(height, 1);
    const glm::vec3 offset = camera_.position - target_;
    const float distance = glm::length(offset);
    if (!(distance > 0.0f)) return;
    const glm::vec3 dir = offset / distance;
    // Elevation above the plane normal to worldUp, kept within 1 degree of the poles.
    const double elevation = std::asin(std::clamp(double(glm::dot(dir, worldUp_)), -1.0, 1.0));
    const double limit = std::numbers::pi / 2 - std::numbers::pi / 180;
    const double newElevation = std::clamp(elevation + dy * perPixel, -limit, limit);
    glm::vec3 flat = dir - glm::dot(dir, worldUp_) * worldUp_;
    if (glm::length(flat) < 1e-6f) flat = glm::cross(camera_.up, worldUp_) + camera_.up;  // any horizontal
    flat = glm::normalize(flat);
    const glm::quat yaw = glm::angleAxis(float(-dx * perPixel), worldUp_);
    flat = yaw * flat;
    const glm::vec3 next = float(std::cos(newElevation)) * flat + float(std::sin(newElevation)) * worldUp_;
    place(target_ + distance * next, target_);
}

void CameraControl::pan(double dx, double dy, int height) {
    const float distance = glm::length(camera_.position - target_);
    const float perPixel = 2.0f * distance * std::tan(camera_.yfov * 0.5f) / float(std::max(height, 1));
    const glm::vec3 right = glm::normalize(glm::cross(camera_.forward, camera_.up));
    const glm::vec3 move = (-float(dx) * right + float(dy) * camera_.up) * perPixel;
    place(camera_.position + move, target_ + move);
}

void CameraControl::zoom(double steps) {
    const glm::vec3 offset = camera_.position - target_;
    const float scale = float(std::pow(0.85, steps));
    if (glm::length(offset * scale) < 1e-4f * float(radius_)) return;
    place(target_ + offset * scale, target_);
}

void CameraControl::fly(const glm::vec3& move, double seconds) {
    if (move == glm::vec3(0.0f) || !(seconds > 0.0)) return;
    const glm::vec3 right = glm::normalize(glm::cross(camera_.forward, camera_.up));
    const glm::vec3 step =
        (move.x * right + move.y * camera_.up + move.z * camera_.forward) * float(0.5 * radius_ * seconds);
    place(camera_.position + step, target_ + step);
}

glm::vec3 orbitTarget(const Camera& camera, glm::vec3 sceneCenter, double sceneRadius) {
    const float depth = glm::dot(sceneCenter - camera.position, camera.forward);
    return camera.position + camera.forward * std::max(depth, float(0.1 * sceneRadius));
}

}  // namespace strata
