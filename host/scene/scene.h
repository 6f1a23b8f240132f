// The scene as the host sees it after loading: flat arrays in world space,
// and with instancing the meshes stored once and their placements.
#pragma once
#include <cmath>
#include <cstddef>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/geometric.hpp>

namespace strata {

// One pose of something that moves during the shutter (motion blur): its
// world transform at `time` (seconds on the animation's timeline) as T R S.
// Keys are in time order; between two the pose is interpolated (T and S
// linearly, R by slerp); two keys at one time are a jump (before, after).
struct MotionKey {
    float time = 0.0f;
    glm::vec3 translation{0.0f};
    glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // unit quaternion xyzw
    glm::vec3 scale{1.0f};
};

struct Camera {
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit, camera's local -Z
    glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, camera's local +Y, orthogonal to forward
    float yfov = 0.8f;                     // radians
    std::string name;                      // glTF camera name, else its node's name
    // An animated camera node over the shutter (LoadOptions::motion): its
    // position and orientation (scale 1; rotation takes camera space to
    // world space); empty when it does not move. At most gpu::kMaxCameraKeys.
    std::vector<MotionKey> motion;
};

// KHR_texture_transform of one texture reference: uv' = offset +
// R(rotation) (scale * uv), R rotating counter-clockwise by `rotation` radians
// as the ratified extension's GLSL does.
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;
    glm::vec2 scale{1.0f};
};

// A material's reference to Scene::textures; texture < 0 when the slot is empty.
// texCoord is the TEXCOORD set read (any n >= 0), after the
// KHR_texture_transform override.
struct TextureSlot {
    int texture = -1;
    int texCoord = 0;
    TextureTransform transform;
    bool used() const { return texture >= 0; }
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
    float transmission = 0.0f;  // KHR_materials_transmission transmissionFactor
    float specular = 1.0f;      // KHR_materials_specular specularFactor
    glm::vec3 specularColor{1.0f};   // KHR_materials_specular specularColorFactor (linear, may exceed 1)
    TextureSlot specularTexture;     // linear A: scales specular
    TextureSlot specularColorTexture;  // sRGB RGB: scales specularColor
    bool doubleSided = false;
    enum class AlphaMode { Opaque, Mask, Blend } alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    TextureSlot baseColorTexture;          // sRGB rgb, linear alpha
    TextureSlot metallicRoughnessTexture;  // linear: G roughness, B metallic
    TextureSlot normalTexture;             // linear, tangent space
    TextureSlot emissiveTexture;           // sRGB
    TextureSlot transmissionTexture;       // linear R (KHR_materials_transmission)
    float normalScale = 1.0f;              // normalTexture.scale
    // KHR_materials_unlit: the surface shows baseColor (factor x texture) and
    // does not scatter; the other properties, emission included, are ignored.
    bool unlit = false;
    // KHR_materials_volume: thicknessFactor (0: thin-walled, no volume), and
    // the Beer-Lambert attenuation inside: a path of length x keeps
    // attenuationColor^(x / attenuationDistance) (infinite distance: none).
    float thickness = 0.0f;
    float attenuationDistance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuationColor{1.0f};
    // KHR_materials_clearcoat: a GGX coat of ior 1.5 (0: none).
    float clearcoat = 0.0f;                // clearcoatFactor
    float clearcoatRoughness = 0.0f;       // clearcoatRoughnessFactor
    TextureSlot clearcoatTexture;          // linear R
    TextureSlot clearcoatRoughnessTexture; // linear G
    TextureSlot clearcoatNormalTexture;    // linear, tangent space
    float clearcoatNormalScale = 1.0f;     // clearcoatNormalTexture.scale
    bool coated() const { return clearcoat > 0.0f && !unlit; }
    // KHR_materials_sheen: a Charlie sheen over the base (sheenColor 0: none).
    glm::vec3 sheenColor{0.0f};            // sheenColorFactor, linear
    float sheenRoughness = 0.0f;           // sheenRoughnessFactor
    TextureSlot sheenColorTexture;         // sRGB RGB
    TextureSlot sheenRoughnessTexture;     // linear A
    // KHR_materials_iridescence: a thin film over the base's specular
    // reflection (iridescence 0: none). Thickness in nanometres: without a
    // thickness texture the maximum, with one mix(min, max, G).
    float iridescence = 0.0f;              // iridescenceFactor
    float iridescenceIor = 1.3f;           // the film's index
    float iridescenceThicknessMin = 100.0f;
    float iridescenceThicknessMax = 400.0f;
    TextureSlot iridescenceTexture;        // linear R: scales iridescence
    TextureSlot iridescenceThicknessTexture;  // linear G
    bool iridescent() const { return iridescence > 0.0f && !unlit; }
    // KHR_materials_diffuse_transmission: a Lambertian lobe through the
    // surface taking that share of the dielectric's diffuse light (0: none).
    float diffuseTransmission = 0.0f;                 // diffuseTransmissionFactor
    glm::vec3 diffuseTransmissionColor{1.0f};         // diffuseTransmissionColorFactor, linear
    TextureSlot diffuseTransmissionTexture;           // linear A: scales the factor
    TextureSlot diffuseTransmissionColorTexture;      // sRGB RGB: scales the colour
    bool diffuselyTransmitting() const { return diffuseTransmission > 0.0f && !unlit; }
    // A closed volume that attenuates (KHR_materials_volume: thickness > 0,
    // a finite distance, a colour below 1, on a transmitting dielectric):
    // a medium, the one rule for the loader's check and packing.
    bool hasVolume() const {
        return thickness > 0.0f && (transmission > 0.0f || diffuselyTransmitting()) && metallic < 1.0f && !unlit &&
               std::isfinite(attenuationDistance) && glm::any(glm::lessThan(attenuationColor, glm::vec3(1.0f)));
    }
    // KHR_materials_anisotropy: the base's GGX lobes stretched along a
    // direction of the tangent frame (strength 0: none).
    float anisotropyStrength = 0.0f;
    float anisotropyRotation = 0.0f;       // radians, counter-clockwise from the tangent
    TextureSlot anisotropyTexture;         // linear: RG direction in [-1, 1], B scales the strength
    bool anisotropic() const { return anisotropyStrength > 0.0f && !unlit; }
    // KHR_materials_volume_scatter (draft): the share of the volume's
    // attenuation that scatters, from the multi-scatter albedo (gpu_scene.cpp
    // singleScatterAlbedo), and the Henyey-Greenstein g of its events.
    glm::vec3 multiscatterColor{0.0f};     // multiscatterColor, linear (0: absorption only)
    float scatterAnisotropy = 0.0f;        // in (-1, 1)
    // KHR_materials_dispersion: 20 / the Abbe number V_d (0: none); the ior
    // is n_d, at 587.56 nm (lib/spectrum.glsl dispersiveIor).
    float dispersion = 0.0f;
    // KHR_materials_specular's colour or textures change the dielectric's Fresnel.
    bool tinted() const {
        return (specularColor != glm::vec3(1.0f) || specularTexture.used() || specularColorTexture.used()) &&
               specular > 0.0f && !unlit;
    }
    bool sheened() const { return glm::any(glm::greaterThan(sheenColor, glm::vec3(0.0f))) && !unlit; }
    // The TEXCOORD sets in the two texture coordinate slots of TriangleUv
    // (xy, zw): {0, 1} when every texture slot reads set 0 or 1; else the
    // distinct sets the slots read in increasing order ({s, s} for one). A
    // material may read at most two sets (the loader's error otherwise).
    std::array<int, 2> uvSets{0, 1};
    // The TriangleUv slot (0: xy, 1: zw) holding TEXCOORD_set.
    int uvSlot(int set) const { return set == uvSets[0] ? 0 : 1; }
    glm::vec3 emission() const { return unlit ? glm::vec3(0.0f) : emissiveFactor * emissiveStrength; }
    // Every texture slot with its glTF name, in one fixed order.
    struct NamedSlot {
        const TextureSlot* slot;
        const char* name;
    };
    std::array<NamedSlot, 17> textureSlots() const {
        return {{{&baseColorTexture, "baseColorTexture"},
                 {&metallicRoughnessTexture, "metallicRoughnessTexture"},
                 {&normalTexture, "normalTexture"},
                 {&emissiveTexture, "emissiveTexture"},
                 {&transmissionTexture, "transmissionTexture"},
                 {&clearcoatTexture, "clearcoatTexture"},
                 {&clearcoatRoughnessTexture, "clearcoatRoughnessTexture"},
                 {&clearcoatNormalTexture, "clearcoatNormalTexture"},
                 {&sheenColorTexture, "sheenColorTexture"},
                 {&sheenRoughnessTexture, "sheenRoughnessTexture"},
                 {&specularTexture, "specularTexture"},
                 {&specularColorTexture, "specularColorTexture"},
                 {&iridescenceTexture, "iridescenceTexture"},
                 {&iridescenceThicknessTexture, "iridescenceThicknessTexture"},
                 {&diffuseTransmissionTexture, "diffuseTransmissionTexture"},
                 {&diffuseTransmissionColorTexture, "diffuseTransmissionColorTexture"},
                 {&anisotropyTexture, "anisotropyTexture"}}};
    }
};

// A decoded image: RGBA, rows top to bottom (glTF uv (0, 0) is the top-left
// corner), 8 bits (data holds bytes) or 16 bits (data holds uint16 in host
// byte order, 2 bytes each) per channel. stb_image through tinygltf expands
// grey and RGB images to RGBA (alpha 1).
struct TextureImage {
    std::string name;  // uri, else the glTF image name
    int width = 0;
    int height = 0;
    int bits = 8;      // 8 or 16
    std::vector<std::uint8_t> data;
};

// glTF sampler wrap modes and magnification filter (minFilter is ignored:
// minification is texture LOD's, lib/material.glsl textureLevel).
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
struct Texture {
    int image = 0;     // index into Scene::images; -1 for a texture no material may use (no decodable image)
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
    bool nearest = false;  // magFilter NEAREST; LINEAR (bilinear) otherwise
};

// Per-vertex texture coordinates of one triangle: (TEXCOORD_a, TEXCOORD_b)
// of vertex K in uv[K], {a, b} its material's uvSets ({0, 1} unless it reads
// a higher set), zero where the primitive lacks a set.
using TriangleUv = std::array<glm::vec4, 3>;
// Per-vertex COLOR_0 of one triangle: linear RGBA of vertex K in c[K] (alpha
// 1 from a VEC3 accessor; (1, 1, 1, 1) for a primitive without COLOR_0).
using TriangleColors = std::array<glm::vec4, 3>;
// Per-vertex world-space unit tangents, w = +-1 handedness (glTF TANGENT).
using TriangleTangents = std::array<glm::vec4, 3>;

// One triangle in world space. Normals are unit length; a triangle from a
// primitive without NORMAL repeats its geometric normal.
struct Triangle {
    glm::vec3 v[3];
    glm::vec3 n[3];
    std::uint32_t material = 0;
};

// KHR_lights_punctual light in world space. Units are the extension's,
// read radiometrically: point and spot `color * intensity` is radiant
// intensity (W/sr, falling off as 1/d^2); directional is the irradiance
// (W/m^2) on a surface facing the light. `range` is ignored.
struct PunctualLight {
    enum class Type { Point, Spot, Directional } type = Type::Point;
    std::string name;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    glm::vec3 position{0.0f};                // point, spot: the node's world origin
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // spot, directional: unit, where the light travels
                                             // (the node's local -Z in world space)
    float innerConeAngle = 0.0f;             // spot, radians: 0 <= inner < outer <= pi/2
    float outerConeAngle = 0.7853982f;
    glm::vec3 intensityRgb() const { return color * intensity; }
};

// Environment light from the command line (--env FILE or --env-color).
// Radiance arriving from world direction d is `scale * map(d)`, or `scale`
// without a map. The map is equirectangular (latitude-longitude), +Y up:
// row 0 is +Y, the bottom row -Y; the image centre is -Z (the direction an
// unrotated glTF camera looks) and u grows towards +X, so
//   u = 1/2 + atan2(d.x, -d.z) / (2 pi),   v = acos(d.y) / pi.
// `rotation` turns the environment about +Y by that angle (counter-clockwise
// seen from above): d sees the map at R_y(-rotation) d.
struct Environment {
    bool enabled = false;
    std::string source;          // the file, or "--env-color" (for messages)
    glm::vec3 scale{1.0f};       // --env-color times --env-intensity (map: intensity in rgb)
    float rotation = 0.0f;       // radians
    int width = 0, height = 0;   // 0 x 0 without a map
    std::vector<float> rgb;      // linear RGB, 3 floats per texel, row 0 at the top
};

// A mesh stored once in its own space and placed by instances
// (kFeatureInstancing): triangles [first, first + count) of Scene::triangles.
struct SharedMesh {
    std::size_t first = 0;
    std::size_t count = 0;
    std::string name;  // "mesh 3 (\"Tree\")", for --stats
    // A copy of an emitting mesh that moves (MotionOptions), placed once:
    // its emissive triangles are that placement's lights.
    bool lights = false;
};

// One placement of a SharedMesh: world = toWorld * object (affine). A
// mirroring placement (det < 0) places the mesh's copy whose winding is
// reversed, so its front faces stay front faces.
struct MeshInstance {
    std::uint32_t mesh = 0;  // index into Scene::sharedMeshes
    glm::mat4 toWorld{1.0f};  // with motion: the pose at the shutter's open
    std::vector<MotionKey> motion;  // over the shutter; empty: it does not move
};

struct Scene;

// Poses a loaded scene's animated placements and cameras for another
// shutter (--frames): their toWorld, MotionKeys and camera transforms, as
// loading with that shutter would have made them. Set by the loader with
// MotionOptions::frames.
class ScenePoser {
public:
    virtual ~ScenePoser() = default;
    virtual void pose(Scene& scene, double open, double close) const = 0;
};

struct Scene {
    std::string path;                 // file it was loaded from (for messages)
    // World space, except with instancing: triangles [0, worldTriangles())
    // are in world space and each SharedMesh's range after them in its own.
    std::vector<Triangle> triangles;
    std::vector<SharedMesh> sharedMeshes;
    std::vector<MeshInstance> instances;
    std::size_t worldTriangles() const { return sharedMeshes.empty() ? triangles.size() : sharedMeshes.front().first; }
    bool instanced() const { return !instances.empty(); }
    // The file's materials in file order, then the glTF default material
    // (spec defaults, name "default") when a primitive has none or the file
    // has no materials: never empty.
    std::vector<MaterialDesc> materials;
    std::vector<Camera> cameras;      // in node order (depth-first)
    std::vector<PunctualLight> lights;  // KHR_lights_punctual, in node order; zero-power lights dropped
    Environment environment;          // set by the caller (command line), not by the loader
    std::vector<std::string> extensionsUsed;
    // KHR_materials_variants: the file's variants, and the one the materials
    // were chosen for (LoadOptions::variant; empty: the primitives' own).
    std::vector<std::string> variants;
    std::string variant;
    std::vector<TextureImage> images;
    std::vector<Texture> textures;
    // Parallel to `triangles` when some primitive has TEXCOORD_0/1 (empty
    // otherwise), and when some material has a normalTexture (empty otherwise).
    std::vector<TriangleUv> texcoords;
    std::vector<TriangleTangents> tangents;
    // Parallel to `triangles` when some primitive has COLOR_0, else empty.
    std::vector<TriangleColors> colors;
    // Triangles with an emissive material but zero area. They stay in
    // `triangles` as geometry and are not emitters (see isEmitter).
    std::size_t droppedEmitters = 0;
    // MotionOptions::frames with an animation, unless something animated
    // cannot be posed again (a light, an emitting, skinned or morphed
    // mesh): null then, and each frame is loaded anew.
    std::shared_ptr<const ScenePoser> poser;
};

// Frees what packing copies (triangles, texture coordinates, tangents, colours,
// images, environment texels) once the scene is packed (pack/gpu_scene.h);
// materials, cameras, lights and the other small members stay.
inline void releaseGeometry(Scene& scene) {
    std::vector<Triangle>().swap(scene.triangles);
    std::vector<MeshInstance>().swap(scene.instances);
    std::vector<TriangleUv>().swap(scene.texcoords);
    std::vector<TriangleTangents>().swap(scene.tangents);
    std::vector<TriangleColors>().swap(scene.colors);
    std::vector<TextureImage>().swap(scene.images);
    std::vector<float>().swap(scene.environment.rgb);
}

// Area in world units squared.
inline float triangleArea(const Triangle& t) {
    return 0.5f * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
}

// True when some channel of emission() is > 0.
inline bool isEmissive(const MaterialDesc& m) {
    const glm::vec3 e = m.emission();
    return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
}

// The one emitter rule shared by the loader and the renderer: an emissive
// material and an area > 0 (computed in float as triangleArea does).
inline bool isEmitter(const Scene& scene, const Triangle& t) {
    return t.material < scene.materials.size() && isEmissive(scene.materials[t.material]) &&
           triangleArea(t) > 0.0f;
}

// Environment::source of the light a scene without any gets.
inline constexpr const char* kDefaultEnvironment = "default (no light in the scene)";

// Whether a mesh placed more than once is stored once and placed by
// instances (a two-level BVH) or flattened into world-space triangles.
// Auto: instanced when its placements hold more than kInstancingMinTriangles
// triangles together (flattened scenes render faster; above that line their
// memory decides: docs/benchmarks.md);
// On: every mesh placed twice or more; Off: everything flattened. Meshes that
// are skinned or have morph targets are always flattened, and meshes that
// emit unless they move.
enum class Instancing { Auto, On, Off };
inline constexpr std::size_t kInstancingMinTriangles = std::size_t(1) << 20;

// glTF animation (--animation, --shutter): the scene is posed at `open` on
// the chosen animation's timeline; with open < close every placement and
// camera that moves within [open, close] gets MotionKeys (its mesh is then
// instanced, whatever `instancing` says; an emitting mesh with a copy per
// placement, SharedMesh::lights). Skinned and morphed meshes stay at the
// pose at `open` (a warning says so).
struct MotionOptions {
    bool enabled = false;   // off: the nodes' static transforms, as if no animation
    std::string animation;  // its name or index; empty: the first
    double open = 0.0;
    double close = 0.0;
    // A sequence of frames (--frames): every mesh the animation moves is
    // instanced, whatever this shutter, and Scene::poser poses the others.
    bool frames = false;
};

// A device's memory and the words naming it ("llvmpipe (its largest
// device-local heap)"), for LoadOptions::deviceMemory; 0 bytes: not known.
struct DeviceBudget {
    std::uint64_t bytes = 0;
    std::string device;
};

struct LoadOptions {
    // A scene where nothing emits or was meant to (no emissive material on a
    // triangle, no punctual light) and no externalLight gets a uniform white
    // environment of radiance 1, with a warning.
    bool defaultLight = true;
    // Otherwise some light is required: an emitter triangle of non-zero area,
    // a punctual light, or externalLight (a scene whose only lights are black
    // or have no area is an error).
    bool requireEmitter = true;
    bool externalLight = false;   // an environment light comes from the command line
    // KHR_materials_variants: the variant whose materials the primitives get
    // (--variant); empty for their own. A name the file lacks is an error.
    std::string variant;
    Instancing instancing = Instancing::Auto;
    MotionOptions motion;
    // --restrict-paths: the canonical folder (restrictRoot) that the scene
    // file and every file it names must resolve into; empty: no such rule
    // (uris are still relative paths or data: URIs).
    std::string restrictPaths;
    // The host memory the loaded scene may take, in bytes; 0: what the
    // machine has (hostMemoryBudget). A scene whose flattened triangles,
    // emitters and instances need more (kHostBytesPerTriangle,
    // kHostBytesPerEmitter, kHostBytesPerInstance each) is an error before
    // they are made.
    std::uint64_t hostMemory = 0;
    // The memory of the device that will render the scene, asked for with
    // the bytes the flattened triangles' packed arrays need at least
    // (kDeviceBytesPerTriangle each, kDeviceBytesPerEmitter more for an
    // emitter) once the placements are known: a scene that needs more is an
    // error before its triangles are made (the upload checks the whole
    // render again). Unset, or 0 bytes returned: not known.
    std::function<DeviceBudget(std::uint64_t needed)> deviceMemory;
};

// The host memory a world-space triangle takes from loading to upload
// (the Scene's arrays, the BVH build, the packed arrays), at its peak,
// rounded up (docs/security.md: how it was measured).
inline constexpr std::uint64_t kHostBytesPerTriangle = 128;
// The same for an instanced placement (its transforms, the top level's
// build, the packed record and nodes).
inline constexpr std::uint64_t kHostBytesPerInstance = 256;
// More for an emitting triangle (emitters are always flattened): its
// Emitter, the light tree's build and nodes, the alias table.
inline constexpr std::uint64_t kHostBytesPerEmitter = 384;
// Device memory a flattened triangle takes at least: its TriVerts and
// TriShading (shaders/shared/types.h; pack/gpu_scene.cpp asserts the sum),
// and an emitting one's Emitter. The tree over them and the other arrays
// come on top.
inline constexpr std::uint64_t kDeviceBytesPerTriangle = 96;
inline constexpr std::uint64_t kDeviceBytesPerEmitter = 80;
// Instanced placements at most: the instances array's texel indices
// (top-level nodes, kInstanceTexels per record, motion keys) stay in 32 bits.
inline constexpr std::uint64_t kMaxInstances = std::uint64_t(1) << 28;

// Loads .gltf or .glb (binary when the file starts with the 'glTF' magic).
// Throws strata::Error with a one-line message naming the file and the
// problem; warnings (unsupported used extensions, zero-area emitters) go to
// strata::warn.
Scene loadGltf(const std::string& path, const LoadOptions& options = {});
// The same from the file's bytes, read already; `path` names the file in
// messages, and uris resolve against its folder.
Scene loadGltf(const std::string& path, const std::vector<unsigned char>& bytes, const LoadOptions& options = {});

}  // namespace strata
