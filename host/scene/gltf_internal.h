// Internals of the glTF loader, shared by host/scene/gltf*.cpp only.
// Every function throws strata::Error ("<path>: error: <what>", one line).
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/pose.h"
#include "scene/scene.h"

namespace strata::gltf {

// The key under which parseModel leaves, in an image's extras, why it could
// not be decoded (the image is left without pixels: an error only where a
// material reads it).
inline constexpr const char* kUndecodable = "strata-undecodable";

// The file parsed by tinygltf (JSON or binary glTF, told apart by the GLB
// magic), buffers and images resolved next to the file only: relative
// paths, inside the canonical folder `restrictPaths` unless it is empty.
// Images are refused before decoding when over limits::imageSizeProblem or
// when together they would need more than `hostMemory` bytes (0: what the
// machine has, hostMemoryBudget).
tinygltf::Model parseModel(const std::string& path, const std::vector<unsigned char>& bytes,
                           const std::string& restrictPaths, std::uint64_t hostMemory);
// The bytes of a scene file (a directory or an unreadable file is an error).
std::vector<unsigned char> readSceneFile(const std::string& path);
// The file at `path`, without a folder to stay in and with the machine's memory.
inline tinygltf::Model parseModel(const std::string& path) { return parseModel(path, readSceneFile(path), "", 0); }

// Extensions outside the supported list: in extensionsRequired an error, in
// extensionsUsed a warning. A supported extension whose decoder this build
// lacks (missingDecoder): required, an error; used, a warning.
void checkExtensions(const std::string& path, const tinygltf::Model& model);

// A string as it appears in one message line: in double quotes, with
// quotes, backslashes and control characters escaped.
std::string quoted(const std::string& s);

// Joins the non-empty lines of a multi-line text with "; ", other control
// characters become spaces; data URIs are cut to their first 48 characters
// followed by "...".
std::string oneLine(const std::string& text);

// `mesh 2 ("Cube")`, or `mesh 2` for an unnamed mesh.
std::string meshLabel(const tinygltf::Model& model, int mesh);

// The accessor storages an attribute accepts: its type, the component types,
// and whether integer components must be `normalized` (FLOAT ignores it).
struct AccessorFormat {
    int type = 0;                     // TINYGLTF_TYPE_*
    std::vector<int> componentTypes;  // TINYGLTF_COMPONENT_TYPE_*
    bool normalizedIntegers = false;
};

// The memory rule for accessors: one with a bufferView is bounded by it; one
// without (zeros, then any sparse substitution) may have at most
// max(kZeroAccessorFloor, the bytes of the file's buffers) elements, else
// an error, so no accessor makes the loader allocate more than 16 bytes of
// floats per byte the file stores (or 16 MiB).
inline constexpr std::size_t kZeroAccessorFloor = std::size_t(1) << 20;

// The elements of accessor `index` (of `format`'s type, N components) as
// floats: from its bufferView, or zeros without one (accessor.bufferView in
// the glTF 2.0 schema; bounded as above), then the sparse substitution
// (3.6.2.3). Normalized integers become floats by the glTF
// formulas (max(c / 127, -1), c / 255, max(c / 32767, -1), c / 65535),
// others their integer value. `use` names what the accessor is read for, e.g.
// `mesh 0 ("Quad") primitive 0 POSITION`. `undeclared`, when not null, is the
// format KHR_mesh_quantization would accept: the file does not declare it,
// and an accessor that fits it is told so in the error. Instantiated for N =
// 1 (glm::vec1, <glm/ext/vector_float1.hpp>), 2, 3, 4.
template <int N>
std::vector<glm::vec<N, float>> readFloats(const std::string& path, const tinygltf::Model& model,
                                           int index, const std::string& use,
                                           const AccessorFormat& format,
                                           const AccessorFormat* undeclared);

// The MAT4 FLOAT accessor `index` (column-major, as glTF stores it), dense,
// zeros or sparse; `use` names what it is read for.
std::vector<glm::mat4> readMatrices(const std::string& path, const tinygltf::Model& model, int index,
                                    const std::string& use);

using strata::trs;  // scene/pose.h

// EXT_mesh_gpu_instancing of one node: each attribute's values (empty when
// the file leaves it out) and the instance count.
struct GpuInstances {
    std::vector<glm::vec3> translation;
    std::vector<glm::vec4> rotation;
    std::vector<glm::vec3> scale;
    std::size_t count = 0;
    glm::dmat4 local(std::size_t i) const;  // instance i's T * R * S
};

// The node's instances (count 0 without the extension). Throws a one-line
// strata::Error for a node without a mesh, no attribute, counts that differ,
// or a value that is not finite or a rotation of length 0.
GpuInstances readGpuInstances(const std::string& path, const tinygltf::Model& model, int node,
                              const std::string& nodeLabel);

// The node's instance count as its accessors declare it (the largest
// `count` among TRANSLATION, ROTATION and SCALE; 0 without the extension),
// before anything is read: the walk checks the instances' memory with it.
// readGpuInstances checks the accessors themselves.
std::size_t gpuInstanceCount(const tinygltf::Model& model, int node);

// A node's translation, rotation (a quaternion of any non-zero length) and
// scale, the glTF defaults where absent, checked (sizes, rotation length);
// for a node without `matrix` (gltf_nodes.cpp).
struct NodeTrs {
    glm::dvec3 translation{0.0};
    glm::dvec4 rotation{0.0, 0.0, 0.0, 1.0};
    glm::dvec3 scale{1.0};
};
NodeTrs nodeTrs(const std::string& path, const tinygltf::Model& model, int node);

// The glTF transform of node `node` alone: `matrix`, or T * R * S.
glm::dmat4 nodeTransform(const std::string& path, const tinygltf::Model& model, int node);

// Scene `sceneIndex`'s nodes depth first, parents before children, children
// in file order, each with its world transform; `local(node, parent)` gives
// a node's local transform (parent -1 for a root). Fails on a node or child
// that does not exist, a cycle, or a node reached twice.
struct NodeVisit {
    int node;
    glm::dmat4 world;
    // KHR_node_visibility: false where the node or an ancestor has
    // visible: false (its meshes and lights are not rendered; its camera is).
    bool visible = true;
};
std::vector<NodeVisit> walkNodes(const std::string& path, const tinygltf::Model& model, int sceneIndex,
                                 const std::function<glm::dmat4(int node, int parent)>& local);

// A SCALAR u8/u16/u32 accessor (indices), dense, zeros or sparse as above.
// (tinygltf 2.7 itself refuses a primitive whose indices accessor has no
// bufferView, before this is reached.)
std::vector<std::uint32_t> readIndices(const std::string& path, const tinygltf::Model& model,
                                       int index, const std::string& use);

// n of an attribute name `prefix`n (n decimal, at most 9 digits, no
// leading zero; prefix "TEXCOORD_", "JOINTS_", ...), else -1.
int attributeSet(const std::string& semantic, std::string_view prefix);
inline int texcoordSet(const std::string& semantic) { return attributeSet(semantic, "TEXCOORD_"); }

// One morph target of a primitive (glTF 2.0 3.7.2.2): displacements of
// POSITION, NORMAL and TANGENT xyz, each empty or one per vertex.
struct MorphTarget {
    std::vector<glm::vec3> positions, normals, tangents;
};

// One JOINTS_n / WEIGHTS_n set of a primitive, one entry per vertex.
struct SkinInfluences {
    std::vector<glm::uvec4> joints;
    std::vector<glm::vec4> weights;
};

// One primitive of a mesh decoded in the mesh's local space. `indices` always
// holds 3 entries per triangle (0,1,2,... for a non-indexed primitive), each
// < positions.size(). `normals`, each of `texcoords` (TEXCOORD_n by n) and
// `tangents` (TANGENT, w = +-1) are each empty or the same size as `positions`.
struct LocalPrimitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::map<int, std::vector<glm::vec2>> texcoords;
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec4> colors;  // COLOR_0, linear RGBA (alpha 1 from VEC3)
    std::vector<MorphTarget> targets;
    std::vector<SkinInfluences> skin;  // JOINTS_n / WEIGHTS_n by n
    std::vector<std::uint32_t> indices;
    int material = -1;      // glTF material index, -1 for none
    std::size_t index = 0;  // in the mesh's primitives (for messages)
    // TEXCOORD_set, empty when the primitive lacks it.
    const std::vector<glm::vec2>& texcoord(int set) const {
        static const std::vector<glm::vec2> kNone;
        const auto it = texcoords.find(set);
        return it == texcoords.end() ? kNone : it->second;
    }
};

// The triangle primitives of a mesh, and the others it skips.
struct LocalMesh {
    std::vector<LocalPrimitive> primitives;
    // One entry per POINTS/LINES/LINE_LOOP/LINE_STRIP primitive, in file
    // order: `mesh 1 ("Wire") primitive 0 (LINES)`.
    std::vector<std::string> skipped;
    // One entry per primitive glTF 2.0 says not to render (no POSITION, a
    // non-indexed triangle count not a multiple of 3): `... primitive 1 (no POSITION)`.
    std::vector<std::string> invalid;
};

// Decodes every primitive of `mesh` (gltf_mesh.cpp). TRIANGLES as they are;
// TRIANGLE_STRIP and TRIANGLE_FAN (at least 3 indices) converted to
// triangles with the glTF 2.0 3.7.2.1 winding, dropping those that repeat an
// index; the point and line modes skipped; any other mode is an error. Accessor storage: POSITION float VEC3
// with finite values, NORMAL float VEC3 (optional), TEXCOORD_0/1 VEC2 float
// or normalized u8/u16 (optional), TANGENT float VEC4 (optional); with
// KHR_mesh_quantization declared also POSITION and TEXCOORD_n as
// i8/u8/i16/u16 (normalized or not), NORMAL and TANGENT as normalized
// i8/i16. Indices u8/u16/u32 in range. Every accessor inside its bufferView
// and buffer, or without a bufferView (zeros); sparse accessors anywhere.
LocalMesh decodeMesh(const std::string& path, const tinygltf::Model& model, int mesh);

// KHR_draco_mesh_compression and EXT_meshopt_compression (gltf_compressed.cpp,
// gltf_draco.cpp, gltf_meshopt.cpp).

// The JSON parseModel rewrites before tinygltf 2.7 parses it, and how to put
// the model back after: tinygltf fails a file with an `indices` accessor
// without bufferView (every Draco-compressed primitive's), so such `indices`
// are removed; it refuses a buffer without uri in a .gltf (an
// EXT_meshopt_compression fallback buffer), so fallback buffers load as a
// one-byte placeholder whose data is then emptied; it requires a skin's
// inverseBindMatrices (given -1: identity) and a channel's node
// (KHR_animation_pointer channels: a node's transform or weights become
// that node's channel, others are dropped with a warning); it reads image
// data: URIs of four media types only (others, WebP and KTX2 among them,
// are given as application/octet-stream). Only files that may hold one of
// these are parsed for this (gltf_compressed.cpp).
struct TinygltfFixups {
    struct HiddenIndices {
        std::size_t mesh, primitive;
        int accessor;
    };
    std::vector<unsigned char> bytes;  // the file with its JSON rewritten; empty: unchanged
    std::vector<HiddenIndices> indices;
    std::vector<std::size_t> placeholders;  // buffer indices, emptied after the parse
    bool changed = false;                   // other rewrites (skins, pointer channels)
    std::vector<std::string> warnings;      // to print once the file has parsed
};
TinygltfFixups prepareForTinygltf(const std::vector<unsigned char>& bytes, bool binary);
void restoreAfterTinygltf(const TinygltfFixups& fixups, tinygltf::Model& model);

// Bytes [offset, offset + length) of buffer `buffer`, checked to lie inside
// its data; `label` names the range in messages.
const unsigned char* bufferRange(const std::string& path, const tinygltf::Model& model, int buffer,
                                 std::size_t offset, std::size_t length, const std::string& label);

// Integer `key` (>= 0) of extension object `object`; `fallback` when absent,
// an error when absent without one. tinygltf keeps extension integers as int.
std::size_t extensionCount(const std::string& path, const tinygltf::Value& object,
                           const std::string& key, const std::string& label,
                           std::optional<std::size_t> fallback);

// "the Draco decoder (libdraco)" for KHR_draco_mesh_compression in a build
// without STRATA_DRACO, likewise for EXT_meshopt_compression without
// STRATA_MESHOPT and EXT_texture_webp without STRATA_WEBP; always for
// KHR_texture_basisu; nullptr otherwise.
const char* missingDecoder(std::string_view extension);

// A primitive with KHR_draco_mesh_compression, decoded from its Draco stream
// into `out`: the attributes the extension names (`decoded` lists them;
// the others are the caller's to read from their accessors, as the
// extension's conformance says) and `indices`, 3 per Draco triangle in
// order: the triangles of a TRIANGLES primitive, the index sequence of a
// TRIANGLE_STRIP one (the mode converts it, as for an indices accessor).
// Every accessor's count and type is checked against the decoded data;
// returns true. False when the primitive has no such extension, or strata
// was built without the decoder (its accessors are then the data, and one
// without any is an error). `label` names the primitive in messages.
bool decodeDracoPrimitive(const std::string& path, const tinygltf::Model& model,
                          const tinygltf::Primitive& prim, const std::string& label,
                          LocalPrimitive& out, std::vector<std::string>& decoded);

// Every bufferView with EXT_meshopt_compression decoded into a buffer of its
// own (appended to model.buffers; the view then names it at byteOffset 0).
// Without the decoder the views keep their buffer; one that is a placeholder
// is an error.
void decodeMeshoptViews(const std::string& path, tinygltf::Model& model);

// KHR_materials_variants (gltf_variants.cpp): the names of the file's
// variants, in order (empty without the extension).
std::vector<std::string> readVariants(const std::string& path, const tinygltf::Model& model);

// Checks every primitive's variant mappings (material and variant indices in
// range) and, for the variant called `name` (none when empty), sets each
// mapped primitive's material to the mapping's. A name that is not one of
// `variants` is an error listing them.
void applyVariant(const std::string& path, tinygltf::Model& model, const std::vector<std::string>& variants,
                  const std::string& name);

// pbrMetallicRoughness factors, emissive factor, KHR_materials_emissive_strength,
// KHR_materials_ior, doubleSided, alphaMode/alphaCutoff of material `index`.
// Also the texture slots (textureInfo + KHR_texture_transform), checked
// against model.textures.
MaterialDesc convertMaterial(const std::string& path, const tinygltf::Model& model, int index);

// The images (decoded by tinygltf; an image without pixels is an error) and
// textures (source + sampler) of the model, in file order.
void convertTextures(const std::string& path, const tinygltf::Model& model, Scene& scene);

// The image texture `index` shows (its index in model.images), or -1 with
// the reason in `why`: EXT_texture_webp's source in a build with libwebp,
// else the texture's `source` (the fallback); KHR_texture_basisu's source is
// never decoded (Debian has no Basis Universal decoder), so its `source`
// fallback. The image must have decoded pixels.
int textureImage(const tinygltf::Model& model, int index, std::string& why);

// One warning when textures that materials read are KHR_texture_basisu (no
// decoder) and show their fallback source instead.
void warnTextureFallbacks(const std::string& path, const tinygltf::Model& model,
                          const std::vector<MaterialDesc>& materials);

// One warning when materials have a KHR_materials_volume_scatter
// multiscatterTexture, which strata does not read (multiscatterColor alone).
void warnUnreadMaterialTextures(const std::string& path, const tinygltf::Model& model);

// The TextureSlot of a textureInfo: `index` (checked against model.textures),
// `texCoord` (a TEXCOORD set, >= 0) and the KHR_texture_transform object `transform`
// (nullptr when absent). `label` names the textureInfo in messages.
TextureSlot convertTextureSlot(const std::string& path, const tinygltf::Model& model,
                               const std::string& label, int index, int texCoord,
                               const tinygltf::Value* transform);
// The KHR_lights_punctual light index of node `node`
// (node.extensions.KHR_lights_punctual.light), or -1 when it has none.
int nodeLight(const std::string& path, const tinygltf::Model& model, int node,
              const std::string& nodeLabel);

// KHR_lights_punctual light `index` placed by the node's world transform:
// type point, spot or directional; color 3 finite numbers >= 0; intensity
// finite and >= 0; spot 0 <= innerConeAngle < outerConeAngle <= pi/2.
PunctualLight convertLight(const std::string& path, const tinygltf::Model& model, int index,
                           const glm::dmat4& world, const std::string& nodeLabel);

// The scene's size once its placements are decided, before any triangle is
// placed: the triangles stored (the flattened meshes' world-space copies and
// the instanced meshes' copies per emitting placement), the emitting ones
// among them, the instanced placements and the placed nodes.
struct SceneSize {
    std::size_t triangles = 0;
    std::size_t emitters = 0;
    std::size_t instances = 0;
    std::size_t placements = 0;
};

// LoadOptions' memory limits (hostMemory 0: the machine's budget;
// deviceMemory unset: not known).
struct SizeBudget {
    std::uint64_t hostMemory = 0;
    std::function<DeviceBudget(std::uint64_t needed)> deviceMemory;
};

// Refuses a scene past the instances strata can index, the host memory its
// flattened triangles and instances take to load and build
// (kHostBytesPerTriangle, kHostBytesPerInstance), or the device memory its
// flattened triangles' packed arrays take at least (kDeviceBytesPerTriangle,
// kDeviceBytesPerEmitter): a small file can place a mesh many times, and is
// refused before those are made (gltf_budget.cpp).
void checkSceneSize(const std::string& path, const SceneSize& size, const SizeBudget& budget);

}  // namespace strata::gltf
