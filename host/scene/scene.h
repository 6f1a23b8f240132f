// The scene as the host sees it after loading: flat arrays in world space.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace strata {

struct Camera {
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit, camera's local -Z
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, camera's local +Y
    float yfov = 0.8f;                     // radians
    std::string name;
};

// glTF material, all factors kept even where the renderer does not use them
// yet. `emission` = emissiveFactor * KHR_materials_emissive_strength.
struct MaterialDesc {
    std::string name;
    glm::vec4 baseColor{1.0f};
    float metallic = 1.0f;
    float roughness = 1.0f;
    glm::vec3 emissiveFactor{0.0f};
    float emissiveStrength = 1.0f;
    float ior = 1.5f;
    bool doubleSided = false;
    enum class AlphaMode { Opaque, Mask, Blend } alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    glm::vec3 emission() const { return emissiveFactor * emissiveStrength; }
};

// One triangle in world space. Normals are unit length; a triangle from a
// primitive without NORMAL repeats its geometric normal.
struct Triangle {
    glm::vec3 v[3];
    glm::vec3 n[3];
    std::uint32_t material = 0;
};

struct Scene {
    std::string path;                 // file it was loaded from (for messages)
    std::vector<Triangle> triangles;
    std::vector<MaterialDesc> materials;  // always at least one (the default)
    std::vector<Camera> cameras;      // in node order (depth-first)
    std::vector<std::string> extensionsUsed;
    std::size_t droppedEmitters = 0;  // zero-area emissive triangles dropped at load
};

struct LoadOptions {
    bool requireCamera = true;
    bool requireEmitter = true;
};

// Loads .gltf or .glb. Throws strata::Error with a one-line message naming the
// file and the problem.
Scene loadGltf(const std::string& path, const LoadOptions& options = {});

}  // namespace strata
