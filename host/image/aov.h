// The AOVs of a render (--aov): per-pixel images made from a Film's AOV
// sums, their EXR channels, and the same images read back from an EXR (what
// `strata denoise` takes). The layers and their meaning: docs/denoising.md.
#pragma once
#include <string>
#include <vector>

#include "image/film.h"
#include "oiio/image.h"

namespace strata {

// Row-major, row 0 at the top; 3 floats per pixel unless stated.
struct AovImages {
    int width = 0, height = 0;
    std::vector<float> color;      // the mean of all samples (R, G, B)
    std::vector<float> variance;   // variance of each pixel's mean (variance.R/G/B)
    std::vector<float> halfA;      // mean of the even-indexed samples (halfA.R/G/B)
    std::vector<float> halfB;      // mean of the odd-indexed samples (halfB.R/G/B)
    std::vector<float> albedo;     // albedo.R/G/B, in [0,1]
    std::vector<float> normal;     // normal.X/Y/Z: camera space, the mean of unit normals
    std::vector<float> depth;      // depth.Z (1 per pixel): 0 where the camera ray escaped
    std::vector<float> emitter;    // emitter.A (1 per pixel): the fraction of samples that saw
                                   // an emitter, an unlit surface or the background first
    // The variance of each feature's mean (for the denoiser's feature
    // prefilter); empty when a file has none.
    std::vector<float> albedoVariance;  // albedoVariance.R/G/B
    std::vector<float> normalVariance;  // normalVariance.X/Y/Z
    std::vector<float> depthVariance;   // depthVariance.Z
    // The EXR header's strata:... attributes (ExtraChannels::attributes).
    std::vector<std::pair<std::string, int>> attributes;
};

// The AOV images of a film rendered with AOVs (film.aov).
AovImages aovImages(const Film& film);

// variance and the AOV layers as EXR channels, in the order of AovImages.
ExtraChannels aovChannels(const AovImages& aov);

// The AOV images of an EXR that has R, G, B and the layers above (the colour
// from noisy.R/G/B when the file has them: a denoised render's). A missing
// layer (other than the feature variances) is an error naming the file and
// the layer; a NaN or Inf value is an error naming the pixel.
AovImages readAovImages(const std::string& path);

}  // namespace strata
