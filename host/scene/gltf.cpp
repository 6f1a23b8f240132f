// glTF 2.0 (.gltf / .glb) -> Scene: the default scene's node hierarchy is
// flattened into world-space triangles and cameras.
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>

#include "scene/gltf_deform.h"
#include "scene/gltf_internal.h"
#include "scene/gltf_motion.h"
#include "scene/media_check.h"
#include "scene/scene.h"
#include "scene/tangents.h"
#include "util/files.h"
#include "util/error.h"
#include "util/files.h"
#include "util/memory.h"

namespace strata {

namespace {

using gltf::LocalMesh;
using gltf::LocalPrimitive;
using gltf::nodeName;
using gltf::quoted;

// Used where a normal cannot be computed (zero-area triangle, degenerate
// transform); any unit vector is valid for a triangle that is never hit.
constexpr glm::dvec3 kFallbackNormal{0.0, 0.0, 1.0};

std::optional<glm::dvec3> tryNormalize(const glm::dvec3& v) {
    const double len = glm::length(v);
    if (!(len > 0.0) || !std::isfinite(len)) return std::nullopt;
    return v / len;
}

bool isFinite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

class SceneBuilder {
public:
    SceneBuilder(const std::string& path, const tinygltf::Model& model, Scene& scene)
        : path_(path), model_(model), scene_(scene), meshes_(model.meshes.size()) {}

    // Depth-first, parents before children, children in file order. The
    // nodes are listed first, so the triangles are allocated once.
    void walk(int sceneIndex) {
        const std::vector<gltf::NodeVisit> visits =
            gltf::walkNodes(path_, model_, sceneIndex, [&](int node, int parent) {
                timeline_->setParent(node, parent);
                if (frames_) targets_.hierarchy.push_back({node, parent});
                return timeline_->localAtOpen(node, gltf::nodeTransform(path_, model_, node));
            });
        // Each mesh's placements (a node, or each of its EXT_mesh_gpu_instancing
        // instances) decide whether it is flattened or instanced.
        std::vector<gltf::GpuInstances> gpu(visits.size());
        const std::size_t meshCount = model_.meshes.size();
        std::vector<std::size_t> placements(meshCount, 0), meshTriangles(meshCount, 0), meshEmitters(meshCount, 0);
        std::vector<char> eligible(meshCount, 1), moving(meshCount, 0), emits(meshCount, 0);
        for (std::size_t k = 0; k < visits.size(); ++k) {
            const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(visits[k].node)];
            const int mesh = node.mesh;
            if (!visits[k].visible) continue;  // KHR_node_visibility: not rendered
            if (mesh < 0 || static_cast<std::size_t>(mesh) >= meshCount) continue;  // visit reports it
            decodedMesh(mesh);  // in the order the meshes are reached (skippedPrimitives)
            placements[std::size_t(mesh)] += std::max<std::size_t>(1, gltf::gpuInstanceCount(model_, visits[k].node));
            if (node.skin >= 0) eligible[std::size_t(mesh)] = 0;
            if ((timeline_->blurs() || frames_) && timeline_->animated(visits[k].node)) moving[std::size_t(mesh)] = 1;
        }
        std::size_t stillMoving = 0;  // moving meshes that cannot be instanced
        gltf::SceneSize size;
        instanced_.assign(meshCount, 0);
        emits_.assign(meshCount, 0);
        for (std::size_t m = 0; m < meshCount; ++m) {
            if (placements[m] == 0) continue;
            for (const LocalPrimitive& prim : decodedMesh(int(m)).primitives) {
                meshTriangles[m] += prim.indices.size() / 3;
                if (prim.material >= 0 && isEmissive(scene_.materials[std::size_t(prim.material)]))
                    emits[m] = 1, meshEmitters[m] += prim.indices.size() / 3;
            }
            for (const tinygltf::Primitive& prim : model_.meshes[m].primitives)
                if (!prim.targets.empty()) eligible[m] = 0;  // each node may pose it differently
            std::size_t placed = 0;
            if (__builtin_mul_overflow(placements[m], meshTriangles[m], &placed)) placed = SIZE_MAX;
            // Each triangle of an emitting mesh is a light of its own: it is
            // flattened, unless it moves.
            bool instance = eligible[m] && !emits[m] && placements[m] >= 2 && instancing_ != Instancing::Off;
            if (instancing_ == Instancing::Auto) instance = instance && placed > kInstancingMinTriangles;
            // A mesh that moves during the shutter is instanced: its placements
            // carry MotionKeys. An emitting one gets a copy per placement
            // (place), whose triangles are that placement's lights.
            if (moving[m] && eligible[m]) instance = true;
            // Its lights are posed anew for each frame by loading it anew.
            if (moving[m] && emits[m] && frames_) targets_.complete = false;
            if (moving[m] && !eligible[m]) ++stillMoving, targets_.complete = false;
            instanced_[m] = instance;
            emits_[m] = emits[m];
            // A flattened mesh's triangles, and the copies of an emitting one, are each stored.
            if ((!instance || emits[m]) && __builtin_add_overflow(size.triangles, placed, &size.triangles))
                size.triangles = SIZE_MAX;
            std::size_t lights = 0;
            if (__builtin_mul_overflow(placements[m], meshEmitters[m], &lights) ||
                __builtin_add_overflow(size.emitters, lights, &size.emitters))
                size.emitters = SIZE_MAX;
            if (instance) size.instances += placements[m];  // a node adds at most max(2^20, its buffers' bytes): no overflow
        }
        size.placements = visits.size();
        gltf::checkSceneSize(path_, size, budget_);
        // Their count checked above; a mesh without triangles (every
        // primitive skipped) places nothing, so its instances go unread.
        for (std::size_t k = 0; k < visits.size(); ++k) {
            const int mesh = model_.nodes[static_cast<std::size_t>(visits[k].node)].mesh;
            const bool empty = mesh >= 0 && std::size_t(mesh) < meshCount && meshTriangles[std::size_t(mesh)] == 0;
            if (visits[k].visible && !empty)
                gpu[k] = gltf::readGpuInstances(path_, model_, visits[k].node, nodeName(model_, visits[k].node));
        }
        if (stillMoving > 0 && timeline_->blurs())
            warn(path_, std::to_string(stillMoving) + " moving mesh(es) are skinned or have morph targets: "
                        "rendered at the pose at the shutter's open, without motion blur");
        reserveHuge(scene_.triangles, size.triangles);
        for (std::size_t k = 0; k < visits.size(); ++k) visit(visits[k].node, visits[k].world, gpu[k], visits[k].visible);
        // The instanced meshes' own triangles after the world's, once per
        // winding their placements need.
        std::vector<std::pair<SharedKey, std::uint32_t>> order(shared_.begin(), shared_.end());
        std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
        for (const auto& [key, index] : order) {
            SharedMesh m;
            m.first = scene_.triangles.size();
            addMesh(key.node, glm::dmat4(1.0), key.mirrored);
            m.count = scene_.triangles.size() - m.first;
            const int mesh = model_.nodes[std::size_t(key.node)].mesh;
            m.name = gltf::meshLabel(model_, mesh) + (key.mirrored ? " (mirrored)" : "") +
                     (key.copy > 0 ? " (placement " + std::to_string(key.copy) + ")" : "");
            m.lights = key.copy > 0;
            scene_.sharedMeshes.push_back(m);
        }
    }

    void setInstancing(Instancing mode) { instancing_ = mode; }
    void setBudget(const LoadOptions& options) {
        budget_.hostMemory = options.hostMemory;
        budget_.deviceMemory = options.deviceMemory;
    }
    // `frames`: every animated mesh is instanced and the poser's targets recorded.
    void setTimeline(gltf::NodeTimeline& timeline, bool frames) {
        timeline_ = &timeline;
        frames_ = frames;
    }
    gltf::PoseTargets& poseTargets() { return targets_; }

    bool usesDefaultMaterial() const { return usesDefault_; }
    std::size_t zeroLights() const { return zeroLights_; }

    // The primitives skipped as not triangles (points, lines), in the order
    // their meshes were first reached: `N primitive(s) that are not
    // triangles: mesh 1 ("Wire") primitive 0 (LINES), ...`, the first three
    // named; empty when none.
    std::string skippedPrimitives() const { return listed(skipped_, " primitive(s) that are not triangles: "); }

    // The primitives glTF 2.0 says not to render (no POSITION; a
    // non-indexed triangle list whose count is not a multiple of 3), listed
    // the same way.
    std::string invalidPrimitives() const {
        return listed(invalid_, " primitive(s) that glTF 2.0 says not to render: ");
    }

    // One warning each, after the walk: zero-power lights dropped, ranges ignored.
    void warnLights() const {
        if (zeroLights_ > 0)
            warn(path_, std::to_string(zeroLights_) +
                            " punctual light(s) have zero intensity or a black color; they emit nothing and are dropped");
        if (rangeIgnored_ > 0)
            warn(path_, std::to_string(rangeIgnored_) +
                            " punctual light(s) give a range; strata ignores it (falloff is 1/d^2 to infinity)");
    }

private:
    // COLOR_0 of a primitive without it, in a scene where another has it.
    static inline const TriangleColors kWhite = {glm::vec4(1.0f), glm::vec4(1.0f), glm::vec4(1.0f)};
    // Tangents of a primitive without normal map: unused, any unit vector.
    static inline const TriangleTangents kNoTangents = {glm::vec4(1, 0, 0, 1), glm::vec4(1, 0, 0, 1),
                                                     glm::vec4(1, 0, 0, 1)};

    // Checks that the primitive has every TEXCOORD set its material's
    // textures read; drops TANGENT when the material has no normal map
    // (normalTexture, clearcoatNormalTexture) and no anisotropy, and
    // generates tangents (tangents.h) when it has one and no TANGENT. Runs
    // on the cached local primitive, so once per mesh in practice.
    void prepareTextureInputs(int mesh, LocalPrimitive& prim) {
        const MaterialDesc& m = scene_.materials[static_cast<std::size_t>(prim.material)];
        for (const auto& [slot, name] : m.textureSlots()) {
            if (slot->used() && prim.texcoord(slot->texCoord).empty()) {
                fail(path_, gltf::meshLabel(model_, mesh) + " primitive " + std::to_string(prim.index) +
                                ": material " + std::to_string(prim.material) + " " + name +
                                " reads TEXCOORD_" + std::to_string(slot->texCoord) +
                                ", which the primitive does not have");
            }
        }
        // One tangent frame serves both normal maps and the anisotropy
        // (generated from the normalTexture's set, else the
        // clearcoatNormalTexture's, else the anisotropyTexture's or
        // TEXCOORD_0; without texture coordinates any frame about the normal).
        const TextureSlot& mapped = m.normalTexture.used() ? m.normalTexture : m.clearcoatNormalTexture;
        if (!mapped.used() && !m.anisotropic()) {
            prim.tangents.clear();
        } else if (prim.tangents.empty()) {
            const int set = mapped.used() ? mapped.texCoord : m.anisotropyTexture.used() ? m.anisotropyTexture.texCoord : 0;
            const std::vector<glm::vec2>& uvs = prim.texcoord(set);
            prim.tangents = generateTangents(prim.positions, prim.normals,
                                             uvs.empty() ? std::vector<glm::vec2>(prim.positions.size()) : uvs,
                                             prim.indices);
        }
    }

    // The material's two TEXCOORD sets (MaterialDesc::uvSets) of each vertex.
    static TriangleUv uvsOf(const LocalPrimitive& prim, const std::array<int, 2>& sets,
                            const std::array<std::uint32_t, 3>& idx) {
        TriangleUv uv{};
        for (int k = 0; k < 3; ++k) {
            for (int set = 0; set < 2; ++set) {
                const std::vector<glm::vec2>& values = prim.texcoord(sets[static_cast<std::size_t>(set)]);
                if (values.empty()) continue;
                const glm::vec2 t = values[idx[static_cast<std::size_t>(k)]];
                uv[static_cast<std::size_t>(k)][2 * set] = t.x;
                uv[static_cast<std::size_t>(k)][2 * set + 1] = t.y;
            }
        }
        return uv;
    }

    // Tangents go to world space by the node's linear part (not the normal
    // matrix), stay unit, and flip handedness under a mirroring transform
    // (then cross(n', M t) = -M b). A tangent that vanishes falls back to
    // one orthogonal to the vertex normal.
    static TriangleTangents worldTangents(const LocalPrimitive& prim,
                                          const std::array<std::uint32_t, 3>& idx,
                                          const glm::dmat3& linear, bool flip, const Triangle& tri) {
        TriangleTangents out{};
        for (int k = 0; k < 3; ++k) {
            const glm::vec4 t = prim.tangents[idx[static_cast<std::size_t>(k)]];
            const auto world = tryNormalize(linear * glm::dvec3(t));
            const glm::vec3 xyz = world ? glm::vec3(*world) : anyOrthogonal(tri.n[k]);
            out[static_cast<std::size_t>(k)] = glm::vec4(xyz, flip ? -t.w : t.w);
        }
        return out;
    }

    LocalMesh& decodedMesh(int mesh) {
        auto& decoded = meshes_[static_cast<std::size_t>(mesh)];
        if (!decoded) {
            decoded = gltf::decodeMesh(path_, model_, mesh);
            skipped_.insert(skipped_.end(), decoded->skipped.begin(), decoded->skipped.end());
            invalid_.insert(invalid_.end(), decoded->invalid.begin(), decoded->invalid.end());
        }
        return *decoded;
    }

    // A node's camera, mesh and light; a hidden one's camera alone (KHR_node_visibility).
    void visit(int nodeIndex, const glm::dmat4& world, const gltf::GpuInstances& gpu, bool visible) {
        const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
        if (node.camera >= 0 || node.camera < -1) addCamera(nodeIndex, world);
        if (!visible) return;
        if (node.mesh >= 0 || node.mesh < -1) {
            if (gpu.count == 0) {
                place(nodeIndex, world, glm::dmat4(1.0), nodeName(model_, nodeIndex));
            } else {
                for (std::size_t i = 0; i < gpu.count; ++i)
                    place(nodeIndex, world * gpu.local(i), gpu.local(i),
                          nodeName(model_, nodeIndex) + " instance " + std::to_string(i));
            }
        }
        const int light = gltf::nodeLight(path_, model_, nodeIndex, nodeName(model_, nodeIndex));
        if (light >= 0) addLight(nodeIndex, light, world);
        if (light >= 0 && frames_ && timeline_->animated(nodeIndex)) targets_.complete = false;
    }

    void addLight(int nodeIndex, int light, const glm::dmat4& world) {
        const PunctualLight l =
            gltf::convertLight(path_, model_, light, world, nodeName(model_, nodeIndex));
        const glm::vec3 i = l.intensityRgb();
        if (!(i.x > 0.0f || i.y > 0.0f || i.z > 0.0f)) {
            ++zeroLights_;
            return;
        }
        if (model_.lights[static_cast<std::size_t>(light)].range != 0.0) ++rangeIgnored_;
        scene_.lights.push_back(l);
    }

    void addCamera(int nodeIndex, const glm::dmat4& world) {
        const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
        if (static_cast<std::size_t>(node.camera) >= model_.cameras.size()) {
            fail(path_, nodeName(model_, nodeIndex) + ": camera " + std::to_string(node.camera) +
                            " does not exist (" + std::to_string(model_.cameras.size()) +
                            " cameras)");
        }
        const tinygltf::Camera& src = model_.cameras[static_cast<std::size_t>(node.camera)];
        std::string label = "camera " + std::to_string(node.camera);
        if (!src.name.empty()) label += " (" + quoted(src.name) + ")";
        if (src.type == "orthographic") {
            fail(path_, label + " is orthographic; only perspective cameras are supported");
        }
        if (src.type != "perspective") {
            fail(path_,
                 label + ": type " + quoted(src.type) + " is not supported; only perspective");
        }
        const double yfov = src.perspective.yfov;
        if (!(yfov > 0.0 && yfov < std::numbers::pi)) {
            std::ostringstream msg;
            msg << label << ": yfov " << yfov << " is outside (0, pi) radians";
            fail(path_, msg.str());
        }
        // Camera space: looks down -Z, +Y up. Normalising removes any scale.
        Camera camera;
        if (!gltf::cameraFromWorld(world, camera)) {
            fail(path_, label + " on " + nodeName(model_, nodeIndex) +
                            ": degenerate world transform (zero scale or not finite)");
        }
        camera.yfov = static_cast<float>(yfov);
        camera.name = !src.name.empty() ? src.name : node.name;
        camera.motion = timeline_->cameraKeys(nodeIndex, label + " on " + nodeName(model_, nodeIndex));
        if (frames_ && timeline_->animated(nodeIndex))
            targets_.cameras.push_back({scene_.cameras.size(), nodeIndex, label + " on " + nodeName(model_, nodeIndex)});
        scene_.cameras.push_back(camera);
    }

    // A placement of the node's mesh (world: at the shutter's open; local:
    // its EXT_mesh_gpu_instancing transform under the node): an instance of
    // its shared copy, with its MotionKeys when it moves, or its triangles in
    // world space.
    void place(int nodeIndex, const glm::dmat4& world, const glm::dmat4& local, const std::string& label) {
        const int mesh = model_.nodes[static_cast<std::size_t>(nodeIndex)].mesh;
        const bool known = mesh >= 0 && std::size_t(mesh) < instanced_.size();
        const double det = glm::determinant(glm::dmat3(world));
        bool finite = true;
        for (int c = 0; c < 4; ++c) finite = finite && isFinite(glm::dvec3(world[c]));
        // A degenerate or non-finite placement is flattened (addMesh reports it).
        if (!known || !instanced_[std::size_t(mesh)] || !finite || det == 0.0) {
            if (frames_ && timeline_->animated(nodeIndex)) targets_.complete = false;
            addMesh(nodeIndex, world);
            return;
        }
        const SharedKey key{mesh, det < 0.0, nodeIndex, emits_[std::size_t(mesh)] ? ++copies_ : 0};
        auto it = shared_.find(key);
        if (it == shared_.end()) it = shared_.emplace(key, std::uint32_t(shared_.size())).first;
        scene_.instances.push_back({it->second, glm::mat4(world), timeline_->keys(nodeIndex, local, label)});
        if (frames_ && timeline_->animated(nodeIndex))
            targets_.placements.push_back({scene_.instances.size() - 1, nodeIndex, local, label});
    }

    void addMesh(int nodeIndex, const glm::dmat4& world, bool reverseWinding = false) {
        const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
        if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
            fail(path_, nodeName(model_, nodeIndex) + ": mesh " + std::to_string(node.mesh) +
                            " does not exist (" + std::to_string(model_.meshes.size()) +
                            " meshes)");
        }
        std::vector<LocalPrimitive>& decoded = decodedMesh(node.mesh).primitives;
        // Morph targets and skins: the node's pose of the mesh (gltf_deform.h).
        const gltf::NodePose pose(path_, model_, nodeIndex, decodedMesh(node.mesh));
        LocalPrimitive posed;
        const glm::dmat4 placed = pose.skinned() ? glm::dmat4(1.0) : world;  // skinned: in world space

        const glm::dmat3 linear(placed);
        const double det = glm::determinant(linear);
        // Cofactor matrix = det * inverse transpose; signed so it points the
        // same way as the inverse transpose, and defined for det == 0.
        const glm::dmat3 normalMatrix =
            glm::dmat3(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                       glm::cross(linear[0], linear[1])) *
            (det < 0.0 ? -1.0 : 1.0);
        const bool flip = (det < 0.0) != reverseWinding;

        std::vector<glm::dvec3> positions;
        std::vector<glm::dvec3> normals;
        for (LocalPrimitive& cached : decoded) {
            std::uint32_t material = 0;
            if (cached.material >= 0) prepareTextureInputs(node.mesh, cached);
            const LocalPrimitive& prim = pose.apply(cached, posed);
            if (prim.material >= 0) {
                material = static_cast<std::uint32_t>(prim.material);
            } else {
                material = static_cast<std::uint32_t>(model_.materials.size());
                usesDefault_ = true;
            }
            const std::array<int, 2> uvSets = scene_.materials.size() > material
                                                  ? scene_.materials[material].uvSets
                                                  : std::array<int, 2>{0, 1};
            const bool storeUv = !scene_.texcoords.empty() || !prim.texcoord(uvSets[0]).empty() ||
                                 !prim.texcoord(uvSets[1]).empty();
            const bool storeTangents = !scene_.tangents.empty() || !prim.tangents.empty();
            const bool storeColors = !scene_.colors.empty() || !prim.colors.empty();
            if (storeColors) scene_.colors.resize(scene_.triangles.size(), kWhite);
            if (storeUv) scene_.texcoords.resize(scene_.triangles.size(), TriangleUv{});
            if (storeTangents) scene_.tangents.resize(scene_.triangles.size(), kNoTangents);
            positions.resize(prim.positions.size());
            for (std::size_t i = 0; i < prim.positions.size(); ++i) {
                positions[i] = glm::dvec3(placed * glm::dvec4(glm::dvec3(prim.positions[i]), 1.0));
                if (!isFinite(positions[i])) {
                    fail(path_, gltf::meshLabel(model_, node.mesh) + " on " +
                                    nodeName(model_, nodeIndex) + ": vertex " + std::to_string(i) +
                                    " is not finite in world space");
                }
            }
            normals.resize(prim.normals.size());
            for (std::size_t i = 0; i < prim.normals.size(); ++i) {
                normals[i] = normalMatrix * glm::dvec3(prim.normals[i]);
            }
            for (std::size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
                std::array<std::uint32_t, 3> idx = {prim.indices[t], prim.indices[t + 1],
                                                    prim.indices[t + 2]};
                // A mirroring transform reverses the winding; swapping two
                // vertices keeps the front face (CCW) the front face.
                if (flip) std::swap(idx[1], idx[2]);
                Triangle tri;
                tri.material = material;
                const glm::dvec3 p0 = positions[idx[0]], p1 = positions[idx[1]],
                                 p2 = positions[idx[2]];
                const glm::dvec3 geometric =
                    tryNormalize(glm::cross(p1 - p0, p2 - p0)).value_or(kFallbackNormal);
                for (int k = 0; k < 3; ++k) {
                    tri.v[k] = glm::vec3(positions[idx[static_cast<std::size_t>(k)]]);
                    const glm::dvec3 n =
                        normals.empty() ? geometric
                                        : tryNormalize(normals[idx[static_cast<std::size_t>(k)]])
                                              .value_or(geometric);
                    tri.n[k] = glm::vec3(n);
                }
                scene_.triangles.push_back(tri);
                if (storeUv) scene_.texcoords.push_back(uvsOf(prim, uvSets, idx));
                if (storeColors) {
                    scene_.colors.push_back(kWhite);
                    for (std::size_t k = 0; k < 3 && !prim.colors.empty(); ++k) scene_.colors.back()[k] = prim.colors[idx[k]];
                }
                if (storeTangents) {
                    scene_.tangents.push_back(prim.tangents.empty()
                                                  ? kNoTangents
                                                  : worldTangents(prim, idx, linear, flip, tri));
                }
            }
        }
    }

    // A mesh's shared copy: a placement that mirrors gets one with the
    // winding reversed, and each placement of an emitting mesh one of its
    // own (`copy` > 0: its triangles are that placement's lights). `node` is
    // the first node that placed it (for the labels; such meshes have no
    // skin or morph targets, so any node poses them alike) and takes no
    // part in the order.
    struct SharedKey {
        int mesh;
        bool mirrored;
        int node;
        std::size_t copy;
        bool operator<(const SharedKey& o) const {
            if (mesh != o.mesh) return mesh < o.mesh;
            return mirrored != o.mirrored ? mirrored < o.mirrored : copy < o.copy;
        }
    };

    const std::string& path_;
    const tinygltf::Model& model_;
    Scene& scene_;
    Instancing instancing_ = Instancing::Auto;
    gltf::SizeBudget budget_;
    gltf::NodeTimeline* timeline_ = nullptr;
    bool frames_ = false;
    gltf::PoseTargets targets_;
    std::vector<char> instanced_;                    // per mesh: placed by instances
    std::vector<char> emits_;                        // per mesh: some primitive's material emits
    std::size_t copies_ = 0;                         // SharedKey::copy of the last emitting placement
    std::map<SharedKey, std::uint32_t> shared_;      // -> index into scene_.sharedMeshes
    std::vector<std::optional<LocalMesh>> meshes_;  // decoded on first use
    std::vector<std::string> skipped_;              // LocalMesh::skipped of each decoded mesh
    std::vector<std::string> invalid_;              // LocalMesh::invalid of each decoded mesh

    // "N<what>first, second, third and M more".
    static std::string listed(const std::vector<std::string>& items, const std::string& what) {
        if (items.empty()) return {};
        constexpr std::size_t kNamed = 3;
        std::string out = std::to_string(items.size()) + what;
        for (std::size_t i = 0; i < std::min(items.size(), kNamed); ++i) out += (i == 0 ? "" : ", ") + items[i];
        if (items.size() > kNamed) out += " and " + std::to_string(items.size() - kNamed) + " more";
        return out;
    }
    bool usesDefault_ = false;
    std::size_t zeroLights_ = 0;
    std::size_t rangeIgnored_ = 0;
};

}  // namespace

Scene loadGltf(const std::string& path, const LoadOptions& options) {
    if (!options.restrictPaths.empty()) {
        if (const std::string outside = outsideRoot(path, options.restrictPaths); !outside.empty())
            fail(path, "the scene resolves to " + outside + ", outside --restrict-paths " + options.restrictPaths);
    }
    return loadGltf(path, gltf::readSceneFile(path), options);
}

Scene loadGltf(const std::string& path, const std::vector<unsigned char>& bytes, const LoadOptions& options) {
    tinygltf::Model model = gltf::parseModel(path, bytes, options.restrictPaths, options.hostMemory);
    gltf::checkExtensions(path, model);
    gltf::decodeMeshoptViews(path, model);

    if (model.scenes.empty()) fail(path, "no scenes: the file defines no scene to load");
    const int sceneIndex = model.defaultScene == -1 ? 0 : model.defaultScene;
    if (sceneIndex < 0 || static_cast<std::size_t>(sceneIndex) >= model.scenes.size()) {
        fail(path, "default scene " + std::to_string(model.defaultScene) + " does not exist (" +
                       std::to_string(model.scenes.size()) + " scenes)");
    }

    Scene scene;
    scene.path = path;
    scene.extensionsUsed = model.extensionsUsed;
    scene.variants = gltf::readVariants(path, model);
    gltf::applyVariant(path, model, scene.variants, options.variant);
    scene.variant = options.variant;
    gltf::convertTextures(path, model, scene);
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        scene.materials.push_back(gltf::convertMaterial(path, model, static_cast<int>(i)));
    }
    gltf::warnTextureFallbacks(path, model, scene.materials);
    gltf::warnUnreadMaterialTextures(path, model);
    std::optional<gltf::Animation> animation;
    if (options.motion.enabled && model.animations.empty() && options.motion.animation.empty())
        warn(path, "no animations in the file: --shutter poses nothing and blurs nothing");
    else if (options.motion.enabled)
        animation = gltf::Animation::load(path, model, options.motion.animation);
    gltf::NodeTimeline timeline(path, model, animation ? &*animation : nullptr, options.motion);
    SceneBuilder builder(path, model, scene);
    builder.setInstancing(options.instancing);
    builder.setBudget(options);
    builder.setTimeline(timeline, options.motion.frames && animation);
    builder.walk(sceneIndex);
    if (options.motion.frames && animation && builder.poseTargets().complete)
        scene.poser = gltf::makePoser(path, model, std::move(*animation), std::move(builder.poseTargets()));
    const std::string skipped = builder.skippedPrimitives(), invalid = builder.invalidPrimitives();
    if (scene.triangles.empty() && !skipped.empty()) fail(path, "no triangles to render: skipped " + skipped);
    if (scene.triangles.empty() && !invalid.empty()) fail(path, "no triangles to render: skipped " + invalid);
    if (builder.usesDefaultMaterial() || scene.materials.empty()) {
        MaterialDesc fallback;  // glTF defaults
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }

    std::size_t emitters = 0;
    for (const Triangle& t : scene.triangles) {
        if (isEmitter(scene, t)) {
            ++emitters;
        } else if (isEmissive(scene.materials[t.material])) {
            ++scene.droppedEmitters;
        }
    }
    const std::string dropped =
        std::to_string(scene.droppedEmitters) + " emissive triangle(s) have zero area";
    const bool unlit = emitters == 0 && scene.lights.empty() && !options.externalLight;
    if (unlit && options.defaultLight && scene.droppedEmitters == 0 && builder.zeroLights() == 0) {
        // Nothing in the file emits or was meant to: what glTF viewers show.
        scene.environment.enabled = true;
        scene.environment.source = kDefaultEnvironment;
        scene.environment.scale = glm::vec3(1.0f);
        warn(path, "no light: lighting the scene with a uniform white environment of radiance 1; --env or "
                   "--env-color sets another");
    } else if (options.requireEmitter && unlit) {
        std::string msg =
            "no light: no triangle has an emissive material (emissiveFactor * emissiveStrength > 0)"
            " and a non-zero area, no node has a KHR_lights_punctual light, and no --env is given";
        if (scene.droppedEmitters > 0) msg += "; " + dropped;
        if (builder.zeroLights() > 0)
            msg += "; " + std::to_string(builder.zeroLights()) + " punctual light(s) have zero intensity or a black color";
        fail(path, msg);
    }
    builder.warnLights();
    const std::string inside = surfacesInsideMedia(scene);
    if (!inside.empty()) warn(path, inside);
    if (!skipped.empty()) warn(path, "skipped " + skipped);
    if (!invalid.empty()) warn(path, "skipped " + invalid);
    if (scene.droppedEmitters > 0) {
        warn(path, dropped + "; they are kept as geometry but emit no light");
    }
    return scene;
}

}  // namespace strata
