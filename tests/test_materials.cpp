// Render tests of the glTF BSDF in the path tracer against known answers
// (scenes from scripts/make_material_tests.py).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/glm.hpp>

#include "test_util.h"

using namespace strata;
using namespace strata::test;

namespace {

// scripts/make_material_tests.py
constexpr float kLampHalf = 0.5f;
constexpr float kLampHeight = 1.0f;
constexpr float kLampLe = 2.0f;

// Fresnel reflectance of a dielectric (relative index eta) for unpolarised
// light at incidence cosine c (Born & Wolf).
double fresnel(double c, double eta) {
    const double s2 = (1.0 - c * c) / (eta * eta);
    if (s2 >= 1.0) return 1.0;
    const double t = std::sqrt(1.0 - s2);
    const double rs = (c - eta * t) / (c + eta * t), rp = (eta * c - t) / (eta * c + t);
    return 0.5 * (rs * rs + rp * rp);
}

// The camera ray through image point (x, y) in pixels, as pathtrace.comp makes it.
glm::dvec3 cameraRay(const Camera& cam, int w, int h, double x, double y) {
    const double tanHalf = std::tan(cam.yfov * 0.5);
    const double aspect = double(w) / h;
    const glm::dvec3 f(cam.forward), right = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
    const glm::dvec3 up = glm::cross(right, f);
    const double nx = 2.0 * x / w - 1.0, ny = 1.0 - 2.0 * y / h;
    return glm::normalize(f + nx * tanHalf * aspect * right + ny * tanHalf * up);
}

struct Reflection {
    bool hitsLamp = false;
    double cosine = 0.0;  // incidence cosine on the floor
};

// The camera ray reflected by the floor y = 0 about its normal.
Reflection reflectOffFloor(const glm::dvec3& o, const glm::dvec3& d) {
    Reflection r;
    if (d.y >= 0.0) return r;
    const glm::dvec3 p = o + (-o.y / d.y) * d;
    if (std::abs(p.x) > 3.0 || std::abs(p.z) > 3.0) return r;
    const glm::dvec3 m(d.x, -d.y, d.z);
    const glm::dvec3 q = p + (kLampHeight / m.y) * m;
    r.hitsLamp = std::abs(q.x) < kLampHalf && std::abs(q.z) < kLampHalf;
    r.cosine = -d.y;
    return r;
}

// Renders the mirror scene at maxDepth 1 and checks every pixel whose
// footprint (box filter, radius 0.5) reflects entirely onto the lamp or
// entirely off it: Le * reflectance(cosine) and exactly 0.
void checkMirror(const char* scene, const std::function<double(double)>& reflectance) {
    RenderSettings s;
    s.width = s.height = 48;
    s.spp = 16;
    s.maxDepth = 1;
    const Rendered r = renderFile(scene, s);
    const Camera& cam = r.scene.cameras.at(0);
    const auto mean = r.result.film.mean();
    int lit = 0, dark = 0, wrong = 0;
    for (int py = 0; py < s.height; ++py) {
        for (int px = 0; px < s.width; ++px) {
            int inside = 0, total = 0;
            double lo = 1e9, hi = -1e9, sum = 0.0;
            for (int j = 0; j <= 8; ++j) {
                for (int i = 0; i <= 8; ++i) {
                    const glm::dvec3 d = cameraRay(cam, s.width, s.height, px + i / 8.0, py + j / 8.0);
                    const Reflection ref = reflectOffFloor(glm::dvec3(cam.position), d);
                    ++total;
                    if (!ref.hitsLamp) continue;
                    ++inside;
                    const double v = kLampLe * reflectance(ref.cosine);
                    lo = std::min(lo, v), hi = std::max(hi, v), sum += v;
                }
            }
            const std::size_t k = (std::size_t(py) * s.width + px) * 3;
            if (inside == total) {
                ++lit;
                for (int c = 0; c < 3; ++c) {
                    if (mean[k + c] < lo - 1e-5 * hi || mean[k + c] > hi * (1.0 + 1e-5)) {
                        if (++wrong <= 5) MESSAGE("pixel " << px << "," << py << ": " << mean[k + c]
                                                           << " outside [" << lo << ", " << hi << "]");
                    }
                }
            } else if (inside == 0) {
                ++dark;
                for (int c = 0; c < 3; ++c) wrong += mean[k + c] != 0.0;
            }
        }
    }
    MESSAGE(std::string(scene) << ": " << lit << " pixels on the lamp's image, " << dark << " off it, " << wrong
                  << " wrong");
    CHECK(lit > 100);
    CHECK(dark > 100);
    CHECK(wrong == 0);
    CHECK(vk::validationMessageCount() == 0);
}

}  // namespace

TEST_CASE("a white metal of roughness 0 and 1e-4 is an exact mirror: the lamp's image at full radiance, no NaN") {
    checkMirror("tests/data/materials/mirror-r0.gltf", [](double) { return 1.0; });
    checkMirror("tests/data/materials/mirror-r1e-4.gltf", [](double) { return 1.0; });
}

TEST_CASE("a smooth black dielectric reflects the lamp by the exact Fresnel factor of ior 1.5") {
    checkMirror("tests/data/materials/black-gloss.gltf", [](double c) { return fresnel(c, 1.5); });
}
