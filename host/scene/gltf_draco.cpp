// KHR_draco_mesh_compression: a primitive's Draco stream (in the bufferView
// the extension names) decoded by libdraco into the LocalPrimitive that
// decodeMesh makes from accessors. The extension's `attributes` map glTF
// semantics to Draco attribute unique ids; the primitive's accessors give
// the count and type the decoded data must have (the spec, "accessors");
// attributes outside the stream are read from their accessors by decodeMesh.
#include <cmath>
#include <limits>
#include <exception>
#include <optional>

#if STRATA_DRACO
#include <draco/compression/decode.h>
#endif

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

// The attributes strata reads, with the accessor type each must have and
// whether its values must be finite (as decodeMesh requires).
struct Semantic {
    int type;
    const char* typeName;
    int components;
    bool finite;
    bool integers;  // normalized UNSIGNED_BYTE/SHORT allowed besides FLOAT
    bool indices = false;  // UNSIGNED_BYTE/SHORT not normalized, and only those (JOINTS_n)
};
constexpr Semantic kPosition{TINYGLTF_TYPE_VEC3, "VEC3", 3, true, false};
constexpr Semantic kNormal{TINYGLTF_TYPE_VEC3, "VEC3", 3, false, false};
constexpr Semantic kTexcoord{TINYGLTF_TYPE_VEC2, "VEC2", 2, true, true};
constexpr Semantic kTangent{TINYGLTF_TYPE_VEC4, "VEC4", 4, false, false};
constexpr Semantic kColor3{TINYGLTF_TYPE_VEC3, "VEC3", 3, true, true};
constexpr Semantic kColor4{TINYGLTF_TYPE_VEC4, "VEC4", 4, true, true};
constexpr Semantic kWeights{TINYGLTF_TYPE_VEC4, "VEC4", 4, true, true};
constexpr Semantic kJoints{TINYGLTF_TYPE_VEC4, "VEC4", 4, true, false, true};

// The Semantic of a glTF attribute name strata reads from a Draco stream
// (COLOR_0 as its accessor's type, `accessorType`); nullptr for the others
// (read from their accessors, or ignored).
const Semantic* semanticOf(const std::string& name, int accessorType) {
    if (name == "POSITION") return &kPosition;
    if (name == "NORMAL") return &kNormal;
    if (name == "TANGENT") return &kTangent;
    if (name == "COLOR_0") return accessorType == TINYGLTF_TYPE_VEC3 ? &kColor3 : &kColor4;
    if (texcoordSet(name) >= 0) return &kTexcoord;
    if (attributeSet(name, "JOINTS_") >= 0) return &kJoints;
    if (attributeSet(name, "WEIGHTS_") >= 0) return &kWeights;
    return nullptr;
}

// The extension's `attributes`: semantic -> Draco unique id.
std::vector<std::pair<std::string, std::uint32_t>> dracoAttributes(const std::string& path,
                                                                   const tinygltf::Value& ext,
                                                                   const std::string& label) {
    if (!ext.Has("attributes") || !ext.Get("attributes").IsObject()) {
        fail(path, label + " has no attributes object");
    }
    const tinygltf::Value& attributes = ext.Get("attributes");
    std::vector<std::pair<std::string, std::uint32_t>> out;
    for (const std::string& key : attributes.Keys()) {
        out.emplace_back(key, static_cast<std::uint32_t>(
                                  extensionCount(path, attributes, key, label + " attributes", {})));
    }
    return out;
}

#if STRATA_DRACO

const std::uint32_t* findId(const std::vector<std::pair<std::string, std::uint32_t>>& ids,
                            const std::string& semantic) {
    for (const auto& [name, id] : ids) {
        if (name == semantic) return &id;
    }
    return nullptr;
}

const char* dracoTypeName(draco::DataType t) {
    switch (t) {
        case draco::DT_INT8: return "INT8";
        case draco::DT_UINT8: return "UINT8";
        case draco::DT_INT16: return "INT16";
        case draco::DT_UINT16: return "UINT16";
        case draco::DT_INT32: return "INT32";
        case draco::DT_UINT32: return "UINT32";
        case draco::DT_FLOAT32: return "FLOAT32";
        case draco::DT_FLOAT64: return "FLOAT64";
        default: return "another type";
    }
}

// The Draco data type an accessor's component type decodes to: FLOAT from
// FLOAT32 (a quantized attribute is dequantized to FLOAT32 by the decoder),
// normalized UNSIGNED_BYTE/SHORT (TEXCOORD_n only) from UINT8/UINT16.
draco::DataType expectedType(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return draco::DT_FLOAT32;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return draco::DT_UINT8;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return draco::DT_UINT16;
        default: return draco::DT_INVALID;
    }
}

// The values of one decoded attribute per point, as floats; normalized
// UINT8/UINT16 become c / 255, c / 65535 (glTF 2.0 3.7.2.1, as decodeMesh
// reads them).
std::vector<float> readAttribute(const std::string& path, const tinygltf::Model& model,
                                 const draco::Mesh& mesh, const tinygltf::Primitive& prim,
                                 const std::string& name, const Semantic& semantic, std::uint32_t id,
                                 const std::string& label) {
    const std::string use = label + " " + name;
    const int accessorIndex = prim.attributes.at(name);
    if (accessorIndex < 0 || static_cast<std::size_t>(accessorIndex) >= model.accessors.size()) {
        fail(path, use + ": accessor " + std::to_string(accessorIndex) + " does not exist (" +
                       std::to_string(model.accessors.size()) + " accessors)");
    }
    const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(accessorIndex)];
    const std::string accLabel = use + ": accessor " + std::to_string(accessorIndex);
    const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(id);
    if (!att) {
        fail(path, use + ": Draco attribute id " + std::to_string(id) +
                       " is not in the Draco stream (" + std::to_string(mesh.num_attributes()) +
                       " attributes)");
    }
    const std::string attLabel = "Draco attribute " + std::to_string(id);
    if (acc.type != semantic.type) {
        fail(path, accLabel + " is not " + semantic.typeName + " (" + attLabel + " has " +
                       std::to_string(att->num_components()) + " components)");
    }
    if (att->num_components() != semantic.components) {
        fail(path, use + ": " + attLabel + " has " + std::to_string(att->num_components()) +
                       " components; " + semantic.typeName + " needs " +
                       std::to_string(semantic.components));
    }
    const bool integers = semantic.integers;
    const draco::DataType expected = expectedType(acc.componentType);
    const bool integer = expected == draco::DT_UINT8 || expected == draco::DT_UINT16;
    if (semantic.indices ? !integer || acc.normalized
                         : expected == draco::DT_INVALID || (integer && !(integers && acc.normalized))) {
        fail(path, accLabel + " has component type " + std::to_string(acc.componentType) +
                       (semantic.indices ? std::string(" (normalized: ") + (acc.normalized ? "yes" : "no") +
                                               "); expected UNSIGNED_BYTE/SHORT, not normalized"
                                         : std::string("; expected FLOAT") +
                                               (integers ? " or normalized UNSIGNED_BYTE/SHORT" : "")));
    }
    if (att->data_type() != expected) {
        fail(path, accLabel + " expects " + dracoTypeName(expected) + " data but " + attLabel +
                       " holds " + dracoTypeName(att->data_type()));
    }
    const std::size_t points = mesh.num_points();
    if (acc.count != points) {
        fail(path, accLabel + " has count " + std::to_string(acc.count) +
                       " but the Draco stream decodes " + std::to_string(points) + " points");
    }
    const std::size_t n = static_cast<std::size_t>(semantic.components);
    const float divisor = semantic.indices ? 1.0f : expected == draco::DT_UINT8 ? 255.0f : 65535.0f;
    std::vector<float> out(points * n);
    std::uint32_t raw[4];
    for (std::size_t i = 0; i < points; ++i) {
        const draco::AttributeValueIndex value = att->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
        const bool ok = integer ? att->ConvertValue<std::uint32_t>(value, static_cast<int8_t>(n), raw)
                                : att->ConvertValue<float>(value, static_cast<int8_t>(n), &out[i * n]);
        if (!ok) {
            fail(path, use + ": " + attLabel + " has no value for point " + std::to_string(i));
        }
        if (integer) {
            for (std::size_t c = 0; c < n; ++c) out[i * n + c] = static_cast<float>(raw[c]) / divisor;
        }
        for (std::size_t c = 0; c < n && semantic.finite; ++c) {
            if (!std::isfinite(out[i * n + c])) {
                fail(path, use + ": point " + std::to_string(i) + " of " + attLabel +
                               " is NaN or Inf");
            }
        }
    }
    return out;
}

// The decoded triangles, checked against the primitive's indices accessor
// (count 3 x triangles, SCALAR, every index within its component type).
std::vector<std::uint32_t> readFaces(const std::string& path, const tinygltf::Model& model,
                                     const draco::Mesh& mesh, const tinygltf::Primitive& prim,
                                     const std::string& label) {
    const std::size_t faces = mesh.num_faces();
    const std::size_t points = mesh.num_points();
    std::uint64_t limit = std::numeric_limits<std::uint32_t>::max();
    if (prim.indices >= 0) {
        const std::string use = label + " indices";
        if (static_cast<std::size_t>(prim.indices) >= model.accessors.size()) {
            fail(path, use + ": accessor " + std::to_string(prim.indices) + " does not exist (" +
                           std::to_string(model.accessors.size()) + " accessors)");
        }
        const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(prim.indices)];
        const std::string accLabel = use + ": accessor " + std::to_string(prim.indices);
        if (acc.type != TINYGLTF_TYPE_SCALAR) fail(path, accLabel + " is not SCALAR");
        if (acc.count != 3 * faces) {
            fail(path, accLabel + " has count " + std::to_string(acc.count) +
                           " but the Draco stream decodes " + std::to_string(faces) +
                           " triangles (" + std::to_string(3 * faces) + " indices)");
        }
        if (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            limit = 0xff;
        } else if (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            limit = 0xffff;
        } else if (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail(path, accLabel + " has component type " + std::to_string(acc.componentType) +
                           "; expected UNSIGNED_BYTE/SHORT/INT");
        }
    }
    std::vector<std::uint32_t> out(3 * faces);
    for (std::size_t f = 0; f < faces; ++f) {
        const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(static_cast<std::uint32_t>(f)));
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t index = face[k].value();
            if (index >= points || index > limit) {
                fail(path, label + ": Draco triangle " + std::to_string(f) + " has index " +
                               std::to_string(index) + ", out of range (" + std::to_string(points) +
                               " points" + (index < points ? ", over the indices component type" : "") +
                               ")");
            }
            out[3 * f + k] = index;
        }
    }
    return out;
}

std::unique_ptr<draco::Mesh> decodeStream(const std::string& path, const unsigned char* bytes,
                                          std::size_t size, const std::string& label) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes), size);
    const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) {
        fail(path, label + ": not a Draco stream: " + oneLine(type.status().error_msg_string()));
    }
    if (type.value() != draco::TRIANGULAR_MESH) {
        fail(path, label + ": the Draco stream holds a point cloud, not a triangle mesh");
    }
    std::optional<draco::StatusOr<std::unique_ptr<draco::Mesh>>> mesh;
    try {
        mesh.emplace(draco::Decoder().DecodeMeshFromBuffer(&buffer));
    } catch (const std::exception& e) {  // a size the stream claims that cannot be allocated
        fail(path, label + ": corrupt Draco stream: " + oneLine(e.what()));
    }
    if (!mesh->ok()) {
        fail(path, label + ": corrupt Draco stream: " + oneLine(mesh->status().error_msg_string()));
    }
    return std::move(*mesh).value();
}

#endif  // STRATA_DRACO

}  // namespace

bool decodeDracoPrimitive(const std::string& path, const tinygltf::Model& model,
                          const tinygltf::Primitive& prim, const std::string& label,
                          LocalPrimitive& out, std::vector<std::string>& decoded) {
    const auto it = prim.extensions.find(kExtension);
    if (it == prim.extensions.end()) return false;
    const std::string extLabel = label + " " + kExtension;
    if (!it->second.IsObject()) fail(path, extLabel + " is not an object");
    const auto ids = dracoAttributes(path, it->second, extLabel);
#if !STRATA_DRACO
    // Without the decoder the primitive's accessors are the data (the spec's
    // conformance, second case): each must have some outside the stream.
    auto requireData = [&](int accessor, const std::string& what) {
        if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size()) return;
        const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(accessor)];
        if (acc.bufferView >= 0 || acc.sparse.isSparse) return;
        fail(path, label + " " + what + ": accessor " + std::to_string(accessor) +
                       " has no data outside its " + kExtension +
                       " stream, and strata was built without " + missingDecoder(kExtension));
    };
    for (const auto& [semantic, id] : ids) {
        const auto a = prim.attributes.find(semantic);
        if (a != prim.attributes.end()) requireData(a->second, semantic);
    }
    requireData(prim.indices, "indices");
    (void)out;
    (void)decoded;
    return false;
#else
    // The extension's "Restrictions on geometry type".
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP) {
        fail(path, extLabel + ": mode " + std::to_string(prim.mode) +
                       " is not allowed with Draco; only TRIANGLES (4) and TRIANGLE_STRIP (5)");
    }
    for (const auto& [semantic, id] : ids) {
        if (prim.attributes.count(semantic) == 0) {
            fail(path, extLabel + ": attributes names " + semantic +
                           ", which the primitive's attributes lack");
        }
    }
    if (!findId(ids, "POSITION")) fail(path, extLabel + ": attributes has no POSITION");

    const std::size_t viewIndex = extensionCount(path, it->second, "bufferView", extLabel, {});
    if (viewIndex >= model.bufferViews.size()) {
        fail(path, extLabel + ": bufferView " + std::to_string(viewIndex) + " does not exist (" +
                       std::to_string(model.bufferViews.size()) + " bufferViews)");
    }
    const tinygltf::BufferView& view = model.bufferViews[viewIndex];
    const std::string viewLabel = extLabel + " bufferView " + std::to_string(viewIndex);
    const unsigned char* bytes =
        bufferRange(path, model, view.buffer, view.byteOffset, view.byteLength, viewLabel);
    const std::unique_ptr<draco::Mesh> mesh = decodeStream(path, bytes, view.byteLength, viewLabel);

    LocalPrimitive local;
    local.material = prim.material;
    local.index = out.index;
    decoded.clear();
    for (const auto& [name, id] : ids) {
        const int accessor = prim.attributes.at(name);
        const bool valid = accessor >= 0 && static_cast<std::size_t>(accessor) < model.accessors.size();
        const Semantic* s = semanticOf(name, valid ? model.accessors[static_cast<std::size_t>(accessor)].type : -1);
        if (!s) continue;
        decoded.push_back(name);
        const std::vector<float> v = readAttribute(path, model, *mesh, prim, name, *s, id, label);
        const std::size_t n = v.size() / static_cast<std::size_t>(s->components);
        if (name == "POSITION" || name == "NORMAL") {
            auto& dst = name == "POSITION" ? local.positions : local.normals;
            dst.resize(n);
            for (std::size_t i = 0; i < n; ++i) dst[i] = glm::vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        } else if (name == "TANGENT") {
            local.tangents.resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                local.tangents[i] = glm::vec4(v[4 * i], v[4 * i + 1], v[4 * i + 2],
                                              v[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
            }
        } else if (name == "COLOR_0") {
            local.colors.resize(n);
            for (std::size_t i = 0; i < n; ++i)
                local.colors[i] = s->components == 3 ? glm::vec4(v[3 * i], v[3 * i + 1], v[3 * i + 2], 1.0f)
                                                     : glm::vec4(v[4 * i], v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]);
        } else if (s == &kJoints || s == &kWeights) {
            const int set = attributeSet(name, s == &kJoints ? "JOINTS_" : "WEIGHTS_");
            if (local.skin.size() <= static_cast<std::size_t>(set)) local.skin.resize(static_cast<std::size_t>(set) + 1);
            SkinInfluences& dst = local.skin[static_cast<std::size_t>(set)];
            for (std::size_t i = 0; i < n; ++i) {
                const glm::vec4 x(v[4 * i], v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]);
                if (s == &kJoints) dst.joints.push_back(glm::uvec4(x));
                else dst.weights.push_back(x);
            }
        } else {
            auto& dst = local.texcoords[texcoordSet(name)];
            dst.resize(n);
            for (std::size_t i = 0; i < n; ++i) dst[i] = glm::vec2(v[2 * i], v[2 * i + 1]);
        }
    }
    local.indices = readFaces(path, model, *mesh, prim, label);
    out = std::move(local);
    return true;
#endif
}

}  // namespace strata::gltf
