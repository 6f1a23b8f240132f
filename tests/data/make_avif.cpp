// Writes the EXT_texture_avif files of tests/test_texture_formats.cpp into
// DIR with libavif's encoder (tests/CMakeLists.txt runs it at build time):
//   make_avif DIR
// checker.avif: format_files.h's 4 x 4 RGBA checker, lossless (4:4:4, the
// identity matrix, quantizer 0: it decodes to its pixels exactly); avif.gltf,
// avif-required.gltf, avif-corrupt.gltf (corrupt.avif): format_files.h's
// writeSet.
#include <cstdio>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <avif/avif.h>

#include "format_files.h"

namespace {

std::vector<std::uint8_t> encodeLossless(std::vector<std::uint8_t> pixels, int size) {
    std::unique_ptr<avifImage, void (*)(avifImage*)> image(
        avifImageCreate(std::uint32_t(size), std::uint32_t(size), 8, AVIF_PIXEL_FORMAT_YUV444), &avifImageDestroy);
    if (!image) throw std::runtime_error("libavif: no image");
    image->matrixCoefficients = AVIF_MATRIX_COEFFICIENTS_IDENTITY;
    image->yuvRange = AVIF_RANGE_FULL;
    avifRGBImage rgb;
    avifRGBImageSetDefaults(&rgb, image.get());
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.depth = 8;
    rgb.pixels = pixels.data();
    rgb.rowBytes = std::uint32_t(size) * 4;
    if (avifImageRGBToYUV(image.get(), &rgb) != AVIF_RESULT_OK) throw std::runtime_error("libavif: RGB to YUV failed");
    std::unique_ptr<avifEncoder, void (*)(avifEncoder*)> encoder(avifEncoderCreate(), &avifEncoderDestroy);
    if (!encoder) throw std::runtime_error("libavif: no encoder");
    encoder->minQuantizer = encoder->maxQuantizer = AVIF_QUANTIZER_LOSSLESS;
    encoder->minQuantizerAlpha = encoder->maxQuantizerAlpha = AVIF_QUANTIZER_LOSSLESS;
    encoder->maxThreads = 1;
    avifRWData out = AVIF_DATA_EMPTY;
    const avifResult r = avifEncoderWrite(encoder.get(), image.get(), &out);
    if (r != AVIF_RESULT_OK) throw std::runtime_error(std::string("libavif: ") + avifResultToString(r));
    std::vector<std::uint8_t> bytes(out.data, out.data + out.size);
    avifRWDataFree(&out);
    return bytes;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_avif DIR\n");
        return 2;
    }
    try {
        const format_files::fs::path dir = argv[1];
        format_files::fs::create_directories(dir);
        const std::vector<std::uint8_t> encoded = encodeLossless(format_files::checker(), format_files::kSize);
        format_files::writeSet(dir, "avif", "avif", "EXT_texture_avif", encoded, "strata tests/data/make_avif.cpp");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_avif: %s\n", e.what());
        return 1;
    }
    return 0;
}
