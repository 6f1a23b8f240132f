// Image files through OpenImageIO, loaded on first use (host/oiio/api.h).
// EXR: linear float RGB. PNG: sRGB-encoded 8-bit, clamped. Every file
// appears whole or not at all: written under a temporary name in the same
// directory, then renamed.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "oiio/image.h"

namespace strata {

namespace oiio {
struct Api;
}

enum class ImageFormat { Exr, Png };

// Format from the file extension (.exr, .png; case-insensitive). Throws
// strata::Error ("<path>: error: ...") for anything else.
ImageFormat outputFormat(const std::string& path);

// Writes all `paths` from one linear RGB image (3 floats per pixel). Either
// every file is written or none is (temporaries are removed on failure).
// EXR files get the `extra` channels after R, G, B (variance.R/G/B, the
// AOVs); PNG files ignore them.
void writeImages(const std::vector<std::string>& paths, int width, int height,
                 const std::vector<float>& rgb, const ExtraChannels& extra = {});

// A PNG of sRGB-encoded 8-bit RGB (3 bytes per pixel), as it is: whole or
// not at all.
void writePng8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

// An RGB image and, when the file has variance.R/G/B channels, the variance
// of each pixel's mean (as `strata reference` writes it).
struct RgbImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;       // 3 floats per pixel
    std::vector<float> variance;  // empty, or 3 floats per pixel
};

// Reads channels R, G, B (and variance.R/G/B when present) by name; a file
// without R, G and B is an error naming it.
RgbImage readRgb(const std::string& path);

// readRgb for an image that measurements are made against (converge, bench
// --reference): a NaN or Inf in R, G or B is an error naming the first such
// pixel, since every error figure would silently leave it out.
RgbImage readReference(const std::string& path);

// Reads any image OpenImageIO can read, as float. Throws strata::Error.
Image readImage(const std::string& path);

// Whether this build has the OpenImageIO module (cmake -DSTRATA_OIIO), and
// a one-line error naming `path` before any work when it has not (and
// $STRATA_OIIO_MODULE names none).
bool imageSupportBuilt();
void requireImageSupport(const std::string& path);

// The OpenImageIO module, loaded on the first call. Throws strata::Error
// naming `path` (the file that needed it) when it cannot be loaded.
const oiio::Api& imageModule(const std::string& path);

// IEC 61966-2-1 sRGB transfer function (linear -> encoded), input clamped to [0,1].
float linearToSrgb(float linear);
// A PNG's byte: linearToSrgb rounded to 8 bits.
std::uint8_t srgb8(float linear);

// srgb8 by a table of the 255 values where it steps (strata view's
// display, a frame at a time): the same byte, without a pow a channel.
class Srgb8Table {
public:
    Srgb8Table();
    std::uint8_t operator()(float linear) const;

private:
    std::array<float, 256> steps_;  // steps_[k]: the least x with srgb8(x) >= k
};

}  // namespace strata
