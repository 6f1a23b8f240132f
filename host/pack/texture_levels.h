// Texture levels: an image halved in the coding its texture reads it (the
// levels of a mip chain, downsampling to a size), and the texel decoding
// they and the emitters' mean colour share (pack/texture_levels.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace strata {

// How a texture slot reads its image, for downsampling: colour in sRGB
// (base colour, emissive, sheen and specular colour), a normal map, or
// other linear data.
enum class TexelCoding { Srgb, Normal, Linear };

// How the used materials' alpha reads an image as their base colour, for
// downsampling and mip chains: MASK with alphaCutoff and baseColorFactor's
// alpha takes colour over the texels that pass the cutoff, and
// downsampling keeps the share of lookups that pass (the alpha test reads
// the first level); BLEND weights colour by alpha; None (no alpha read, or
// read two different ways) takes plain means.
struct AlphaUse {
    enum class Mode { None, Mask, Blend } mode = Mode::None;
    float cutoff = 0.5f;
    float factor = 1.0f;
};

// The mip levels after `image`: each the one before halved as `coding`
// reads it (halving's rule: ceil sides, the mean of up to 2x2), down to 1x1;
// colour as `alpha` says (AlphaUse), alpha the plain mean.
std::vector<TextureImage> textureMips(const TextureImage& image, TexelCoding coding, AlphaUse alpha = {});

// The image halved (each side to ceil(side / 2), a texel the mean of the up
// to 2x2 it covers) until neither side exceeds `maxSize` (>= 1): the mean
// taken in linear light for sRGB colour, and a normal map's mean vector
// renormalised; alpha is averaged as it is, except as `alpha` says
// (AlphaUse: MASK keeps the share of bilinear lookups that pass). Bits per
// channel kept.
TextureImage downsampledTexture(const TextureImage& image, std::uint32_t maxSize, TexelCoding coding,
                                AlphaUse alpha = {});

// The exact sRGB decoding curve (IEC 61966-2-1): c / 12.92 for c <= 0.04045,
// else ((c + 0.055) / 1.055)^2.4; c in [0, 1].
double srgbToLinear(double c);

// Mean linear RGB of an image (sRGB-decoded when `srgb`), for the power of
// emitters with an emissive texture.
glm::dvec3 meanColor(const TextureImage& image, bool srgb);

}  // namespace strata
