// Sampler names of --sampler and the checks each sampler puts on the spp.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

struct SamplerInfo {
    const char* name;
    std::uint32_t kind;        // gpu::kSampler*
    bool needsSquareSpp;       // regular, rotated, stratified: an n x n grid
    bool needsPowerOfTwoSpp;   // bluenoise
    bool prefixesAreSamplings; // the first k samples of an N-sample render are
                               // a valid k-sample render (independent, Sobol)
};

const std::vector<SamplerInfo>& samplers();
// Throws strata::Error ("strata: error: ...") for an unknown name.
const SamplerInfo& samplerByName(const std::string& name);
const SamplerInfo& samplerByKind(std::uint32_t kind);
// Throws strata::Error when spp or the image size does not suit the sampler.
void checkSamplerSettings(const SamplerInfo& s, std::uint32_t spp, int width, int height);

}  // namespace strata
