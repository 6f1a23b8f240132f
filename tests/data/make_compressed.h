// The test-file generator of tests/data/make_compressed.cpp (valid files)
// and make_compressed_broken.cpp (the filters' file and the broken files):
// geometry, a glTF document with its buffers, the Draco and meshopt
// encoders, and the .glb/.gltf writers.
#pragma once
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace makecompressed {

using Json = nlohmann::json;
using Bytes = std::vector<unsigned char>;
namespace fs = std::filesystem;

constexpr int kFloat = 5126, kU16 = 5123, kU32 = 5125;

// One primitive: per-vertex arrays (uv1 and tangents may be empty) and a
// triangle list.
struct Prim {
    std::string name;
    std::vector<float> positions, normals, uv0, uv1, tangents;  // 3, 3, 2, 2, 4 per vertex
    std::vector<float> colors;                                  // COLOR_0, 4 per vertex (or empty)
    std::vector<float> joints, weights;                         // JOINTS_0 (u16), WEIGHTS_0, 4 per vertex
    std::vector<std::uint32_t> indices;
    int material = 0;
    std::size_t vertices() const { return positions.size() / 3; }
};

// A closed box (6 quads, 24 vertices) centred at c with half sides h, with
// TEXCOORD_1 and TANGENT as well.
Prim box(const std::string& name, std::array<float, 3> c, std::array<float, 3> h, int material);

// The Cornell-like scene: five walls, a light under the ceiling, two boxes;
// materials 0 white, 1 red, 2 green, 3 the light.
std::vector<Prim> cornell();

// (semantic, components per vertex, values) of each attribute a primitive
// has; TEXCOORD_1 is stored as normalized UNSIGNED_SHORT (`u16`), the others
// as FLOAT.
struct Attribute {
    const char* semantic;
    int components;
    const std::vector<float>* values;
    bool u16 = false;
    bool integer = false;  // with u16: the values themselves (JOINTS_n), not normalized
};
std::vector<Attribute> attributesOf(const Prim& p);
// The attribute's bytes as stored: floats, or round(v * 65535) as u16.
std::vector<unsigned char> attributeBytes(const Attribute& a);

// A glTF document and its buffers' bytes (json["buffers"] has one entry per
// buffer; the writers fill in buffer 0's and those named as files).
struct Doc {
    Json json;
    std::vector<Bytes> buffers;

    int addBuffer();
    // Appends bytes to buffer b at a 4-byte boundary; returns their offset.
    std::size_t append(int b, const void* data, std::size_t size);
    int addView(Json view);
    int addPlainView(int b, const void* data, std::size_t size, std::size_t stride = 0);
    int addAccessor(Json accessor);
};

// Materials, the camera, one node per primitive's mesh, an empty buffer 0.
Doc baseDocument(const std::vector<Prim>& prims);
void addExtension(Json& j, const char* name, bool required);
Json accessorFor(const Attribute& a, std::size_t count);

// The uncompressed primitive in buffer b (u16 indices).
Json plainPrimitive(Doc& doc, const Prim& p, int b);

struct DracoOptions {
    bool sequential = true;  // MESH_SEQUENTIAL_ENCODING keeps vertex and triangle order
    int positionBits = 0;    // 0: no quantization (lossless)
    // The semantics put in the stream (empty: all); the others stay plain
    // accessors of the primitive.
    std::vector<std::string> compressed = {};
    bool inStream(const std::string& semantic) const;
};
struct DracoStream {
    Bytes bytes;
    std::map<std::string, std::uint32_t> ids;  // semantic -> Draco unique id
    std::size_t points = 0, faces = 0;         // as the decoder gives them back
};
DracoStream encodeDraco(const Prim& p, const DracoOptions& o);

// A KHR_draco_mesh_compression primitive (stream in buffer 0); with
// `fallback`, its accessors hold that uncompressed data as well.
Json dracoPrimitive(Doc& doc, const Prim& p, const DracoOptions& o, const Prim* fallback);

// `count` elements of `stride` bytes in `mode` (ATTRIBUTES, TRIANGLES,
// INDICES; index data is u32 in `data`).
Bytes encodeMeshopt(const std::string& mode, const void* data, std::size_t count, std::size_t stride,
                    std::size_t vertices);

// A bufferView of `rawSize` bytes in buffer `parent` (holding `fallbackData`,
// or reserved in a placeholder) with `compressed` in buffer 0.
int meshoptView(Doc& doc, int parent, std::size_t rawSize, const Bytes& compressed, std::size_t count,
                std::size_t stride, const std::string& mode, const std::string& filter,
                const Bytes* fallbackData);

struct MeshoptOptions {
    std::string indexMode = "TRIANGLES";
    std::size_t indexSize = 2;
};
// A primitive whose every view is meshopt-compressed, the views' own buffer
// being `parent` (with `fallback`'s data when given).
Json meshoptPrimitive(Doc& doc, const Prim& p, int parent, const MeshoptOptions& o, const Prim* fallback);

template <typename T>
Bytes bytesOf(const std::vector<T>& v) {
    Bytes b(v.size() * sizeof(T));
    if (!b.empty()) std::memcpy(b.data(), v.data(), b.size());
    return b;
}

// One mesh per primitive, each written by `write(doc, prim, index)`.
Doc scene(const std::vector<Prim>& prims, const std::function<Json(Doc&, const Prim&, std::size_t)>& write);

void writeBytes(const fs::path& path, const Bytes& bytes);
// Buffer 0 as the BIN chunk; other buffers' JSON entries as the caller set them.
void writeGlb(const fs::path& path, Doc doc);
// The buffers in `files` as those files next to the .gltf, the others'
// JSON entries as the caller set them.
void writeGltf(const fs::path& path, Doc doc, const std::map<int, std::string>& files);

void writeFilterFile(const fs::path& dir);
void writeBrokenFiles(const fs::path& dir);

}  // namespace makecompressed
