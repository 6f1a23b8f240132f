// Textures packed for the shaders: every image a used material reads goes
// once into one R32UI word array (read through a texel buffer view), and
// every used texture slot becomes a gpu::TextureRef (types.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "../../shaders/shared/types.h"
#include "pack/texture_levels.h"
#include "scene/scene.h"

namespace strata {

// One packed image: its name, its size as packed and as the file has it,
// its bytes on the device (--stats), and where its words start, their bits
// per channel and its coding (to halve it again: shrinkTextures).
struct PackedImage {
    std::string name;
    int width = 0, height = 0;
    int fileWidth = 0, fileHeight = 0;
    std::uint64_t bytes = 0;
    std::uint64_t offset = 0;  // into PackedTextures::texels, in words
    int bits = 8;
    TexelCoding coding = TexelCoding::Linear;
    int levels = 1;            // with its mip chain (kTexLevelsShift)
    AlphaUse alpha;            // how its levels treat alpha (packTextures)
    bool alphaSeen = false;    // a material's alpha has set `alpha`
    bool downsampled() const { return width != fileWidth || height != fileHeight; }
};

struct PackedTextures {
    std::vector<gpu::TextureRef> refs;
    std::vector<std::uint32_t> texels;  // the words of every packed image
    std::vector<PackedImage> images;    // in the order they were packed
    double mipMs = 0.0;                 // building the mip chains (wall time)
};

// Fills the *Tex fields of `materials` (parallel to scene.materials) with
// indices into refs, for the materials marked in `used`; other slots stay
// gpu::kNoTexture. When a used material has a sheen (kFeatureSheen), the
// texels start with the sheen albedo table (sheenAlbedoWords). Each image
// is packed once, at most `maxSize` texels a side (0: whole;
// downsampledTexture as its first slot reads it); with `mips` each image
// is followed by its mip chain (textureMips), built in parallel.
PackedTextures packTextures(const Scene& scene, const std::vector<bool>& used,
                            std::vector<gpu::Material>& materials, std::uint32_t maxSize = 0, bool mips = false);

// Halves the largest packed images, one halving at a time, until the texel
// words take at most `maxBytes` (or every image is 1x1), then lays the
// words out again and points the refs at them. Returns the indices into
// `images` of those halved (empty where they fitted).
std::vector<std::size_t> shrinkTextures(std::vector<std::uint32_t>& texels, std::vector<gpu::TextureRef>& refs,
                                        std::vector<PackedImage>& images, std::uint64_t maxBytes);

// KHR_materials_sheen's albedo table as texel words (tools/sheen-albedo).
std::vector<std::uint32_t> sheenAlbedoWords();

// The 2x3 matrix of a KHR_texture_transform (uv' = M (uv, 1)) as the rows
// of gpu::TextureRef.
void transformRows(const TextureTransform& t, glm::vec4& row0, glm::vec4& row1);
// The texels a uv unit of `r` spans at its first level, log2, in row0.w:
// half the log2 of its texel count times the transform's scale of uv area
// (|det| of its 2x2 part). Texture LOD adds it to the footprint
// (lib/material.glsl textureLevel); set after the image's size is final.
void setTexelDensity(gpu::TextureRef& r);

}  // namespace strata
