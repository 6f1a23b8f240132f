#include "render/sampler_kind.h"

#include <bit>
#include <cmath>

#include "../../shaders/shared/types.h"
#include "util/error.h"

namespace strata {

const std::vector<SamplerInfo>& samplers() {
    static const std::vector<SamplerInfo> list = {
        {"independent", gpu::kSamplerIndependent, false, false, true},
        {"regular", gpu::kSamplerRegular, true, false, false},
        {"rotated", gpu::kSamplerRotated, true, false, false},
        {"stratified", gpu::kSamplerStratified, true, false, false},
        {"sobol", gpu::kSamplerSobol, false, false, true},
        {"bluenoise", gpu::kSamplerBlueNoise, false, true, true},
    };
    return list;
}

const SamplerInfo& samplerByName(const std::string& name) {
    std::string names;
    for (const auto& s : samplers()) {
        if (name == s.name) return s;
        names += (names.empty() ? "" : ", ") + std::string(s.name);
    }
    throw Error("strata: error: unknown sampler '" + name + "' (samplers: " + names + ")");
}

const SamplerInfo& samplerByKind(std::uint32_t kind) {
    for (const auto& s : samplers())
        if (s.kind == kind) return s;
    throw Error("strata: error: unknown sampler kind " + std::to_string(kind));
}

void checkSamplerSettings(const SamplerInfo& s, std::uint32_t spp, int width, int height) {
    const auto n = static_cast<std::uint32_t>(std::floor(std::sqrt(static_cast<double>(spp))));
    if (s.needsSquareSpp && n * n != spp)
        throw Error("strata: error: --sampler " + std::string(s.name) + " needs a square spp (n x n grid), got " +
                    std::to_string(spp) + "; try " + std::to_string(n * n == 0 ? 1 : n * n) + " or " +
                    std::to_string((n + 1) * (n + 1)));
    if (s.needsPowerOfTwoSpp) {
        if (!std::has_single_bit(spp))
            throw Error("strata: error: --sampler bluenoise needs a power-of-two spp, got " + std::to_string(spp));
        // Morton code of the largest pixel plus log2(spp) must fit 32 bits.
        const int side = std::max(width, height);
        const int pixelBits = 2 * static_cast<int>(std::bit_width(static_cast<unsigned>(side - 1)));
        const int sppBits = std::countr_zero(spp);
        if (pixelBits + sppBits > 32)
            throw Error("strata: error: --sampler bluenoise supports at most 2^32 pixel samples in Z order; " +
                        std::to_string(width) + "x" + std::to_string(height) + " at " + std::to_string(spp) +
                        " spp needs " + std::to_string(pixelBits + sppBits) + " bits");
    }
}

}  // namespace strata
