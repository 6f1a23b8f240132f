#include "pack/textures.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>

#include "sheen_albedo.h"

namespace strata {
namespace {

// Appends the image's words (layout in types.h, TextureRef) to `texels`.
void appendWords(const TextureImage& image, std::vector<std::uint32_t>& texels) {
    const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
    if (image.bits == 16) {
        const std::size_t first = texels.size();
        texels.resize(first + 2 * count);
        for (std::size_t i = 0; i < count; ++i) {
            std::uint16_t c[4];
            std::memcpy(c, image.data.data() + i * 8, sizeof c);
            texels[first + 2 * i] = c[0] | static_cast<std::uint32_t>(c[1]) << 16;
            texels[first + 2 * i + 1] = c[2] | static_cast<std::uint32_t>(c[3]) << 16;
        }
        return;
    }
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* c = image.data.data() + i * 4;
        texels.push_back(c[0] | static_cast<std::uint32_t>(c[1]) << 8 |
                         static_cast<std::uint32_t>(c[2]) << 16 |
                         static_cast<std::uint32_t>(c[3]) << 24);
    }
}

std::uint32_t wrapBits(Wrap w) {
    switch (w) {
        case Wrap::ClampToEdge: return gpu::kWrapClamp;
        case Wrap::MirroredRepeat: return gpu::kWrapMirror;
        case Wrap::Repeat: break;
    }
    return gpu::kWrapRepeat;
}

// Bytes of an image of w x h texels (`bits` per channel) and, with `mips`, its chain.
std::uint64_t packedBytes(std::uint64_t w, std::uint64_t h, int bits, bool mips) {
    const std::uint64_t texel = bits == 16 ? 8 : 4;
    std::uint64_t bytes = w * h * texel;
    while (mips && (w > 1 || h > 1)) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        bytes += w * h * texel;
    }
    return bytes;
}

}  // namespace

std::vector<std::size_t> shrinkTextures(std::vector<std::uint32_t>& texels, std::vector<gpu::TextureRef>& refs,
                                        std::vector<PackedImage>& images, std::uint64_t maxBytes) {
    std::vector<std::size_t> halvedImages;
    if (images.empty() || texels.size() * sizeof(std::uint32_t) <= maxBytes) return halvedImages;
    // Each image's first level as an image (the words are the texels' bytes, little-endian).
    std::vector<TextureImage> unpacked(images.size());
    std::uint64_t first = texels.size();
    for (std::size_t i = 0; i < images.size(); ++i) {
        const PackedImage& p = images[i];
        TextureImage& im = unpacked[i];
        im.width = p.width;
        im.height = p.height;
        im.bits = p.bits;
        im.data.resize(packedBytes(std::uint64_t(p.width), std::uint64_t(p.height), p.bits, false));
        std::memcpy(im.data.data(), texels.data() + p.offset, im.data.size());
        first = std::min(first, p.offset);
    }
    std::uint64_t bytes = texels.size() * sizeof(std::uint32_t);
    std::vector<char> halvedOnce(images.size(), 0);
    while (bytes > maxBytes) {
        std::size_t largest = images.size();
        for (std::size_t i = 0; i < images.size(); ++i)
            if (unpacked[i].width * unpacked[i].height > 1 &&
                (largest == images.size() || unpacked[i].data.size() > unpacked[largest].data.size()))
                largest = i;
        if (largest == images.size()) break;  // every image 1x1
        TextureImage& im = unpacked[largest];
        const bool mips = images[largest].levels > 1;
        const std::uint64_t before = packedBytes(std::uint64_t(im.width), std::uint64_t(im.height), im.bits, mips);
        im = downsampledTexture(im, std::uint32_t(std::max(im.width, im.height) + 1) / 2, images[largest].coding,
                                images[largest].alpha);  // one halving
        bytes -= before - packedBytes(std::uint64_t(im.width), std::uint64_t(im.height), im.bits, mips);
        if (!halvedOnce[largest]) halvedOnce[largest] = 1, halvedImages.push_back(largest);
    }
    // The words again: what precedes the images (the sheen table), then each
    // image with its chain built again where it had one.
    std::vector<std::uint32_t> out(texels.begin(), texels.begin() + std::ptrdiff_t(first));
    std::vector<std::uint64_t> oldOffset(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        PackedImage& p = images[i];
        oldOffset[i] = p.offset;
        p.offset = out.size();
        p.width = unpacked[i].width;
        p.height = unpacked[i].height;
        appendWords(unpacked[i], out);
        if (p.levels > 1) {
            const std::vector<TextureImage> chain = textureMips(unpacked[i], p.coding, p.alpha);
            for (const TextureImage& level : chain) appendWords(level, out);
            p.levels = 1 + static_cast<int>(chain.size());
        }
        p.bytes = (out.size() - p.offset) * sizeof(std::uint32_t);
    }
    const std::uint32_t levelBits = ~std::uint32_t(0) << gpu::kTexLevelsShift;
    for (gpu::TextureRef& r : refs)
        for (std::size_t i = 0; i < images.size(); ++i)
            if (r.offset == oldOffset[i]) {
                r.offset = static_cast<std::uint32_t>(images[i].offset);
                r.width = static_cast<std::uint32_t>(images[i].width);
                r.height = static_cast<std::uint32_t>(images[i].height);
                r.flags &= ~levelBits;
                if (images[i].levels > 1) r.flags |= static_cast<std::uint32_t>(images[i].levels) << gpu::kTexLevelsShift;
                setTexelDensity(r);
                break;
            }
    texels = std::move(out);
    return halvedImages;
}

void setTexelDensity(gpu::TextureRef& r) {
    const double det = std::abs(double(r.row0.x) * double(r.row1.y) - double(r.row0.y) * double(r.row1.x));
    r.row0.w = static_cast<float>(0.5 * std::log2(double(r.width) * double(r.height) * det));
}

void transformRows(const TextureTransform& t, glm::vec4& row0, glm::vec4& row1) {
    // KHR_texture_transform: M = T(offset) R(rotation) S(scale), R with
    // columns (cos, -sin), (sin, cos) as the ratified extension writes it.
    const double c = std::cos(static_cast<double>(t.rotation));
    const double s = std::sin(static_cast<double>(t.rotation));
    row0 = glm::vec4(static_cast<float>(c * t.scale.x), static_cast<float>(s * t.scale.y), t.offset.x, 0.0f);
    row1 = glm::vec4(static_cast<float>(-s * t.scale.x), static_cast<float>(c * t.scale.y), t.offset.y, 0.0f);
}

std::vector<std::uint32_t> sheenAlbedoWords() {
    std::vector<std::uint32_t> words;
    for (const float e : kSheenAlbedo) words.push_back(std::bit_cast<std::uint32_t>(e));
    return words;
}

namespace {

// The words of one packed image: downsampled to `maxSize` (0: whole), then
// with its mip chain where `mips`.
std::vector<std::uint32_t> imageWords(const TextureImage& image, TexelCoding coding, std::uint32_t maxSize, bool mips,
                                      PackedImage& p) {
    std::vector<std::uint32_t> words;
    TextureImage small;
    const TextureImage* base = &image;
    if (maxSize > 0 && std::uint32_t(std::max(image.width, image.height)) > maxSize) {
        small = downsampledTexture(image, maxSize, coding, p.alpha);
        base = &small;
    }
    p.width = base->width;
    p.height = base->height;
    appendWords(*base, words);
    p.levels = 1;
    if (mips) {
        std::vector<TextureImage> chain = textureMips(*base, coding, p.alpha);
        for (const TextureImage& level : chain) appendWords(level, words);
        p.levels += static_cast<int>(chain.size());
    }
    return words;
}

// Runs job(i) for i in [0, n) on up to the machine's threads; the first
// exception a job throws (std::bad_alloc) is thrown again here.
template <class Job>
void parallelFor(std::size_t n, Job job) {
    const std::size_t threads = std::min<std::size_t>(n, std::max(1u, std::thread::hardware_concurrency()));
    if (threads <= 1) {
        for (std::size_t i = 0; i < n; ++i) job(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failed;
    std::mutex failedMutex;
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            try {
                for (std::size_t i = next++; i < n; i = next++) job(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(failedMutex);
                if (!failed) failed = std::current_exception();
                next = n;  // the others stop after their current job
            }
        });
    for (std::thread& t : pool) t.join();
    if (failed) std::rethrow_exception(failed);
}

}  // namespace

PackedTextures packTextures(const Scene& scene, const std::vector<bool>& used,
                            std::vector<gpu::Material>& materials, std::uint32_t maxSize, bool mips) {
    PackedTextures out;
    // KHR_materials_sheen's albedo table first (lib/sheen.glsl reads it there).
    bool sheen = false;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) sheen = sheen || (used[i] && scene.materials[i].sheened());
    if (sheen) out.texels = sheenAlbedoWords();
    // Each image once, in the order slots first read it, as that slot reads
    // it; the refs hold its index in out.images until the words are laid out.
    std::vector<std::int64_t> packedIndex(scene.images.size(), -1);  // into out.images
    std::vector<std::size_t> sourceImage;                           // out.images -> scene.images
    auto addRef = [&](const MaterialDesc& m, const TextureSlot& slot, TexelCoding coding) -> std::uint32_t {
        if (!slot.used()) return gpu::kNoTexture;
        const bool srgb = coding == TexelCoding::Srgb;
        const Texture& texture = scene.textures[static_cast<std::size_t>(slot.texture)];
        const TextureImage& image = scene.images[static_cast<std::size_t>(texture.image)];
        std::int64_t& index = packedIndex[static_cast<std::size_t>(texture.image)];
        if (index < 0) {
            index = static_cast<std::int64_t>(out.images.size());
            const std::string name = image.name.empty() ? "image " + std::to_string(texture.image) : image.name;
            out.images.push_back({name, image.width, image.height, image.width, image.height, 0, 0, image.bits, coding});
            sourceImage.push_back(static_cast<std::size_t>(texture.image));
        }
        gpu::TextureRef ref{};
        ref.offset = static_cast<std::uint32_t>(index);  // laid out below
        ref.flags = wrapBits(texture.wrapS) | wrapBits(texture.wrapT) << 2;
        if (texture.nearest) ref.flags |= gpu::kTexNearest;
        if (m.uvSlot(slot.texCoord) == 1) ref.flags |= gpu::kTexCoord1;
        if (image.bits == 16) ref.flags |= gpu::kTex16Bit;
        if (srgb) ref.flags |= gpu::kTexSrgb;
        transformRows(slot.transform, ref.row0, ref.row1);
        out.refs.push_back(ref);
        return static_cast<std::uint32_t>(out.refs.size() - 1);
    };
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const MaterialDesc& m = scene.materials[i];
        gpu::Material& g = materials[i];
        g.baseColorTex = addRef(m, m.baseColorTexture, TexelCoding::Srgb);
        g.metallicRoughnessTex = addRef(m, m.metallicRoughnessTexture, TexelCoding::Linear);
        g.normalTex = addRef(m, m.normalTexture, TexelCoding::Normal);
        g.emissiveTex = addRef(m, m.emissiveTexture, TexelCoding::Srgb);
        g.transmissionTex = addRef(m, m.transmissionTexture, TexelCoding::Linear);
        g.clearcoatTex = g.clearcoatRoughnessTex = g.clearcoatNormalTex = gpu::kNoTexture;
        if (m.coated()) {
            g.clearcoatTex = addRef(m, m.clearcoatTexture, TexelCoding::Linear);
            g.clearcoatRoughnessTex = addRef(m, m.clearcoatRoughnessTexture, TexelCoding::Linear);
            g.clearcoatNormalTex = addRef(m, m.clearcoatNormalTexture, TexelCoding::Normal);
        }
        g.specularTex = g.specularColorTex = gpu::kNoTexture;
        if (m.tinted()) {
            g.specularTex = addRef(m, m.specularTexture, TexelCoding::Linear);
            g.specularColorTex = addRef(m, m.specularColorTexture, TexelCoding::Srgb);
        }
        g.sheenColorTex = g.sheenRoughnessTex = gpu::kNoTexture;
        if (m.sheened()) {
            g.sheenColorTex = addRef(m, m.sheenColorTexture, TexelCoding::Srgb);
            g.sheenRoughnessTex = addRef(m, m.sheenRoughnessTexture, TexelCoding::Linear);
        }
        g.iridescenceTex = g.iridescenceThicknessTex = gpu::kNoTexture;
        if (m.iridescent()) {
            g.iridescenceTex = addRef(m, m.iridescenceTexture, TexelCoding::Linear);
            g.iridescenceThicknessTex = addRef(m, m.iridescenceThicknessTexture, TexelCoding::Linear);
        }
        g.diffuseTransmissionTex = g.diffuseTransmissionColorTex = gpu::kNoTexture;
        if (m.diffuselyTransmitting()) {
            g.diffuseTransmissionTex = addRef(m, m.diffuseTransmissionTexture, TexelCoding::Linear);
            g.diffuseTransmissionColorTex = addRef(m, m.diffuseTransmissionColorTexture, TexelCoding::Srgb);
        }
        g.anisotropyTex = m.anisotropic() ? addRef(m, m.anisotropyTexture, TexelCoding::Linear) : gpu::kNoTexture;
    }
    // How the used materials' alpha reads each image as base colour: one
    // MASK cutoff (with its factor) or BLEND; OPAQUE reads no alpha, and an
    // image read two other ways keeps plain means.
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const MaterialDesc& m = scene.materials[i];
        if (!used[i] || !m.baseColorTexture.used() || m.alphaMode == MaterialDesc::AlphaMode::Opaque) continue;
        const int image = scene.textures[static_cast<std::size_t>(m.baseColorTexture.texture)].image;
        PackedImage& p = out.images[static_cast<std::size_t>(packedIndex[static_cast<std::size_t>(image)])];
        AlphaUse use;
        use.mode = m.alphaMode == MaterialDesc::AlphaMode::Mask ? AlphaUse::Mode::Mask : AlphaUse::Mode::Blend;
        if (use.mode == AlphaUse::Mode::Mask) use.cutoff = m.alphaCutoff, use.factor = m.baseColor.a;
        if (!p.alphaSeen) p.alpha = use, p.alphaSeen = true;
        else if (p.alpha.mode != use.mode || p.alpha.cutoff != use.cutoff || p.alpha.factor != use.factor) p.alpha = {};
    }
    // The images' words, built in parallel, then laid out in order.
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::vector<std::uint32_t>> words(out.images.size());
    parallelFor(out.images.size(), [&](std::size_t i) {
        words[i] = imageWords(scene.images[sourceImage[i]], out.images[i].coding, maxSize, mips, out.images[i]);
    });
    std::size_t total = out.texels.size();
    for (const auto& w : words) total += w.size();
    out.texels.reserve(total);
    for (std::size_t i = 0; i < out.images.size(); ++i) {
        out.images[i].offset = out.texels.size();
        out.images[i].bytes = words[i].size() * sizeof(std::uint32_t);
        out.texels.insert(out.texels.end(), words[i].begin(), words[i].end());
        std::vector<std::uint32_t>().swap(words[i]);
    }
    for (gpu::TextureRef& r : out.refs) {
        const PackedImage& p = out.images[r.offset];
        r.offset = static_cast<std::uint32_t>(p.offset);
        r.width = static_cast<std::uint32_t>(p.width);
        r.height = static_cast<std::uint32_t>(p.height);
        if (p.levels > 1) r.flags |= static_cast<std::uint32_t>(p.levels) << gpu::kTexLevelsShift;
        setTexelDensity(r);
    }
    if (mips) out.mipMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace strata
