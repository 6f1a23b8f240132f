// Surfaces inside a medium, found by the parity of a ray's crossings with
// the medium's triangles (scene/media_check.h).
#include "scene/media_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "scene/gltf_internal.h"
#include "scene/scene.h"

namespace strata {
namespace {

// The rays' direction: no axis-aligned edge or face lies along it, so that a
// ray meets an edge shared by two triangles (counted twice) only by chance.
const glm::dvec3 kDirection = glm::normalize(glm::dvec3(0.2713, 0.8829, 0.3829));

struct Tri {
    glm::dvec3 a, e1, e2;
};

enum class Side { Outside, Inside, Boundary };

// One material's medium: its triangles in world space, their bounds, and a
// grid over their projection along kDirection listing the triangles that
// cover each cell (a ray from a point meets only those of its cell).
class Medium {
public:
    void add(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
        if (!finite(a) || !finite(b) || !finite(c)) return;  // a placement past float's range
        tris_.push_back({a, b - a, c - a});
        for (const glm::dvec3& p : {a, b, c}) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
    }

    // False when the grid would take more than `work` cell entries.
    bool build(double& work) {
        u_ = glm::normalize(glm::cross(kDirection, glm::dvec3(1.0, 0.0, 0.0)));
        w_ = glm::cross(kDirection, u_);
        eps_ = 1e-7 * std::max(glm::length(hi_ - lo_), 1e-30);
        glm::dvec2 lo(HUGE_VAL), hi(-HUGE_VAL);
        for (const Tri& t : tris_) {
            for (const glm::dvec3& p : {t.a, t.a + t.e1, t.a + t.e2}) {
                lo = glm::min(lo, project(p));
                hi = glm::max(hi, project(p));
            }
        }
        cells_ = static_cast<int>(std::clamp(std::ceil(std::sqrt(double(tris_.size()))), 1.0, 512.0));
        lo2_ = lo;
        size2_ = glm::max(hi - lo, glm::dvec2(1e-30)) / double(cells_);
        std::vector<std::uint32_t> count(std::size_t(cells_) * cells_ + 1, 0);
        for (int pass = 0; pass < 2; ++pass) {
            for (std::uint32_t i = 0; i < tris_.size(); ++i) {
                const Tri& t = tris_[i];
                glm::dvec2 a = project(t.a), b = project(t.a + t.e1), c = project(t.a + t.e2);
                const glm::ivec2 c0 = cell(glm::min(a, glm::min(b, c))), c1 = cell(glm::max(a, glm::max(b, c)));
                if (pass == 0) {
                    work += double(c1.x - c0.x + 1) * double(c1.y - c0.y + 1);
                    if (work > kMediaCheckWork) return false;
                }
                for (int y = c0.y; y <= c1.y; ++y) {
                    for (int x = c0.x; x <= c1.x; ++x) {
                        const std::size_t k = std::size_t(y) * cells_ + x;
                        if (pass == 0) ++count[k + 1];
                        else items_[start_[k] + fill_[k]++] = i;
                    }
                }
            }
            if (pass == 0) {
                for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
                start_ = std::move(count);
                items_.resize(start_.back());
                fill_.assign(start_.size(), 0);
            }
        }
        return true;
    }

    // Where p is; `work` counts the ray-triangle tests.
    Side side(const glm::dvec3& p, double& work) const {
        if (!finite(p) || glm::any(glm::lessThan(p, lo_ - eps_)) || glm::any(glm::greaterThan(p, hi_ + eps_)))
            return Side::Outside;
        const glm::ivec2 k = cell(project(p));
        const std::size_t c = std::size_t(k.y) * cells_ + k.x;
        bool inside = false;
        work += double(start_[c + 1] - start_[c]);
        for (std::uint32_t j = start_[c]; j < start_[c + 1]; ++j) {
            // Moller-Trumbore in double.
            const Tri& t = tris_[items_[j]];
            const glm::dvec3 pv = glm::cross(kDirection, t.e2);
            const double det = glm::dot(t.e1, pv);
            if (det == 0.0) continue;
            const glm::dvec3 tv = p - t.a;
            const double u = glm::dot(tv, pv) / det;
            if (u < 0.0 || u > 1.0) continue;
            const glm::dvec3 qv = glm::cross(tv, t.e1);
            const double v = glm::dot(kDirection, qv) / det;
            if (v < 0.0 || u + v > 1.0) continue;
            const double dist = glm::dot(t.e2, qv) / det;
            if (std::abs(dist) <= eps_) return Side::Boundary;
            if (dist > 0.0) inside = !inside;
        }
        return inside ? Side::Inside : Side::Outside;
    }

    bool empty() const { return tris_.empty(); }

private:
    static bool finite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
    glm::dvec2 project(const glm::dvec3& p) const { return {glm::dot(p, u_), glm::dot(p, w_)}; }
    glm::ivec2 cell(const glm::dvec2& q) const {
        const glm::dvec2 f = glm::clamp((q - lo2_) / size2_, glm::dvec2(0.0), glm::dvec2(cells_ - 1));
        return glm::ivec2(f);
    }

    std::vector<Tri> tris_;
    glm::dvec3 lo_{HUGE_VAL}, hi_{-HUGE_VAL};
    glm::dvec3 u_{0.0}, w_{0.0};
    double eps_ = 0.0;
    glm::dvec2 lo2_{0.0}, size2_{1.0};
    int cells_ = 1;
    std::vector<std::uint32_t> start_, items_, fill_;
};

std::string label(const Scene& scene, std::uint32_t material) {
    const std::string& name = scene.materials[material].name;
    return "material " + std::to_string(material) + (name.empty() ? "" : " (" + gltf::quoted(name) + ")");
}

// Calls visit(material, a, b, c) for every triangle in world space: the
// flattened ones, then each instance's copy of its mesh at its pose.
template <class Visit>
void forEachTriangle(const Scene& scene, Visit&& visit) {
    for (std::size_t i = 0; i < scene.worldTriangles(); ++i) {
        const Triangle& t = scene.triangles[i];
        visit(t.material, glm::dvec3(t.v[0]), glm::dvec3(t.v[1]), glm::dvec3(t.v[2]));
    }
    for (const MeshInstance& instance : scene.instances) {
        const SharedMesh& mesh = scene.sharedMeshes[instance.mesh];
        const glm::dmat4 m(instance.toWorld);
        for (std::size_t i = mesh.first; i < mesh.first + mesh.count; ++i) {
            const Triangle& t = scene.triangles[i];
            visit(t.material, glm::dvec3(m * glm::dvec4(t.v[0], 1.0)), glm::dvec3(m * glm::dvec4(t.v[1], 1.0)),
                  glm::dvec3(m * glm::dvec4(t.v[2], 1.0)));
        }
    }
}

}  // namespace

std::string surfacesInsideMedia(const Scene& scene) {
    std::map<std::uint32_t, Medium> media;
    for (std::uint32_t i = 0; i < scene.materials.size(); ++i) {
        if (scene.materials[i].hasVolume()) media[i];
    }
    if (media.empty()) return "";
    double work = 0.0;
    forEachTriangle(scene, [&](std::uint32_t material, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
        const auto it = media.find(material);
        if (it != media.end()) it->second.add(a, b, c), work += 1.0;
    });
    std::erase_if(media, [](const auto& entry) { return entry.second.empty(); });  // not placed
    for (auto& [material, medium] : media) {
        if (!medium.build(work)) return "";
    }
    std::map<std::uint32_t, std::size_t> inside;  // per medium material
    std::size_t total = 0;
    std::uint32_t firstMedium = 0, firstSurface = 0;
    bool gaveUp = false;
    forEachTriangle(scene, [&](std::uint32_t material, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
        if (gaveUp) return;
        const glm::dvec3 centroid = (a + b + c) / 3.0;
        for (const auto& [mediumMaterial, medium] : media) {
            if (material == mediumMaterial) continue;
            if (medium.side(centroid, work) == Side::Inside) {
                if (total == 0) firstMedium = mediumMaterial, firstSurface = material;
                ++inside[mediumMaterial];
                ++total;
                break;
            }
        }
        gaveUp = work > kMediaCheckWork;
    });
    if (total == 0) return "";
    std::string where = "the volume of " + label(scene, firstMedium);
    if (inside.size() > 1)
        where = "the volumes of " + std::to_string(inside.size()) + " media (first: " + label(scene, firstMedium) + ")";
    return std::to_string(total) + " triangle(s) lie inside " + where + " (first: one of " +
           label(scene, firstSurface) +
           "): strata does not nest media or render surfaces inside one; a path segment ending on them crosses "
           "no medium";
}

}  // namespace strata
