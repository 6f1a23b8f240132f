// Accessor decoding for the glTF loader: every read is range-checked against
// its bufferView and buffer before any byte is touched.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <sstream>

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

std::string quoted(const std::string& s) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out = "\"";
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20 || u == 0x7f) {
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string oneLine(const std::string& text) {
    static constexpr std::size_t kMaxDataUri = 48;
    std::string out;
    std::string line;
    auto flush = [&] {
        const auto first = line.find_first_not_of(" \t\r");
        if (first != std::string::npos) {
            const auto last = line.find_last_not_of(" \t\r");
            if (!out.empty()) out += "; ";
            out += line.substr(first, last - first + 1);
        }
        line.clear();
    };
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n') {
            flush();
        } else {
            line += (u < 0x20 || u == 0x7f) ? ' ' : c;
        }
    }
    flush();
    // Data URIs quoted by tinygltf can be megabytes long: keep their start.
    for (std::size_t at = out.find("data:"); at != std::string::npos;
         at = out.find("data:", at + 1)) {
        const std::size_t end = std::min(out.find_first_of(" \"'", at), out.size());
        if (end - at > kMaxDataUri) {
            out.replace(at + kMaxDataUri, end - at - kMaxDataUri, "...");
        }
    }
    return out;
}

std::string meshLabel(const tinygltf::Model& model, int mesh) {
    std::string label = "mesh " + std::to_string(mesh);
    const auto& name = model.meshes[static_cast<std::size_t>(mesh)].name;
    if (!name.empty()) label += " (" + quoted(name) + ")";
    return label;
}

namespace {

// Bytes of one component; 0 for an unknown component type.
std::size_t componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
        default: return 0;
    }
}

const char* componentName(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
        default: return "unknown";
    }
}

// Components per element; 0 for an unknown type.
std::size_t componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "unknown";
    }
}

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "unknown";
    }
}

// The validated bytes of one accessor: element i starts at data + i * stride
// and its elementSize bytes lie inside the buffer.
struct AccessorView {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    int componentType = 0;
};

// `use` names what the accessor is read for, e.g. `mesh 0 ("Quad") primitive 0
// POSITION`; `componentTypes` lists the accepted component types.
AccessorView viewAccessor(const std::string& path, const tinygltf::Model& model, int index,
                          const std::string& use, int type,
                          std::initializer_list<int> componentTypes) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        fail(path, use + ": accessor " + std::to_string(index) + " does not exist (" +
                       std::to_string(model.accessors.size()) + " accessors)");
    }
    const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
    const std::string label = "accessor " + std::to_string(index) + " (" + use + ")";

    std::string accepted;
    bool componentOk = false;
    for (const int c : componentTypes) {
        if (!accepted.empty()) accepted += "/";
        accepted += componentName(c);
        componentOk = componentOk || acc.componentType == c;
    }
    if (acc.type != type || !componentOk) {
        fail(path, label + " is " + componentName(acc.componentType) + " " + typeName(acc.type) +
                       "; expected " + accepted + " " + typeName(type));
    }
    if (acc.sparse.isSparse) fail(path, label + " is sparse; sparse accessors are not supported");
    if (acc.bufferView < 0) {
        fail(path, label + " has no bufferView; accessors without one are not supported");
    }
    if (static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size()) {
        fail(path, label + " refers to bufferView " + std::to_string(acc.bufferView) +
                       ", which does not exist (" + std::to_string(model.bufferViews.size()) +
                       " bufferViews)");
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
    const std::string viewLabel = "bufferView " + std::to_string(acc.bufferView);
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        fail(path, viewLabel + " refers to buffer " + std::to_string(view.buffer) +
                       ", which does not exist (" + std::to_string(model.buffers.size()) +
                       " buffers)");
    }
    const std::vector<unsigned char>& bytes =
        model.buffers[static_cast<std::size_t>(view.buffer)].data;
    std::size_t viewEnd = 0;
    if (__builtin_add_overflow(view.byteOffset, view.byteLength, &viewEnd) ||
        viewEnd > bytes.size()) {
        fail(path, viewLabel + " is out of range of buffer " + std::to_string(view.buffer) +
                       ": byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                       std::to_string(view.byteLength) + " > buffer size " +
                       std::to_string(bytes.size()));
    }

    const std::size_t elementSize = componentSize(acc.componentType) * componentCount(acc.type);
    const std::size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize) {
        fail(path, label + ": " + viewLabel + " byteStride " + std::to_string(stride) +
                       " is smaller than the element size " + std::to_string(elementSize));
    }
    AccessorView out;
    out.stride = stride;
    out.count = acc.count;
    out.componentType = acc.componentType;
    if (acc.count == 0) return out;

    // offset + stride * (count - 1) + elementSize <= byteLength, overflow-checked.
    std::size_t span = 0;
    std::size_t end = 0;
    const bool overflow = __builtin_mul_overflow(stride, acc.count - 1, &span) ||
                          __builtin_add_overflow(span, elementSize, &end) ||
                          __builtin_add_overflow(end, acc.byteOffset, &end);
    if (overflow || end > view.byteLength) {
        std::ostringstream msg;
        msg << label << " is out of range of " << viewLabel << ": byteOffset " << acc.byteOffset
            << " + byteStride " << stride << " * (count " << acc.count << " - 1) + element size "
            << elementSize << " = ";
        if (overflow) {
            msg << "overflow";
        } else {
            msg << end;
        }
        msg << " > byteLength " << view.byteLength;
        fail(path, msg.str());
    }
    out.data = bytes.data() + view.byteOffset + acc.byteOffset;
    return out;
}

std::vector<glm::vec3> readVec3(const std::string& path, const tinygltf::Model& model, int index,
                                const std::string& use, bool requireFinite) {
    const AccessorView view =
        viewAccessor(path, model, index, use, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    std::vector<glm::vec3> out(view.count);
    for (std::size_t i = 0; i < view.count; ++i) {
        float xyz[3];
        std::memcpy(xyz, view.data + i * view.stride, sizeof xyz);
        out[i] = glm::vec3(xyz[0], xyz[1], xyz[2]);
        if (requireFinite &&
            !(std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]))) {
            std::ostringstream msg;
            msg << "accessor " << index << " (" << use << "): vertex " << i
                << " has a NaN or Inf coordinate (" << xyz[0] << ", " << xyz[1] << ", " << xyz[2]
                << ")";
            fail(path, msg.str());
        }
    }
    return out;
}

// TEXCOORD_n: float, or unsigned byte/short normalized to [0, 1] (glTF 2.0
// 3.7.2.1: c / 255, c / 65535).
std::vector<glm::vec2> readTexcoords(const std::string& path, const tinygltf::Model& model,
                                     int index, const std::string& use) {
    const AccessorView view =
        viewAccessor(path, model, index, use, TINYGLTF_TYPE_VEC2,
                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    const auto& acc = model.accessors[static_cast<std::size_t>(index)];
    if (view.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !acc.normalized) {
        fail(path, "accessor " + std::to_string(index) + " (" + use + ") is " +
                       componentName(view.componentType) + " but not normalized");
    }
    std::vector<glm::vec2> out(view.count);
    for (std::size_t i = 0; i < view.count; ++i) {
        const unsigned char* p = view.data + i * view.stride;
        if (view.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            float uv[2];
            std::memcpy(uv, p, sizeof uv);
            if (!std::isfinite(uv[0]) || !std::isfinite(uv[1])) {
                fail(path, "accessor " + std::to_string(index) + " (" + use + "): element " +
                               std::to_string(i) + " is NaN or Inf");
            }
            out[i] = glm::vec2(uv[0], uv[1]);
        } else if (view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            out[i] = glm::vec2(p[0], p[1]) / 255.0f;
        } else {
            std::uint16_t uv[2];
            std::memcpy(uv, p, sizeof uv);
            out[i] = glm::vec2(uv[0], uv[1]) / 65535.0f;
        }
    }
    return out;
}

// TANGENT: float VEC4, xyz the tangent, w = +-1 the handedness.
std::vector<glm::vec4> readTangents(const std::string& path, const tinygltf::Model& model,
                                    int index, const std::string& use) {
    const AccessorView view =
        viewAccessor(path, model, index, use, TINYGLTF_TYPE_VEC4, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    std::vector<glm::vec4> out(view.count);
    for (std::size_t i = 0; i < view.count; ++i) {
        float t[4];
        std::memcpy(t, view.data + i * view.stride, sizeof t);
        out[i] = glm::vec4(t[0], t[1], t[2], t[3] < 0.0f ? -1.0f : 1.0f);
    }
    return out;
}

std::vector<std::uint32_t> readIndices(const std::string& path, const tinygltf::Model& model,
                                       int index, const std::string& use) {
    const AccessorView view =
        viewAccessor(path, model, index, use, TINYGLTF_TYPE_SCALAR,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    std::vector<std::uint32_t> out(view.count);
    for (std::size_t i = 0; i < view.count; ++i) {
        const unsigned char* p = view.data + i * view.stride;
        if (view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            out[i] = p[0];
        } else if (view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            std::uint16_t v;
            std::memcpy(&v, p, sizeof v);
            out[i] = v;
        } else {
            std::memcpy(&out[i], p, sizeof out[i]);
        }
    }
    return out;
}

}  // namespace

std::vector<LocalPrimitive> decodeMesh(const std::string& path, const tinygltf::Model& model,
                                       int mesh) {
    const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(mesh)];
    std::vector<LocalPrimitive> out;
    out.reserve(m.primitives.size());
    for (std::size_t p = 0; p < m.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = m.primitives[p];
        const std::string label = meshLabel(model, mesh) + " primitive " + std::to_string(p);
        if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
            fail(path, label + ": mode " + std::to_string(prim.mode) + " (" + modeName(prim.mode) +
                           ") is not supported; only TRIANGLES");
        }
        if (prim.material < -1 || (prim.material >= 0 && static_cast<std::size_t>(prim.material) >=
                                                             model.materials.size())) {
            fail(path, label + ": material " + std::to_string(prim.material) + " does not exist (" +
                           std::to_string(model.materials.size()) + " materials)");
        }
        LocalPrimitive local;
        local.material = prim.material;
        // KHR_draco_mesh_compression: the Draco stream instead of the accessors.
        if (decodeDracoPrimitive(path, model, prim, label, local)) {
            out.push_back(std::move(local));
            continue;
        }

        const auto position = prim.attributes.find("POSITION");
        if (position == prim.attributes.end()) fail(path, label + ": has no POSITION attribute");
        local.positions = readVec3(path, model, position->second, label + " POSITION", true);
        const std::size_t vertexCount = local.positions.size();
        if (vertexCount > std::numeric_limits<std::uint32_t>::max()) {
            fail(path, label + ": " + std::to_string(vertexCount) + " vertices is too many");
        }

        const auto normal = prim.attributes.find("NORMAL");
        if (normal != prim.attributes.end()) {
            local.normals = readVec3(path, model, normal->second, label + " NORMAL", false);
            if (local.normals.size() != vertexCount) {
                fail(path, label + ": NORMAL has " + std::to_string(local.normals.size()) +
                               " elements but POSITION has " + std::to_string(vertexCount));
            }
        }

        auto sameCount = [&](std::size_t n, const std::string& name) {
            if (n != vertexCount) {
                fail(path, label + ": " + name + " has " + std::to_string(n) +
                               " elements but POSITION has " + std::to_string(vertexCount));
            }
        };
        for (int set = 0; set < 2; ++set) {
            const std::string name = "TEXCOORD_" + std::to_string(set);
            const auto uv = prim.attributes.find(name);
            if (uv == prim.attributes.end()) continue;
            local.texcoords[set] = readTexcoords(path, model, uv->second, label + " " + name);
            sameCount(local.texcoords[set].size(), name);
        }
        const auto tangent = prim.attributes.find("TANGENT");
        if (tangent != prim.attributes.end()) {
            local.tangents = readTangents(path, model, tangent->second, label + " TANGENT");
            sameCount(local.tangents.size(), "TANGENT");
        }

        if (prim.indices >= 0) {
            local.indices = readIndices(path, model, prim.indices, label + " indices");
            if (local.indices.size() % 3 != 0) {
                fail(path, label + ": index count " + std::to_string(local.indices.size()) +
                               " is not a multiple of 3");
            }
            for (std::size_t i = 0; i < local.indices.size(); ++i) {
                if (local.indices[i] >= vertexCount) {
                    fail(path, label + ": index " + std::to_string(local.indices[i]) +
                                   " (indices[" + std::to_string(i) + "], accessor " +
                                   std::to_string(prim.indices) +
                                   ") is out of range: POSITION has " +
                                   std::to_string(vertexCount) + " vertices");
                }
            }
        } else {
            if (vertexCount % 3 != 0) {
                fail(path, label + ": vertex count " + std::to_string(vertexCount) +
                               " of a non-indexed primitive is not a multiple of 3");
            }
            local.indices.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i) {
                local.indices[i] = static_cast<std::uint32_t>(i);
            }
        }
        out.push_back(std::move(local));
    }
    return out;
}

}  // namespace strata::gltf
