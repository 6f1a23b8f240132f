// Mesh primitives for the glTF loader: the accessor storages each attribute
// accepts (glTF 2.0 3.7.2.1, and KHR_mesh_quantization when the file declares
// it), and the triangles of each primitive mode.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "scene/gltf_deform.h"
#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;

// An attribute's storages in core glTF 2.0 (3.7.2.1) and with
// KHR_mesh_quantization ("Extending Mesh Attributes"; the core ones included).
struct AttributeFormats {
    AccessorFormat core;
    AccessorFormat quantized;
};

const AttributeFormats kPosition{{TINYGLTF_TYPE_VEC3, {kFloat}, false},
                                 {TINYGLTF_TYPE_VEC3, {kFloat, kByte, kUByte, kShort, kUShort}, false}};
const AttributeFormats kNormal{{TINYGLTF_TYPE_VEC3, {kFloat}, false},
                               {TINYGLTF_TYPE_VEC3, {kFloat, kByte, kShort}, true}};
const AttributeFormats kTangent{{TINYGLTF_TYPE_VEC4, {kFloat}, false},
                                {TINYGLTF_TYPE_VEC4, {kFloat, kByte, kShort}, true}};
// COLOR_0: VEC3 or VEC4 of these (glTF 2.0 3.7.2.1; KHR_mesh_quantization
// adds none).
const AccessorFormat kColor3{TINYGLTF_TYPE_VEC3, {kFloat, kUByte, kUShort}, true};
const AccessorFormat kColor4{TINYGLTF_TYPE_VEC4, {kFloat, kUByte, kUShort}, true};
const AttributeFormats kTexcoord{{TINYGLTF_TYPE_VEC2, {kFloat, kUByte, kUShort}, true},
                                 {TINYGLTF_TYPE_VEC2, {kFloat, kByte, kUByte, kShort, kUShort}, false}};

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

bool declares(const tinygltf::Model& model, const std::string& extension) {
    auto in = [&](const std::vector<std::string>& list) {
        return std::find(list.begin(), list.end(), extension) != list.end();
    };
    return in(model.extensionsUsed) || in(model.extensionsRequired);
}

// Triangles of a TRIANGLE_STRIP or TRIANGLE_FAN over the vertex sequence `v`
// (its indices, or 0..n-1), n >= 3, by glTF 2.0 3.7.2.1: strip triangle i is
// (v[i], v[i+1], v[i+2]) for even i and (v[i], v[i+2], v[i+1]) for odd i; fan
// triangle i is (v[i+1], v[i+2], v[0]). A triangle that repeats an index is
// dropped: it has no area (writers repeat indices to join strips), and an
// emissive one would be reported as a zero-area emitter.
std::vector<std::uint32_t> stripOrFanTriangles(const std::vector<std::uint32_t>& v, int mode) {
    std::vector<std::uint32_t> out;
    out.reserve(3 * (v.size() - 2));
    for (std::size_t i = 0; i + 2 < v.size(); ++i) {
        std::uint32_t a = v[i], b = v[i + 1], c = v[i + 2];
        if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            a = v[i + 1], b = v[i + 2], c = v[0];
        } else if (i % 2 == 1) {
            std::swap(b, c);
        }
        if (a == b || b == c || a == c) continue;
        out.insert(out.end(), {a, b, c});
    }
    return out;
}

template <int N>
std::vector<glm::vec<N, float>> readAttribute(const std::string& path, const tinygltf::Model& model,
                                              int index, const std::string& use,
                                              const AttributeFormats& formats, bool quantization) {
    return readFloats<N>(path, model, index, use, quantization ? formats.quantized : formats.core,
                         quantization ? nullptr : &formats.quantized);
}

std::vector<glm::vec3> readPositions(const std::string& path, const tinygltf::Model& model,
                                     int index, const std::string& use, bool quantization) {
    std::vector<glm::vec3> out = readAttribute<3>(path, model, index, use, kPosition, quantization);
    for (std::size_t i = 0; i < out.size(); ++i) {
        const glm::vec3 p = out[i];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
            std::ostringstream msg;
            msg << "accessor " << index << " (" << use << "): vertex " << i
                << " has a NaN or Inf coordinate (" << p.x << ", " << p.y << ", " << p.z << ")";
            fail(path, msg.str());
        }
    }
    return out;
}

std::vector<glm::vec2> readTexcoords(const std::string& path, const tinygltf::Model& model,
                                     int index, const std::string& use, bool quantization) {
    std::vector<glm::vec2> out = readAttribute<2>(path, model, index, use, kTexcoord, quantization);
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y)) {
            fail(path, "accessor " + std::to_string(index) + " (" + use + "): element " +
                           std::to_string(i) + " is NaN or Inf");
        }
    }
    return out;
}

// TANGENT: xyz the tangent, w = +-1 the handedness.
std::vector<glm::vec4> readTangents(const std::string& path, const tinygltf::Model& model,
                                    int index, const std::string& use, bool quantization) {
    std::vector<glm::vec4> out = readAttribute<4>(path, model, index, use, kTangent, quantization);
    for (glm::vec4& t : out) t.w = t.w < 0.0f ? -1.0f : 1.0f;
    return out;
}

// COLOR_0 as linear RGBA: a VEC3 accessor gets alpha 1; every value finite.
std::vector<glm::vec4> readColors(const std::string& path, const tinygltf::Model& model, int index,
                                  const std::string& use) {
    const bool exists = index >= 0 && static_cast<std::size_t>(index) < model.accessors.size();
    const int type = exists ? model.accessors[static_cast<std::size_t>(index)].type : TINYGLTF_TYPE_VEC4;
    if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4) {
        fail(path, "accessor " + std::to_string(index) + " (" + use + ") is neither VEC3 nor VEC4");
    }
    const bool rgb = type == TINYGLTF_TYPE_VEC3;
    std::vector<glm::vec4> out;
    if (rgb) {
        for (const glm::vec3& c : readFloats<3>(path, model, index, use, kColor3, nullptr)) out.emplace_back(c, 1.0f);
    } else {
        out = readFloats<4>(path, model, index, use, kColor4, nullptr);
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
        const glm::vec4 c = out[i];
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w)) {
            fail(path, "accessor " + std::to_string(index) + " (" + use + "): element " + std::to_string(i) +
                           " is NaN or Inf");
        }
    }
    return out;
}

}  // namespace

int attributeSet(const std::string& semantic, std::string_view prefix) {
    if (semantic.size() <= prefix.size() || semantic.size() > prefix.size() + 9 ||
        semantic.compare(0, prefix.size(), prefix) != 0)
        return -1;
    const std::string digits = semantic.substr(prefix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || (digits.size() > 1 && digits[0] == '0'))
        return -1;
    return std::stoi(digits);
}

LocalMesh decodeMesh(const std::string& path, const tinygltf::Model& model, int mesh) {
    const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(mesh)];
    const bool quantization = declares(model, "KHR_mesh_quantization");
    LocalMesh out;
    out.primitives.reserve(m.primitives.size());
    for (std::size_t p = 0; p < m.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = m.primitives[p];
        const std::string label = meshLabel(model, mesh) + " primitive " + std::to_string(p);
        switch (prim.mode) {
            case TINYGLTF_MODE_TRIANGLES:
            case TINYGLTF_MODE_TRIANGLE_STRIP:
            case TINYGLTF_MODE_TRIANGLE_FAN: break;
            case TINYGLTF_MODE_POINTS:
            case TINYGLTF_MODE_LINE:
            case TINYGLTF_MODE_LINE_LOOP:
            case TINYGLTF_MODE_LINE_STRIP:
                out.skipped.push_back(label + " (" + modeName(prim.mode) + ")");
                continue;
            default:
                fail(path, label + ": mode " + std::to_string(prim.mode) +
                               " is not a glTF primitive mode (0 to 6)");
        }
        if (prim.material < -1 || (prim.material >= 0 && static_cast<std::size_t>(prim.material) >=
                                                             model.materials.size())) {
            fail(path, label + ": material " + std::to_string(prim.material) + " does not exist (" +
                           std::to_string(model.materials.size()) + " materials)");
        }
        LocalPrimitive local;
        local.material = prim.material;
        local.index = p;
        // KHR_draco_mesh_compression: the attributes in the Draco stream and
        // the index sequence from it; any other attribute from its accessor.
        std::vector<std::string> inStream;
        const bool draco = decodeDracoPrimitive(path, model, prim, label, local, inStream);
        auto fromAccessor = [&](const std::string& semantic) {
            const auto it = prim.attributes.find(semantic);
            if (it == prim.attributes.end()) return -1;
            return std::find(inStream.begin(), inStream.end(), semantic) == inStream.end() ? it->second : -1;
        };

        if (!draco) {
            const auto position = prim.attributes.find("POSITION");
            // glTF 2.0 3.7.2.1: a primitive without positions is not rendered.
            if (position == prim.attributes.end()) {
                out.invalid.push_back(label + " (no POSITION)");
                continue;
            }
            local.positions =
                readPositions(path, model, position->second, label + " POSITION", quantization);
        }
        const std::size_t vertexCount = local.positions.size();
        if (vertexCount > std::numeric_limits<std::uint32_t>::max()) {
            fail(path, label + ": " + std::to_string(vertexCount) + " vertices is too many");
        }

        auto sameCount = [&](std::size_t n, const std::string& name) {
            if (n != vertexCount) {
                fail(path, label + ": " + name + " has " + std::to_string(n) +
                               " elements but POSITION has " + std::to_string(vertexCount));
            }
        };
        if (const int normal = fromAccessor("NORMAL"); normal >= 0) {
            local.normals = readAttribute<3>(path, model, normal, label + " NORMAL", kNormal,
                                             quantization);
            sameCount(local.normals.size(), "NORMAL");
        }
        for (const auto& [name, accessor] : prim.attributes) {
            const int set = texcoordSet(name);
            if (set < 0 || fromAccessor(name) < 0) continue;
            local.texcoords[set] = readTexcoords(path, model, accessor, label + " " + name, quantization);
            sameCount(local.texcoords[set].size(), name);
        }
        if (const int color = fromAccessor("COLOR_0"); color >= 0) {
            local.colors = readColors(path, model, color, label + " COLOR_0");
            sameCount(local.colors.size(), "COLOR_0");
        }
        if (const int tangent = fromAccessor("TANGENT"); tangent >= 0) {
            local.tangents = readTangents(path, model, tangent, label + " TANGENT", quantization);
            sameCount(local.tangents.size(), "TANGENT");
        }

        local.targets = readMorphTargets(path, model, prim, label, vertexCount, quantization);
        std::vector<SkinInfluences> streamSkin = std::move(local.skin);
        local.skin = readSkinInfluences(path, model, prim, label, vertexCount, inStream, streamSkin);

        const bool triangles = prim.mode == TINYGLTF_MODE_TRIANGLES;
        std::vector<std::uint32_t> sequence;
        if (draco) {
            sequence = std::move(local.indices);  // in range: checked against the decoded points
        } else if (prim.indices >= 0) {
            sequence = readIndices(path, model, prim.indices, label + " indices");
            if (triangles && sequence.size() % 3 != 0) {
                fail(path, label + ": index count " + std::to_string(sequence.size()) +
                               " is not a multiple of 3");
            }
            for (std::size_t i = 0; i < sequence.size(); ++i) {
                if (sequence[i] >= vertexCount) {
                    fail(path, label + ": index " + std::to_string(sequence[i]) + " (indices[" +
                                   std::to_string(i) + "], accessor " +
                                   std::to_string(prim.indices) +
                                   ") is out of range: POSITION has " +
                                   std::to_string(vertexCount) + " vertices");
                }
            }
        } else {
            if (triangles && vertexCount % 3 != 0) {
                out.invalid.push_back(label + " (" + std::to_string(vertexCount) +
                                      " vertices without indices, not a multiple of 3)");
                continue;
            }
            sequence.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i) {
                sequence[i] = static_cast<std::uint32_t>(i);
            }
        }
        if (triangles) {
            local.indices = std::move(sequence);
        } else {
            if (sequence.size() < 3) {
                fail(path, label + ": " + (prim.indices >= 0 || draco ? "index count " : "vertex count ") +
                               std::to_string(sequence.size()) + " of a " + modeName(prim.mode) +
                               " primitive is less than 3");
            }
            local.indices = stripOrFanTriangles(sequence, prim.mode);
        }
        out.primitives.push_back(std::move(local));
    }
    return out;
}

}  // namespace strata::gltf
