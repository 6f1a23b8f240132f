// libstrata_avif.so: EXT_texture_avif's images through libavif (one
// thread), behind api.h.
#include <cstring>
#include <memory>

#include <avif/avif.h>

#include "avif/api.h"

namespace {

using Decoder = std::unique_ptr<avifDecoder, void (*)(avifDecoder*)>;

// A decoder that has parsed `bytes` (their header), or null.
Decoder parsed(const unsigned char* bytes, std::size_t count) {
    Decoder d(avifDecoderCreate(), &avifDecoderDestroy);
    if (!d || avifDecoderSetIOMemory(d.get(), bytes, count) != AVIF_RESULT_OK || avifDecoderParse(d.get()) != AVIF_RESULT_OK ||
        d->image->width == 0 || d->image->height == 0)
        return Decoder(nullptr, &avifDecoderDestroy);
    return d;
}

bool size(const unsigned char* bytes, std::size_t count, std::uint32_t* width, std::uint32_t* height) {
    const Decoder d = parsed(bytes, count);
    if (!d) return false;
    *width = d->image->width;
    *height = d->image->height;
    return true;
}

bool decode(const unsigned char* bytes, std::size_t count, strata::avif::Image* out) {
    const Decoder d = parsed(bytes, count);
    if (!d || avifDecoderNextImage(d.get()) != AVIF_RESULT_OK) return false;
    avifRGBImage rgb;
    avifRGBImageSetDefaults(&rgb, d->image);
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.depth = d->image->depth > 8 ? 16 : 8;
    avifRGBImageAllocatePixels(&rgb);
    const bool ok = rgb.pixels && avifImageYUVToRGB(d->image, &rgb) == AVIF_RESULT_OK;
    if (ok) {
        const std::size_t row = std::size_t(rgb.width) * 4 * (rgb.depth / 8);
        out->rgba.resize(row * rgb.height);
        for (std::uint32_t y = 0; y < rgb.height; ++y)
            std::memcpy(out->rgba.data() + y * row, rgb.pixels + std::size_t(y) * rgb.rowBytes, row);
        out->width = rgb.width;
        out->height = rgb.height;
        out->bits = static_cast<int>(rgb.depth);
    }
    avifRGBImageFreePixels(&rgb);
    return ok;
}

const strata::avif::Api kApi{strata::avif::kApiVersion, &size, &decode};

}  // namespace

extern "C" __attribute__((visibility("default"))) const void* strata_avif_api() { return &kApi; }
