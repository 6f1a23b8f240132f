#include "scene/view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "util/error.h"

namespace strata {
namespace {

float radians(float degrees) { return degrees * std::numbers::pi_v<float> / 180.0f; }

std::string pointText(glm::vec3 p) {
    char text[96];
    std::snprintf(text, sizeof text, "(%.4g, %.4g, %.4g)", double(p.x), double(p.y), double(p.z));
    return text;
}

}  // namespace

Camera frameScene(const Scene& scene, float aspect, float yfov) {
    // The world triangles' vertices, and an instanced mesh's placements by
    // the corners of its box.
    const std::size_t world = scene.worldTriangles();
    std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes;  // each shared mesh's, once
    for (const SharedMesh& m : scene.sharedMeshes) {
        glm::dvec3 a(std::numeric_limits<double>::max()), b(-std::numeric_limits<double>::max());
        for (std::size_t i = m.first; i < m.first + m.count; ++i)
            for (const glm::vec3& v : scene.triangles[i].v) a = glm::min(a, glm::dvec3(v)), b = glm::max(b, glm::dvec3(v));
        boxes.emplace_back(a, b);
    }
    std::vector<glm::dvec3> corners;
    for (const MeshInstance& inst : scene.instances) {
        if (scene.sharedMeshes[inst.mesh].count == 0) continue;
        const auto& [a, b] = boxes[inst.mesh];
        const glm::dmat4 toWorld(inst.toWorld);
        for (int c = 0; c < 8; ++c)
            corners.push_back(glm::dvec3(toWorld * glm::dvec4((c & 1) ? b.x : a.x, (c & 2) ? b.y : a.y, (c & 4) ? b.z : a.z, 1.0)));
    }
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (std::size_t i = 0; i < world; ++i)
        for (const glm::vec3& v : scene.triangles[i].v) lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
    for (const glm::dvec3& c : corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
    if (world == 0 && corners.empty()) lo = hi = glm::dvec3(0.0);
    const glm::dvec3 centre = (lo + hi) * 0.5;
    double radius = 0.0;
    for (std::size_t i = 0; i < world; ++i)
        for (const glm::vec3& v : scene.triangles[i].v) radius = std::max(radius, glm::length(glm::dvec3(v) - centre));
    for (const glm::dvec3& c : corners) radius = std::max(radius, glm::length(c - centre));
    // All geometry in one point: a unit sphere about it, scaled to its distance from the origin.
    if (!(radius > 0.0)) radius = std::max(1.0, glm::length(centre)) * 1e-3;
    // A sphere of radius r whose centre lies on the view axis at distance d
    // is inside the frustum when d sin(h) >= r, h the smaller half-angle of
    // the two (vertical, horizontal); 1e-4 more leaves room for the float
    // rounding of the eye position.
    const double halfY = 0.5 * double(yfov);
    const double halfX = std::atan(double(aspect) * std::tan(halfY));
    const double distance = radius / std::sin(std::min(halfX, halfY)) * (1.0 + 1e-4);
    const double elevation = double(radians(kFrameElevationDegrees));
    const glm::dvec3 back(0.0, std::sin(elevation), std::cos(elevation));  // from the centre to the eye
    Camera cam;
    cam.position = glm::vec3(centre + back * distance);
    cam.forward = glm::vec3(-back);
    cam.up = glm::vec3(glm::normalize(glm::cross(glm::cross(-back, glm::dvec3(0, 1, 0)), -back)));
    cam.yfov = yfov;
    cam.name = "default view";
    return cam;
}

Camera lookAtCamera(const std::string& file, glm::vec3 from, glm::vec3 at, glm::vec3 up, float yfov) {
    const glm::dvec3 dir = glm::dvec3(at) - glm::dvec3(from);
    if (!(glm::length(dir) > 0.0)) fail(file, "--look-from and --look-at are the same point " + pointText(from));
    const glm::dvec3 forward = glm::normalize(dir);
    const glm::dvec3 side = glm::cross(forward, glm::dvec3(up));
    if (!(glm::length(side) > 1e-6 * glm::length(glm::dvec3(up))))
        fail(file, "--up " + pointText(up) + " is parallel to the view direction from --look-from to --look-at");
    Camera cam;
    cam.position = from;
    cam.forward = glm::vec3(forward);
    cam.up = glm::vec3(glm::normalize(glm::cross(glm::normalize(side), forward)));
    cam.yfov = yfov;
    cam.name = "--look-from";
    return cam;
}

Camera chooseCamera(const Scene& scene, const ViewOptions& view, int width, int height) {
    const bool hasCamera = !scene.cameras.empty();
    if (hasCamera && (view.camera < 0 || static_cast<std::size_t>(view.camera) >= scene.cameras.size()))
        fail(scene.path, "--camera " + std::to_string(view.camera) + " does not exist (the scene has " +
                             std::to_string(scene.cameras.size()) + " camera(s))");
    if (!hasCamera && view.camera != 0)
        fail(scene.path, "--camera " + std::to_string(view.camera) + " does not exist (the scene has no camera)");
    const float fov = view.fovDegrees ? radians(*view.fovDegrees)
                      : hasCamera     ? scene.cameras[static_cast<std::size_t>(view.camera)].yfov
                                      : radians(kFrameYfovDegrees);
    if (view.lookGiven())
        return lookAtCamera(scene.path, *view.lookFrom, *view.lookAt, view.up.value_or(glm::vec3(0, 1, 0)), fov);
    if (hasCamera) {
        Camera cam = scene.cameras[static_cast<std::size_t>(view.camera)];
        cam.yfov = fov;
        return cam;
    }
    const Camera cam = frameScene(scene, float(width) / float(height), fov);
    char fovText[32];
    std::snprintf(fovText, sizeof fovText, "%g", double(view.fovDegrees.value_or(kFrameYfovDegrees)));
    warn(scene.path, std::string("no camera: viewing the whole scene from the front and ") +
                         std::to_string(int(kFrameElevationDegrees)) + " degrees above, from " +
                         pointText(cam.position) + " (vertical field of view " + fovText +
                         " degrees); --look-from and --look-at choose another view");
    return cam;
}

}  // namespace strata
