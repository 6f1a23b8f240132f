// The sizes strata accepts from an input file, checked before anything of
// that size is allocated, so a hostile file is a one-line error instead of
// an exhausted machine (docs/security.md lists every limit).
#pragma once
#include <cstdint>
#include <string>

namespace strata::limits {

// An image (a glTF texture, an environment map, a reference): at most this
// many pixels on a side (Vulkan's usual maxImageDimension2D) and in all.
constexpr std::uint64_t kImageSide = 16384;
constexpr std::uint64_t kImagePixels = std::uint64_t(1) << 27;  // 16384 x 8192
// Values (pixels times channels) of an image read as floats: 2 GiB.
constexpr std::uint64_t kImageFloats = std::uint64_t(1) << 29;

// JSON objects and arrays nested deeper than this are refused before any
// parser (tinygltf's converts extras recursively) sees them.
constexpr int kJsonDepth = 128;

// "" when a width x height image is within the limits, else why not.
inline std::string imageSizeProblem(std::uint64_t width, std::uint64_t height) {
    if (width <= kImageSide && height <= kImageSide && width * height <= kImagePixels) return "";
    return std::to_string(width) + "x" + std::to_string(height) + " pixels is over the limit of " +
           std::to_string(kImageSide) + " on a side and " + std::to_string(kImagePixels) +
           " in all (refused before decoding)";
}

}  // namespace strata::limits
