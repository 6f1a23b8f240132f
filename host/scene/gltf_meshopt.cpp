// EXT_meshopt_compression: every bufferView with the extension is decoded
// by libmeshoptimizer into a buffer of its own, which the view then names,
// so the accessors read it as an ordinary bufferView. The extension object
// (spec, "JSON schema updates"): buffer, byteOffset (0), byteLength,
// byteStride, count, mode (ATTRIBUTES, TRIANGLES, INDICES) and filter
// (NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL; ATTRIBUTES only).
#include <array>
#include <new>

#if STRATA_MESHOPT
#include <meshoptimizer.h>
#endif

#include "scene/gltf_internal.h"
#include "util/error.h"

namespace strata::gltf {

namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

#if STRATA_MESHOPT

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

struct Compressed {
    int buffer = -1;
    std::size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
};

std::string stringField(const std::string& path, const tinygltf::Value& ext, const char* key,
                        const std::string& label, const char* fallback) {
    if (!ext.Has(key)) {
        if (fallback) return fallback;
        fail(path, label + " has no " + key);
    }
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsString()) fail(path, label + ": " + key + " is not a string");
    return v.Get<std::string>();
}

// The names of Mode's and Filter's enumerators, in their order.
constexpr std::array<const char*, 3> kModes = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
constexpr std::array<const char*, 4> kFilters = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};

template <typename E, std::size_t N>
E named(const std::string& path, const std::string& label, const char* key, const std::string& name,
        const std::array<const char*, N>& names) {
    std::string list;
    for (std::size_t i = 0; i < N; ++i) {
        if (name == names[i]) return static_cast<E>(i);
        list += (i ? ", " : "") + std::string(names[i]);
    }
    fail(path, label + ": " + key + " " + quoted(name) + " is not one of " + list);
}

// The extension object, checked against the spec's rules of validity.
Compressed readExtension(const std::string& path, const tinygltf::BufferView& view,
                         const tinygltf::Value& ext, const std::string& label) {
    if (!ext.IsObject()) fail(path, label + " is not an object");
    Compressed c;
    c.buffer = static_cast<int>(extensionCount(path, ext, "buffer", label, {}));
    c.byteOffset = extensionCount(path, ext, "byteOffset", label, 0);
    c.byteLength = extensionCount(path, ext, "byteLength", label, {});
    c.byteStride = extensionCount(path, ext, "byteStride", label, {});
    c.count = extensionCount(path, ext, "count", label, {});

    const std::string mode = stringField(path, ext, "mode", label, nullptr);
    c.mode = named<Mode>(path, label, "mode", mode, kModes);
    const std::string filter = stringField(path, ext, "filter", label, "NONE");
    c.filter = named<Filter>(path, label, "filter", filter, kFilters);

    const std::string stride = "byteStride " + std::to_string(c.byteStride);
    if (view.byteStride != 0 && view.byteStride != c.byteStride) {
        fail(path, label + ": " + stride + " differs from the bufferView's byteStride " +
                       std::to_string(view.byteStride));
    }
    std::size_t decoded = 0;
    if (__builtin_mul_overflow(c.count, c.byteStride, &decoded) || decoded != view.byteLength) {
        fail(path, label + ": count " + std::to_string(c.count) + " x " + stride +
                       " is not the bufferView's byteLength " + std::to_string(view.byteLength));
    }
    if (c.mode == Mode::Attributes) {
        if (c.byteStride == 0 || c.byteStride % 4 != 0 || c.byteStride > 256) {
            fail(path, label + ": " + stride + " of ATTRIBUTES is not a multiple of 4 in [4, 256]");
        }
    } else {
        if (c.byteStride != 2 && c.byteStride != 4) {
            fail(path, label + ": " + stride + " of " + mode + " is not 2 or 4");
        }
        if (c.filter != Filter::None) fail(path, label + ": " + mode + " with filter " + filter);
        if (c.mode == Mode::Triangles && c.count % 3 != 0) {
            fail(path, label + ": TRIANGLES count " + std::to_string(c.count) +
                           " is not a multiple of 3");
        }
    }
    const bool strideOk = c.filter == Filter::None || c.filter == Filter::Exponential ||
                          (c.filter == Filter::Octahedral && (c.byteStride == 4 || c.byteStride == 8)) ||
                          (c.filter == Filter::Quaternion && c.byteStride == 8);
    if (!strideOk) {
        fail(path, label + ": filter " + filter + " with " + stride + " (OCTAHEDRAL needs 4 or 8, " +
                       "QUATERNION 8)");
    }
    // Every mode's bitstream (spec, Appendix A) spends at least 1/64 byte per
    // decoded byte: ATTRIBUTES 2 header bits per 16 bytes, TRIANGLES a code
    // byte per triangle, INDICES a byte per index. A larger claim is corrupt
    // and is refused before its memory is allocated.
    if (decoded / 64 > c.byteLength) {
        fail(path, label + ": byteLength " + std::to_string(c.byteLength) +
                       " is too short to decode " + std::to_string(decoded) + " bytes");
    }
    return c;
}

std::vector<unsigned char> decode(const std::string& path, const tinygltf::Model& model,
                                  const Compressed& c, const std::string& label) {
    const unsigned char* source =
        bufferRange(path, model, c.buffer, c.byteOffset, c.byteLength, label + " data");
    std::vector<unsigned char> out;
    try {
        out.resize(c.count * c.byteStride);
    } catch (const std::bad_alloc&) {
        fail(path, label + ": cannot allocate " + std::to_string(c.count * c.byteStride) +
                       " bytes to decode into");
    }
    int rc = 0;
    const char* decoder = "";
    switch (c.mode) {
        case Mode::Attributes:
            decoder = "meshopt_decodeVertexBuffer";
            rc = meshopt_decodeVertexBuffer(out.data(), c.count, c.byteStride, source, c.byteLength);
            break;
        case Mode::Triangles:
            decoder = "meshopt_decodeIndexBuffer";
            rc = meshopt_decodeIndexBuffer(out.data(), c.count, c.byteStride, source, c.byteLength);
            break;
        case Mode::Indices:
            decoder = "meshopt_decodeIndexSequence";
            rc = meshopt_decodeIndexSequence(out.data(), c.count, c.byteStride, source, c.byteLength);
            break;
    }
    if (rc != 0) {
        fail(path, label + ": corrupt or truncated data (" + decoder + " returned " +
                       std::to_string(rc) + ")");
    }
    switch (c.filter) {
        case Filter::None: break;
        case Filter::Octahedral: meshopt_decodeFilterOct(out.data(), c.count, c.byteStride); break;
        case Filter::Quaternion: meshopt_decodeFilterQuat(out.data(), c.count, c.byteStride); break;
        case Filter::Exponential: meshopt_decodeFilterExp(out.data(), c.count, c.byteStride); break;
    }
    return out;
}

#endif  // STRATA_MESHOPT

}  // namespace

void decodeMeshoptViews(const std::string& path, tinygltf::Model& model) {
    const std::size_t views = model.bufferViews.size();
    for (std::size_t v = 0; v < views; ++v) {
        tinygltf::BufferView& view = model.bufferViews[v];
        const auto it = view.extensions.find(kExtension);
        if (it == view.extensions.end()) continue;
        const std::string label = "bufferView " + std::to_string(v) + " " + kExtension;
#if STRATA_MESHOPT
        const Compressed c = readExtension(path, view, it->second, label);
        tinygltf::Buffer decoded;
        decoded.name = label;
        decoded.data = decode(path, model, c, label);
        model.buffers.push_back(std::move(decoded));
        view.buffer = static_cast<int>(model.buffers.size() - 1);
        view.byteOffset = 0;
#else
        // Without the decoder the view's own buffer is the data (a fallback
        // buffer that holds it); a placeholder has none.
        const bool hasBuffer = view.buffer >= 0 && static_cast<std::size_t>(view.buffer) < model.buffers.size();
        if (hasBuffer && model.buffers[static_cast<std::size_t>(view.buffer)].data.empty()) {
            fail(path, "bufferView " + std::to_string(v) + " has no data outside its " + kExtension +
                           " stream (buffer " + std::to_string(view.buffer) +
                           " is a placeholder), and strata was built without " +
                           missingDecoder(kExtension));
        }
#endif
    }
}

}  // namespace strata::gltf
