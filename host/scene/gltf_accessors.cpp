// Accessor decoding for the glTF loader: every read is range-checked against
// its bufferView and buffer before any byte is touched; an accessor without a
// bufferView is zeros; sparse substitution; integer components to floats.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <glm/ext/vector_float1.hpp>

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

bool isIndexType(int componentType) {
    return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
           componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// Type and component type in `format`.
bool typeFits(const AccessorFormat& format, const tinygltf::Accessor& acc) {
    return acc.type == format.type &&
           std::find(format.componentTypes.begin(), format.componentTypes.end(),
                     acc.componentType) != format.componentTypes.end();
}

// Type, component type and the normalized flag in `format`.
bool fits(const AccessorFormat& format, const tinygltf::Accessor& acc) {
    return typeFits(format, acc) && (acc.normalized || !format.normalizedIntegers ||
                                     acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
}

// `FLOAT/UNSIGNED_BYTE/UNSIGNED_SHORT VEC2, integers normalized`
std::string formatText(const AccessorFormat& format) {
    std::string out;
    bool integers = false;
    for (const int c : format.componentTypes) {
        if (!out.empty()) out += "/";
        out += componentName(c);
        integers = integers || c != TINYGLTF_COMPONENT_TYPE_FLOAT;
    }
    out += std::string(" ") + typeName(format.type);
    if (format.normalizedIntegers && integers) out += ", integers normalized";
    return out;
}

// The bytes of bufferView `index`, checked to lie inside its buffer. `who`
// names what refers to it, e.g. `accessor 3 (...): sparse.indices`.
struct ViewBytes {
    const unsigned char* data = nullptr;
    std::size_t byteLength = 0;
    std::size_t byteStride = 0;
    std::string label;  // `bufferView 2`
};

ViewBytes viewBytes(const std::string& path, const tinygltf::Model& model, int index,
                    const std::string& who) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.bufferViews.size()) {
        fail(path, who + " refers to bufferView " + std::to_string(index) +
                       ", which does not exist (" + std::to_string(model.bufferViews.size()) +
                       " bufferViews)");
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(index)];
    const std::string viewLabel = "bufferView " + std::to_string(index);
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
    return {bytes.data() + view.byteOffset, view.byteLength, view.byteStride, viewLabel};
}

// byteOffset + stride * (count - 1) + elementSize <= view.byteLength,
// overflow-checked; nothing to check for count 0.
void checkExtent(const std::string& path, const std::string& who, const ViewBytes& view,
                 std::size_t byteOffset, std::size_t stride, std::size_t count,
                 std::size_t elementSize) {
    if (count == 0) return;
    std::size_t span = 0;
    std::size_t end = 0;
    const bool overflow = __builtin_mul_overflow(stride, count - 1, &span) ||
                          __builtin_add_overflow(span, elementSize, &end) ||
                          __builtin_add_overflow(end, byteOffset, &end);
    if (overflow || end > view.byteLength) {
        std::ostringstream msg;
        msg << who << " is out of range of " << view.label << ": byteOffset " << byteOffset
            << " + byteStride " << stride << " * (count " << count << " - 1) + element size "
            << elementSize << " = ";
        if (overflow) {
            msg << "overflow";
        } else {
            msg << end;
        }
        msg << " > byteLength " << view.byteLength;
        fail(path, msg.str());
    }
}

std::uint32_t decodeIndex(const unsigned char* p, int componentType) {
    if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
    if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    std::uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

// One component as a float: for normalized integers the int-to-float table
// of glTF 2.0 3.11 and KHR_mesh_quantization, otherwise the integer value.
float decodeComponent(const unsigned char* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            std::int8_t c;
            std::memcpy(&c, p, sizeof c);
            return normalized ? std::max(static_cast<float>(c) / 127.0f, -1.0f)
                              : static_cast<float>(c);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? static_cast<float>(p[0]) / 255.0f : static_cast<float>(p[0]);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t c;
            std::memcpy(&c, p, sizeof c);
            return normalized ? std::max(static_cast<float>(c) / 32767.0f, -1.0f)
                              : static_cast<float>(c);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t c;
            std::memcpy(&c, p, sizeof c);
            return normalized ? static_cast<float>(c) / 65535.0f : static_cast<float>(c);
        }
        default: {  // FLOAT
            float f;
            std::memcpy(&f, p, sizeof f);
            return f;
        }
    }
}

// The validated bytes of one accessor: element i starts at data + i * stride
// (no data: every element is zero), then sparseIndices[j] is replaced by the
// element at sparseValues + j * elementSize. Every such element lies inside
// its buffer.
struct AccessorView {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    std::size_t elementSize = 0;
    int componentType = 0;
    bool normalized = false;
    std::vector<std::uint32_t> sparseIndices;  // strictly increasing, < count
    const unsigned char* sparseValues = nullptr;
};

// Calls element(i, bytes) for each element of the dense part, then for each
// sparse substitution in order.
template <class Element>
void forEachElement(const AccessorView& view, Element element) {
    if (view.data != nullptr) {
        for (std::size_t i = 0; i < view.count; ++i) element(i, view.data + i * view.stride);
    }
    for (std::size_t j = 0; j < view.sparseIndices.size(); ++j) {
        element(view.sparseIndices[j], view.sparseValues + j * view.elementSize);
    }
}

// A sparse byteOffset (an int in tinygltf) as a size.
std::size_t sparseOffset(const std::string& path, const std::string& who, int byteOffset) {
    if (byteOffset < 0) fail(path, who + " byteOffset " + std::to_string(byteOffset) + " is negative");
    return static_cast<std::size_t>(byteOffset);
}

// glTF 2.0 3.6.2.3: sparse.count in [1, count], indices u8/u16/u32 strictly
// increasing and < count, both bufferViews in range and read tightly packed.
void viewSparse(const std::string& path, const tinygltf::Model& model,
                const tinygltf::Accessor& acc, const std::string& label, AccessorView& out) {
    const auto& sparse = acc.sparse;
    if (sparse.count < 1 || static_cast<std::size_t>(sparse.count) > acc.count) {
        fail(path, label + ": sparse.count " + std::to_string(sparse.count) + " is not in [1, " +
                       std::to_string(acc.count) + "] (the accessor's count)");
    }
    const auto count = static_cast<std::size_t>(sparse.count);
    const std::string indicesLabel = label + ": sparse.indices";
    const int indexType = sparse.indices.componentType;
    if (!isIndexType(indexType)) {
        fail(path, indicesLabel + " componentType " + std::to_string(indexType) + " (" +
                       componentName(indexType) +
                       ") is not UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT");
    }
    const std::size_t indexSize = componentSize(indexType);
    const ViewBytes indexView = viewBytes(path, model, sparse.indices.bufferView, indicesLabel);
    const std::size_t indexOffset = sparseOffset(path, indicesLabel, sparse.indices.byteOffset);
    checkExtent(path, indicesLabel, indexView, indexOffset, indexSize, count, indexSize);

    const std::string valuesLabel = label + ": sparse.values";
    const ViewBytes valueView = viewBytes(path, model, sparse.values.bufferView, valuesLabel);
    const std::size_t valueOffset = sparseOffset(path, valuesLabel, sparse.values.byteOffset);
    checkExtent(path, valuesLabel, valueView, valueOffset, out.elementSize, count, out.elementSize);

    out.sparseIndices.resize(count);
    for (std::size_t j = 0; j < count; ++j) {
        const std::uint32_t i = decodeIndex(indexView.data + indexOffset + j * indexSize, indexType);
        const std::string at = "sparse index " + std::to_string(i) + " (sparse.indices[" +
                               std::to_string(j) + "])";
        if (i >= acc.count) {
            fail(path, label + ": " + at + " is out of range: the accessor has " +
                           std::to_string(acc.count) + " elements");
        }
        if (j > 0 && i <= out.sparseIndices[j - 1]) {
            fail(path, label + ": " + at + " is not greater than the previous one, " +
                           std::to_string(out.sparseIndices[j - 1]) +
                           "; sparse indices must be strictly increasing");
        }
        out.sparseIndices[j] = i;
    }
    out.sparseValues = valueView.data + valueOffset;
}

// The bytes of all the model's buffers (decoded EXT_meshopt_compression
// buffers included).
std::size_t bufferBytes(const tinygltf::Model& model) {
    std::size_t total = 0;
    for (const tinygltf::Buffer& b : model.buffers) total += b.data.size();
    return total;
}

// The most elements an accessor without a bufferView may have: one per byte
// of the file's buffers (a stored element takes at least one byte, so a
// count the data can use is below it), and kZeroAccessorFloor for any file.
// Its decoded floats then take at most 16 bytes per buffer byte, or 16 MiB.
std::size_t zeroAccessorLimit(const tinygltf::Model& model) {
    return std::max(kZeroAccessorFloor, bufferBytes(model));
}

AccessorView viewAccessor(const std::string& path, const tinygltf::Model& model, int index,
                          const std::string& use, const AccessorFormat& format,
                          const AccessorFormat* undeclared) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
        fail(path, use + ": accessor " + std::to_string(index) + " does not exist (" +
                       std::to_string(model.accessors.size()) + " accessors)");
    }
    const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
    const std::string label = "accessor " + std::to_string(index) + " (" + use + ")";
    if (!fits(format, acc)) {
        std::string msg = label + " is " + componentName(acc.componentType);
        if (typeFits(format, acc)) {
            msg += " but not normalized";
        } else {
            msg += std::string(" ") + typeName(acc.type) + "; expected " + formatText(format);
        }
        if (undeclared != nullptr && fits(*undeclared, acc)) {
            msg += " (KHR_mesh_quantization allows it, but the file does not declare that extension)";
        }
        fail(path, msg);
    }
    AccessorView out;
    out.count = acc.count;
    out.componentType = acc.componentType;
    out.normalized = acc.normalized;
    out.elementSize = componentSize(acc.componentType) * componentCount(acc.type);
    if (acc.bufferView < 0) {
        // Zeros (the schema's accessor.bufferView; then the sparse
        // substitution, glTF 2.0 3.6.2.3). A bufferView's length bounds the
        // count of the other accessors; this one is bounded by zeroAccessorLimit.
        const std::size_t limit = zeroAccessorLimit(model);
        if (acc.count > limit) {
            fail(path, label + " has no bufferView and count " + std::to_string(acc.count) +
                           ", more than the file can justify: at most max(" +
                           std::to_string(kZeroAccessorFloor) + ", the " + std::to_string(bufferBytes(model)) +
                           " bytes of its buffers) = " + std::to_string(limit) + " elements");
        }
    } else {
        const ViewBytes view = viewBytes(path, model, acc.bufferView, label);
        const std::size_t stride = view.byteStride != 0 ? view.byteStride : out.elementSize;
        if (stride < out.elementSize) {
            fail(path, label + ": " + view.label + " byteStride " + std::to_string(stride) +
                           " is smaller than the element size " + std::to_string(out.elementSize));
        }
        checkExtent(path, label, view, acc.byteOffset, stride, acc.count, out.elementSize);
        out.stride = stride;
        if (acc.count > 0) out.data = view.data + acc.byteOffset;
    }
    if (acc.sparse.isSparse) viewSparse(path, model, acc, label, out);
    return out;
}

const AccessorFormat kIndexFormat{TINYGLTF_TYPE_SCALAR,
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                                  false};

}  // namespace

template <int N>
std::vector<glm::vec<N, float>> readFloats(const std::string& path, const tinygltf::Model& model,
                                           int index, const std::string& use,
                                           const AccessorFormat& format,
                                           const AccessorFormat* undeclared) {
    using Vec = glm::vec<N, float>;
    static_assert(sizeof(Vec) == N * sizeof(float));
    const AccessorView view = viewAccessor(path, model, index, use, format, undeclared);
    std::vector<Vec> out(view.count, Vec(0.0f));
    const std::size_t size = componentSize(view.componentType);
    forEachElement(view, [&](std::size_t i, const unsigned char* p) {
        if (view.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            std::memcpy(&out[i], p, sizeof(Vec));
            return;
        }
        for (int k = 0; k < N; ++k) {
            out[i][k] = decodeComponent(p + static_cast<std::size_t>(k) * size, view.componentType,
                                        view.normalized);
        }
    });
    return out;
}

template std::vector<glm::vec1> readFloats<1>(const std::string&, const tinygltf::Model&, int,
                                              const std::string&, const AccessorFormat&,
                                              const AccessorFormat*);
template std::vector<glm::vec2> readFloats<2>(const std::string&, const tinygltf::Model&, int,
                                              const std::string&, const AccessorFormat&,
                                              const AccessorFormat*);
template std::vector<glm::vec3> readFloats<3>(const std::string&, const tinygltf::Model&, int,
                                              const std::string&, const AccessorFormat&,
                                              const AccessorFormat*);
template std::vector<glm::vec4> readFloats<4>(const std::string&, const tinygltf::Model&, int,
                                              const std::string&, const AccessorFormat&,
                                              const AccessorFormat*);

std::vector<glm::mat4> readMatrices(const std::string& path, const tinygltf::Model& model, int index,
                                    const std::string& use) {
    static const AccessorFormat kMat4{TINYGLTF_TYPE_MAT4, {TINYGLTF_COMPONENT_TYPE_FLOAT}, false};
    const AccessorView view = viewAccessor(path, model, index, use, kMat4, nullptr);
    std::vector<glm::mat4> out(view.count, glm::mat4(0.0f));
    static_assert(sizeof(glm::mat4) == 64);
    forEachElement(view, [&](std::size_t i, const unsigned char* p) { std::memcpy(&out[i], p, sizeof(glm::mat4)); });
    return out;
}

std::vector<std::uint32_t> readIndices(const std::string& path, const tinygltf::Model& model,
                                       int index, const std::string& use) {
    const AccessorView view = viewAccessor(path, model, index, use, kIndexFormat, nullptr);
    std::vector<std::uint32_t> out(view.count, 0);
    forEachElement(view, [&](std::size_t i, const unsigned char* p) {
        out[i] = decodeIndex(p, view.componentType);
    });
    return out;
}

}  // namespace strata::gltf
