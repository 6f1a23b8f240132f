// Textures packed for the shaders: every image a used material reads goes
// once into one R32UI word array (read through a texel buffer view), and
// every used texture slot becomes a gpu::TextureRef (types.h).
#pragma once
#include <cstdint>
#include <vector>

#include "../../shaders/shared/types.h"
#include "scene/scene.h"

namespace strata {

struct PackedTextures {
    std::vector<gpu::TextureRef> refs;
    std::vector<std::uint32_t> texels;  // the words of every packed image
};

// Fills the *Tex fields of `materials` (parallel to scene.materials) with
// indices into refs, for the materials marked in `used`; other slots stay
// gpu::kNoTexture. When a used material has a sheen (kFeatureSheen), the
// texels start with the sheen albedo table (sheenAlbedoWords).
PackedTextures packTextures(const Scene& scene, const std::vector<bool>& used,
                            std::vector<gpu::Material>& materials);

// KHR_materials_sheen's albedo table as texel words (tools/sheen-albedo).
std::vector<std::uint32_t> sheenAlbedoWords();

// The exact sRGB decoding curve (IEC 61966-2-1): c / 12.92 for c <= 0.04045,
// else ((c + 0.055) / 1.055)^2.4; c in [0, 1].
double srgbToLinear(double c);

// Mean linear RGB of an image (sRGB-decoded when `srgb`), for the power of
// emitters with an emissive texture.
glm::dvec3 meanColor(const TextureImage& image, bool srgb);

// The 2x3 matrix of a KHR_texture_transform (uv' = M (uv, 1)) as the rows
// of gpu::TextureRef.
void transformRows(const TextureTransform& t, glm::vec4& row0, glm::vec4& row1);

}  // namespace strata
