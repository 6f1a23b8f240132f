// Reading a glTF file: the bytes (.gltf JSON or .glb binary), the uris it
// names (next to the file only), tinygltf's parse with its messages made
// one line, and the extensions strata reads.
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <filesystem>
#include <string_view>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>
#if STRATA_WEBP
#include <webp/decode.h>
#endif
#if STRATA_AVIF
#include "avif/module.h"
#endif

#include "scene/gltf_deform.h"
#include "scene/gltf_internal.h"
#include "util/error.h"
#include "util/files.h"
#include "util/limits.h"
#include "util/memory.h"

namespace strata::gltf {

namespace {

// Extensions strata reads; others named in extensionsUsed are ignored with a
// warning, and in extensionsRequired are an error.
constexpr std::string_view kSupportedExtensions[] = {
    "EXT_mesh_gpu_instancing", "EXT_meshopt_compression", "KHR_draco_mesh_compression",
    "KHR_lights_punctual", "KHR_materials_anisotropy", "KHR_materials_clearcoat", "KHR_materials_emissive_strength", "KHR_materials_ior",
    "KHR_materials_diffuse_transmission", "KHR_materials_dispersion", "KHR_materials_iridescence",
    "KHR_materials_sheen", "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_unlit",
    "KHR_materials_variants",
    "KHR_materials_volume", "KHR_materials_volume_scatter", "KHR_mesh_quantization",
    "KHR_texture_transform", "EXT_texture_webp", "EXT_texture_avif", "KHR_texture_basisu", "KHR_animation_pointer",
    "KHR_node_visibility"};

std::string supportedList() {
    std::string out;
    for (auto e : kSupportedExtensions) out += (out.empty() ? "" : ", ") + std::string(e);
    return out;
}

}  // namespace

std::vector<unsigned char> readSceneFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail(path, "cannot read file: is a directory");
    errno = 0;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                         &std::fclose);
    if (!file) fail(path, std::string("cannot open file: ") + std::strerror(errno));
    std::vector<unsigned char> bytes;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec) bytes.reserve(size);  // one allocation (not a doubling vector) for a regular file
    unsigned char chunk[1 << 16];
    std::size_t got = 0;
    while ((got = std::fread(chunk, 1, sizeof chunk, file.get())) > 0) {
        bytes.insert(bytes.end(), chunk, chunk + got);
    }
    if (std::ferror(file.get()))
        fail(path, std::string("cannot read file: ") + std::strerror(errno));
    return bytes;
}

namespace {

// Why a uri that is not a data: URI is not read, or "": glTF's uris are
// relative references, and an absolute path or a URI scheme (file:,
// http:, ...) would let a scene name any file of the machine.
std::string uriProblem(const std::string& uri) {
    if (!uri.empty() && (uri[0] == '/' || uri[0] == '\\'))
        return "is an absolute path; a glTF uri is a path relative to the scene's folder or a data: URI";
    std::size_t i = 0;
    while (i < uri.size() && (std::isalnum(static_cast<unsigned char>(uri[i])) || uri[i] == '+' || uri[i] == '-' ||
                              uri[i] == '.'))
        ++i;
    if (i > 0 && i < uri.size() && uri[i] == ':' && std::isalpha(static_cast<unsigned char>(uri[0]))) {
        if (i == 1) return "is an absolute (drive letter) path; a glTF uri is a path relative to the scene's folder or a data: URI";
        if (uri.compare(0, 5, "data:") == 0)
            return "is a data: URI strata cannot read (base64 data of the media types of glTF buffers and images "
                   "only)";
        return "has the scheme " + gltf::quoted(uri.substr(0, i + 1)) +
               "; strata reads paths relative to the scene's folder and data: URIs only";
    }
    return "";
}

bool hasGlbMagic(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

bool hasGlbExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".glb";
}

// Files named by uris (buffers, images) are looked up next to the glTF file
// only (tinygltf also tries the working directory); misses are recorded.
// glTF uris are relative references or data: URIs (glTF 2.0 section 3.3):
// an absolute path, a file: URI or any other scheme is refused, and under
// --restrict-paths so is a path that resolves (symlinks followed) outside
// that folder.
struct FsContext {
    std::string prefix;                // base directory ending in '/'
    std::string root;                  // --restrict-paths, canonical; empty: none
    std::vector<std::string> missing;  // paths looked up and not found
    std::string unreadable;            // the first uri that names a directory or an empty file
    std::string refused;               // the first uri refused by the rules above
};

bool fileExists(const std::string& file, void* user) {
    auto* context = static_cast<FsContext*>(user);
    if (file.rfind(context->prefix, 0) != 0) return false;
    const std::string uri = file.substr(context->prefix.size());
    if (const std::string why = uriProblem(uri); !why.empty()) {
        if (context->refused.empty()) context->refused = "uri " + gltf::quoted(uri) + " " + why;
        return false;
    }
    if (!context->root.empty()) {
        if (const std::string outside = outsideRoot(file, context->root); !outside.empty()) {
            if (context->refused.empty())
                context->refused = "uri " + gltf::quoted(uri) + " resolves to " + outside + ", outside --restrict-paths " +
                                   context->root;
            return false;
        }
    }
    if (tinygltf::FileExists(file, nullptr)) return true;
    context->missing.push_back(file);
    return false;
}

std::string keepPath(const std::string& file, void*) { return file; }

// tinygltf's reader, but a directory or an empty file is refused with a
// message of ours (a directory made tinygltf allocate its bogus size and
// fail with std::bad_alloc; an empty image was a warning, then an error).
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
    auto* context = static_cast<FsContext*>(user);
    if (const Unusable u = unusableInput(file); u != Unusable::No) {
        const char* what = u == Unusable::Directory ? "a directory" : "an empty file";
        if (context->unreadable.empty()) {
            const std::string uri = file.rfind(context->prefix, 0) == 0 ? file.substr(context->prefix.size()) : file;
            context->unreadable = "unreadable file: uri " + gltf::quoted(uri) + " refers to " + file + ", which is " + what;
        }
        if (err) *err += context->unreadable + "\n";
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, file, nullptr);
}

// tinygltf's stb_image loader (RGBA, 8 or 16 bits), with the failure kept
// as one message naming the image instead of tinygltf's multi-line text.
struct ImageContext {
    std::string failure;
    std::vector<std::string> undecodable;  // images left without pixels: a warning, an error where read
    std::uint64_t budget = 0;   // host memory the decoded images may take (0: no limit)
    std::uint64_t decoded = 0;  // bytes the images decoded so far claimed
};

// A WebP file (RIFF container, WEBP form) and a KTX2 file (its 12-byte
// identifier), told apart by their first bytes.
bool isWebp(const unsigned char* bytes, int size) {
    return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}
bool isKtx2(const unsigned char* bytes, int size) {
    static constexpr unsigned char kId[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    return size >= 12 && std::memcmp(bytes, kId, sizeof kId) == 0;
}

// PNG and JPEG, glTF 2.0's own image formats, by their signatures: the
// only files handed to stb_image, whose other readers (GIF, PSD, PNM, HDR,
// PIC, TGA, BMP) glTF never needs and which tinygltf copies out of bounds
// for some PNM files (the image fuzzer's finding).
bool isPng(const unsigned char* bytes, int size) {
    static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    return size >= 8 && std::memcmp(bytes, kPng, sizeof kPng) == 0;
}
bool isJpeg(const unsigned char* bytes, int size) {
    return size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

#if STRATA_AVIF
// An AVIF file: an ISO BMFF 'ftyp' box of major brand avif (or avis).
bool isAvif(const unsigned char* bytes, int size) {
    return size >= 12 && std::memcmp(bytes + 4, "ftyp", 4) == 0 &&
           (std::memcmp(bytes + 8, "avif", 4) == 0 || std::memcmp(bytes + 8, "avis", 4) == 0);
}

// EXT_texture_avif through the AVIF module (host/avif): its first frame.
bool decodeAvif(tinygltf::Image* image, const avif::Api& api, const unsigned char* bytes, int size) {
    avif::Image frame;
    if (!api.decode(bytes, static_cast<std::size_t>(size), &frame)) return false;
    image->width = static_cast<int>(frame.width);
    image->height = static_cast<int>(frame.height);
    image->component = 4;
    image->bits = frame.bits;
    image->pixel_type = frame.bits == 16 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(frame.rgba);
    return true;
}
#endif

#if STRATA_WEBP
// EXT_texture_webp through libwebp: RGBA, 8 bits.
bool decodeWebp(tinygltf::Image* image, const unsigned char* bytes, int size) {
    int width = 0, height = 0;
    std::unique_ptr<std::uint8_t, void (*)(void*)> rgba(WebPDecodeRGBA(bytes, static_cast<std::size_t>(size), &width, &height),
                                                       &WebPFree);
    if (!rgba || width < 1 || height < 1) return false;
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(rgba.get(), rgba.get() + static_cast<std::size_t>(width) * height * 4);
    return true;
}
#endif

bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string* warn,
                 int width, int height, const unsigned char* bytes, int size, void* user) {
    // KHR_texture_basisu's KTX2 images have no decoder (none in Debian), nor
    // have WebP images without libwebp: left without pixels, so a texture
    // needing one is an error only where a material uses it (textureImage).
    if (isKtx2(bytes, size) || (isWebp(bytes, size) && !STRATA_WEBP)) return true;
    auto* context = static_cast<ImageContext*>(user);
    std::string label = "image " + std::to_string(index);
    if (!image->uri.empty()) {
        label += " (" + gltf::quoted(image->uri) + ")";
    } else if (!image->name.empty()) {
        label += " (" + gltf::quoted(image->name) + ")";
    }
    // The size its header claims, checked before the decoder allocates it.
    int claimedWidth = 0, claimedHeight = 0, channels = 0;
    bool known = false;
    // A PNG's IHDR is read here: stb_image's reader refuses a size over
    // 2^30 bytes with a message of its own, which would hide the limit.
    const auto bigEndian = [&](int at) {
        return std::uint32_t(bytes[at]) << 24 | std::uint32_t(bytes[at + 1]) << 16 | std::uint32_t(bytes[at + 2]) << 8 |
               std::uint32_t(bytes[at + 3]);
    };
    std::uint64_t w = 0, h = 0;
#if STRATA_AVIF
    const avif::Api* avifApi = nullptr;
    std::string avifError;
#endif
    if (size >= 24 && isPng(bytes, size) && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
        w = bigEndian(16);
        h = bigEndian(20);
        known = true;
    }
#if STRATA_WEBP
    else if (isWebp(bytes, size)) known = WebPGetInfo(bytes, std::size_t(size), &claimedWidth, &claimedHeight) != 0;
#endif
#if STRATA_AVIF
    else if (isAvif(bytes, size)) {
        std::uint32_t aw = 0, ah = 0;
        avifApi = avif::module(avifError);
        if ((known = avifApi && avifApi->size(bytes, std::size_t(size), &aw, &ah))) w = aw, h = ah;
    }
#endif
    else if (isJpeg(bytes, size)) known = stbi_info_from_memory(bytes, size, &claimedWidth, &claimedHeight, &channels) != 0;
    if (known && w == 0 && h == 0) {
        w = std::uint64_t(std::max(claimedWidth, 0));
        h = std::uint64_t(std::max(claimedHeight, 0));
    }
    if (known) {
        std::string tooLarge = limits::imageSizeProblem(w, h);
        // RGBA of up to 16 bits a channel: 8 bytes a pixel at most.
        context->decoded += w * h * 8;
        if (tooLarge.empty() && context->budget != 0 && context->decoded > context->budget)
            tooLarge = "the images decoded up to this one need up to " + bytesText(context->decoded) +
                       " of host memory; " + bytesText(context->budget) + " are available (refused before decoding)";
        if (!tooLarge.empty()) {
            context->failure = label + ": " + tooLarge;
            if (err) *err += context->failure + "\n";
            return false;
        }
    }
    bool decoded = false;
    const char* what = "a corrupt or too large PNG/JPEG image (stb_image)";
#if STRATA_WEBP
    if (isWebp(bytes, size)) {
        decoded = decodeWebp(image, bytes, size);
        what = "a corrupt WebP image (libwebp)";
    } else
#endif
#if STRATA_AVIF
    if (isAvif(bytes, size)) {
        decoded = known && decodeAvif(image, *avifApi, bytes, size);
        what = avifApi ? "a corrupt AVIF image (libavif)" : avifError.c_str();
    } else
#endif
    if (isPng(bytes, size) || isJpeg(bytes, size)) {
        std::string ignored;
        decoded = tinygltf::LoadImageData(image, index, &ignored, warn, width, height, bytes, size, nullptr);
    } else {
        what = "not a PNG or JPEG (the image formats of glTF 2.0), nor a WebP or AVIF image";
    }
    if (decoded) return true;
    // glTF 2.0 lets a texture fall back from an image strata cannot read
    // (EXT_texture_avif's, say) and lets an image go unused: left without
    // pixels, an error only where a material reads it (textureImage).
    context->undecodable.push_back(label + ": cannot decode " + std::to_string(size) + " bytes: " + what);
    image->image.clear();
    tinygltf::Value::Object why;
    why[kUndecodable] = tinygltf::Value(context->undecodable.back());
    image->extras = tinygltf::Value(why);  // the message for textureImage
    return true;
}

// Little-endian u32 at `offset`.
std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t offset) {
    return static_cast<std::uint32_t>(bytes[offset]) |
           static_cast<std::uint32_t>(bytes[offset + 1]) << 8 |
           static_cast<std::uint32_t>(bytes[offset + 2]) << 16 |
           static_cast<std::uint32_t>(bytes[offset + 3]) << 24;
}

// GLB header: magic, version 2, total length <= file size.
void checkGlbHeader(const std::string& path, const std::vector<unsigned char>& bytes) {
    if (bytes.size() < 12)
        fail(path, "truncated GLB: " + std::to_string(bytes.size()) +
                       " bytes is shorter than the 12-byte header");
    const std::uint32_t version = readU32(bytes, 4);
    if (version != 2)
        fail(path, "GLB version " + std::to_string(version) + " is not supported; only 2");
    const std::uint32_t length = readU32(bytes, 8);
    if (length > bytes.size()) {
        fail(path, "truncated GLB: the header says " + std::to_string(length) +
                       " bytes but the file has " + std::to_string(bytes.size()));
    }
}

// Fails when JSON objects and arrays nest deeper than limits::kJsonDepth
// in [begin, end) (brackets inside strings do not count), before a parser
// that recurses over the nesting sees them.
void checkJsonDepth(const std::string& path, const unsigned char* begin, const unsigned char* end) {
    int depth = 0;
    bool inString = false;
    for (const unsigned char* p = begin; p < end; ++p) {
        const unsigned char c = *p;
        if (inString) {
            if (c == '\\') ++p;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > limits::kJsonDepth)
                fail(path, "invalid glTF: JSON nested deeper than " + std::to_string(limits::kJsonDepth) +
                               " objects and arrays (at byte " + std::to_string(p - begin) + " of the JSON)");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

bool isSupported(const std::string& extension) {
    return std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), extension) !=
           std::end(kSupportedExtensions);
}

// glTF 2.0 (5.25, node.matrix) asks for an affine matrix; one whose last row
// is not (0, 0, 0, 1) is applied without that row, with one warning for
// the file.
void warnProjectiveMatrices(const std::string& path, const tinygltf::Model& model) {
    std::size_t count = 0;
    std::string first;
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        const std::vector<double>& m = model.nodes[n].matrix;
        if (m.size() != 16 || (m[3] == 0.0 && m[7] == 0.0 && m[11] == 0.0 && m[15] == 1.0)) continue;
        if (count++ == 0) first = nodeName(model, static_cast<int>(n));
    }
    if (count > 0)
        warn(path, std::to_string(count) + " node matrix(es) with a last row other than (0, 0, 0, 1), applied as "
                   "affine (the row ignored; first: " + first + ")");
}

}  // namespace

tinygltf::Model parseModel(const std::string& path, const std::vector<unsigned char>& bytes,
                           const std::string& restrictPaths, std::uint64_t hostMemory) {
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
        fail(path, "file is larger than 4 GiB");
    }
    const bool binary = hasGlbMagic(bytes);
    if (binary) {
        checkGlbHeader(path, bytes);
    } else if (hasGlbExtension(path)) {
        fail(path, "not a binary glTF file: it does not start with the 'glTF' magic");
    } else if (bytes.empty()) {
        fail(path, "empty file");
    } else {
        // JSON glTF is a UTF-8 object: '{' after any whitespace (and a byte
        // order mark, which the spec forbids but some writers emit).
        std::size_t i = bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF ? 3 : 0;
        while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\n' || bytes[i] == '\r')) ++i;
        if (i == bytes.size() || bytes[i] != '{')
            fail(path, "not a glTF file: neither a JSON object (it does not start with '{') nor binary glTF "
                       "(no 'glTF' magic)");
    }
    if (binary) {
        // The JSON chunk: its length at byte 12, its bytes from 20.
        if (bytes.size() >= 20) {
            const std::size_t length = std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20);
            checkJsonDepth(path, bytes.data() + 20, bytes.data() + 20 + length);
        }
    } else {
        checkJsonDepth(path, bytes.data(), bytes.data() + bytes.size());
    }
    std::string baseDir = std::filesystem::path(path).parent_path().string();
    if (baseDir.empty()) baseDir = ".";

    // JSON that tinygltf 2.7 refuses where glTF allows it (the compressed
    // extensions' indices and buffers, skins without inverseBindMatrices,
    // pointer animations, newer image data: URIs), rewritten
    // (gltf_compressed.cpp, prepareForTinygltf).
    const TinygltfFixups fixups = prepareForTinygltf(bytes, binary);
    const std::vector<unsigned char>& input = fixups.bytes.empty() ? bytes : fixups.bytes;

    FsContext fsContext;
    fsContext.prefix = baseDir.back() == '/' ? baseDir : baseDir + "/";
    fsContext.root = restrictPaths;
    tinygltf::TinyGLTF context;
    context.SetFsCallbacks(
        {&fileExists, &keepPath, &readWholeFile, &tinygltf::WriteWholeFile, &fsContext});
    ImageContext imageContext;
    imageContext.budget = hostMemory != 0 ? hostMemory : hostMemoryBudget();
    context.SetImageLoader(&decodeImage, &imageContext);
    tinygltf::Model model;
    std::string err;
    std::string warnings;
    bool ok = false;
    try {
        const auto size = static_cast<unsigned int>(input.size());
        if (binary) {
            ok = context.LoadBinaryFromMemory(&model, &err, &warnings, input.data(), size, baseDir);
        } else {
            ok = context.LoadASCIIFromString(&model, &err, &warnings,
                                             reinterpret_cast<const char*>(input.data()), size,
                                             baseDir);
        }
    } catch (const std::exception& e) {
        fail(path, std::string("invalid glTF: ") + gltf::oneLine(e.what()));
    }
    if (!fsContext.refused.empty()) fail(path, fsContext.refused);
    if (!fsContext.unreadable.empty()) fail(path, fsContext.unreadable);
    if (!imageContext.failure.empty()) fail(path, imageContext.failure);
    // tinygltf only warns about a missing image file; strata fails on it.
    if (!fsContext.missing.empty()) {
        const std::string& file = fsContext.missing.front();
        fail(path, "missing file: uri " + quoted(file.substr(fsContext.prefix.size())) + " refers to " + file +
                       ", which does not exist");
    }
    // Anything in err fails, also when tinygltf loads on: it reports some
    // malformed required properties there and drops them (a primitive's
    // 'attributes' that are not accessor indices, and its mesh with them),
    // which would otherwise surface as a misleading error later.
    const std::string why = gltf::oneLine(err);
    // A buffer without a uri in a .gltf: said plainly, with its index.
    if (!binary && why.find("'uri' is missing from non binary glTF file buffer") != std::string::npos) {
        const auto root = nlohmann::json::parse(input.begin(), input.end(), nullptr, false);
        if (root.is_object() && root.contains("buffers") && root["buffers"].is_array())
            for (std::size_t b = 0; b < root["buffers"].size(); ++b)
                if (root["buffers"][b].is_object() && !root["buffers"][b].contains("uri"))
                    fail(path, "buffer " + std::to_string(b) + " has no uri: only a .glb's binary chunk can be a "
                                   "buffer without one, so its data is nowhere");
    }
    if (!ok || !why.empty()) fail(path, "invalid glTF: " + (why.empty() ? std::string("parse failed") : why));
    const std::string notes = gltf::oneLine(warnings);
    if (!notes.empty()) warn(path, notes);
    if (!imageContext.undecodable.empty())
        warn(path, std::to_string(imageContext.undecodable.size()) + " image(s) not decoded, left unused (first: " +
                       imageContext.undecodable.front() + ")");
    restoreAfterTinygltf(fixups, model);
    for (const std::string& w : fixups.warnings) warn(path, w);
    warnProjectiveMatrices(path, model);
    return model;
}

void checkExtensions(const std::string& path, const tinygltf::Model& model) {
    std::string required;
    for (const auto& e : model.extensionsRequired) {
        if (!isSupported(e)) required += (required.empty() ? "" : ", ") + e;
    }
    if (!required.empty()) {
        fail(path, "unsupported required extension(s): " + gltf::oneLine(required) +
                       " (supported: " + supportedList() + ")");
    }
    for (const auto& e : model.extensionsRequired) {
        if (const char* decoder = missingDecoder(e)) {
            fail(path, "required extension " + e + " cannot be read: strata was built without " +
                           decoder);
        }
    }
    std::string used;
    for (const auto& e : model.extensionsUsed) {
        if (!isSupported(e)) used += (used.empty() ? "" : ", ") + e;
    }
    if (!used.empty()) warn(path, "unsupported extension(s) used, ignored: " + gltf::oneLine(used));
    for (const auto& e : model.extensionsUsed) {
        const bool required = std::find(model.extensionsRequired.begin(),
                                        model.extensionsRequired.end(), e) != model.extensionsRequired.end();
        // KHR_texture_basisu: warnTextureFallbacks, where a material reads one.
        if (const char* decoder = missingDecoder(e); decoder && !required && e != "KHR_texture_basisu") {
            warn(path, "extension " + e + " is used but strata was built without " + decoder + "; reading " +
                           (e == "EXT_texture_webp" || e == "EXT_texture_avif" ? "the textures' fallback images"
                                                                                : "the uncompressed fallback data"));
        }
    }
}

}  // namespace strata::gltf
