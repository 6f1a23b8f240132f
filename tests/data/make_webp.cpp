// Writes the EXT_texture_webp files of tests/test_texture_formats.cpp into
// DIR with libwebp's own encoder (tests/CMakeLists.txt runs it at build
// time):
//   make_webp DIR
// checker.webp: format_files.h's 4 x 4 RGBA checker, lossless; webp.gltf,
// webp-required.gltf, webp-corrupt.gltf (corrupt.webp): format_files.h's
// writeSet.
#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <webp/encode.h>

#include "format_files.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_webp DIR\n");
        return 2;
    }
    try {
        const format_files::fs::path dir = argv[1];
        format_files::fs::create_directories(dir);
        const std::vector<std::uint8_t> pixels = format_files::checker();
        constexpr int kSize = format_files::kSize;
        std::uint8_t* webp = nullptr;
        const std::size_t size = WebPEncodeLosslessRGBA(pixels.data(), kSize, kSize, kSize * 4, &webp);
        if (size == 0) throw std::runtime_error("libwebp: encoding failed");
        const std::vector<std::uint8_t> encoded(webp, webp + size);
        WebPFree(webp);
        format_files::writeSet(dir, "webp", "webp", "EXT_texture_webp", encoded, "strata tests/data/make_webp.cpp");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_webp: %s\n", e.what());
        return 1;
    }
    return 0;
}
