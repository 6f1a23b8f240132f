#include "pack/textures.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "sheen_albedo.h"

namespace strata {

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

namespace {

// Channel c (0-3) of texel i as a value in [0, 1].
double channel(const TextureImage& image, std::size_t i, int c) {
    if (image.bits == 16) {
        std::uint16_t v;
        std::memcpy(&v, image.data.data() + (i * 4 + static_cast<std::size_t>(c)) * 2, 2);
        return v / 65535.0;
    }
    return image.data[i * 4 + static_cast<std::size_t>(c)] / 255.0;
}

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

}  // namespace

glm::dvec3 meanColor(const TextureImage& image, bool srgb) {
    const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
    // The 256 decoded 8-bit values, looked up: the same doubles as
    // srgbToLinear(v / 255.0), without a pow per texel.
    static const std::array<double, 256> decoded8 = [] {
        std::array<double, 256> t{};
        for (int k = 0; k < 256; ++k) t[std::size_t(k)] = srgbToLinear(k / 255.0);
        return t;
    }();
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < count; ++i) {
        for (int c = 0; c < 3; ++c) {
            if (srgb && image.bits != 16) {
                sum[c] += decoded8[image.data[i * 4 + static_cast<std::size_t>(c)]];
                continue;
            }
            const double v = channel(image, i, c);
            sum[c] += srgb ? srgbToLinear(v) : v;
        }
    }
    return count ? sum / static_cast<double>(count) : sum;
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

PackedTextures packTextures(const Scene& scene, const std::vector<bool>& used,
                            std::vector<gpu::Material>& materials) {
    PackedTextures out;
    // KHR_materials_sheen's albedo table first (lib/sheen.glsl reads it there).
    bool sheen = false;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) sheen = sheen || (used[i] && scene.materials[i].sheened());
    if (sheen) out.texels = sheenAlbedoWords();
    std::vector<std::int64_t> imageOffset(scene.images.size(), -1);
    auto addRef = [&](const MaterialDesc& m, const TextureSlot& slot, bool srgb) -> std::uint32_t {
        if (!slot.used()) return gpu::kNoTexture;
        const Texture& texture = scene.textures[static_cast<std::size_t>(slot.texture)];
        const TextureImage& image = scene.images[static_cast<std::size_t>(texture.image)];
        std::int64_t& offset = imageOffset[static_cast<std::size_t>(texture.image)];
        if (offset < 0) {
            offset = static_cast<std::int64_t>(out.texels.size());
            appendWords(image, out.texels);
        }
        gpu::TextureRef ref{};
        ref.offset = static_cast<std::uint32_t>(offset);
        ref.width = static_cast<std::uint32_t>(image.width);
        ref.height = static_cast<std::uint32_t>(image.height);
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
        g.baseColorTex = addRef(m, m.baseColorTexture, true);
        g.metallicRoughnessTex = addRef(m, m.metallicRoughnessTexture, false);
        g.normalTex = addRef(m, m.normalTexture, false);
        g.emissiveTex = addRef(m, m.emissiveTexture, true);
        g.transmissionTex = addRef(m, m.transmissionTexture, false);
        g.clearcoatTex = g.clearcoatRoughnessTex = g.clearcoatNormalTex = gpu::kNoTexture;
        if (m.coated()) {
            g.clearcoatTex = addRef(m, m.clearcoatTexture, false);
            g.clearcoatRoughnessTex = addRef(m, m.clearcoatRoughnessTexture, false);
            g.clearcoatNormalTex = addRef(m, m.clearcoatNormalTexture, false);
        }
        g.specularTex = g.specularColorTex = gpu::kNoTexture;
        if (m.tinted()) {
            g.specularTex = addRef(m, m.specularTexture, false);
            g.specularColorTex = addRef(m, m.specularColorTexture, true);
        }
        g.sheenColorTex = g.sheenRoughnessTex = gpu::kNoTexture;
        if (m.sheened()) {
            g.sheenColorTex = addRef(m, m.sheenColorTexture, true);
            g.sheenRoughnessTex = addRef(m, m.sheenRoughnessTexture, false);
        }
        g.iridescenceTex = g.iridescenceThicknessTex = gpu::kNoTexture;
        if (m.iridescent()) {
            g.iridescenceTex = addRef(m, m.iridescenceTexture, false);
            g.iridescenceThicknessTex = addRef(m, m.iridescenceThicknessTexture, false);
        }
    }
    return out;
}

}  // namespace strata
