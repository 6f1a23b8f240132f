// The AVIF decoder's whole interface. libavif (and the AV1 codecs it links)
// lives in a module, libstrata_avif.so (decode.cpp), loaded on the first
// AVIF image (module.h), so that a scene without one loads none of it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::avif {

inline constexpr int kApiVersion = 1;

// A decoded frame: RGBA rows top to bottom, 8 bits a channel, or 16 (uint16
// in host byte order, two bytes each) for an image deeper than 8 bits.
struct Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int bits = 8;
    std::vector<unsigned char> rgba;
};

struct Api {
    int version;  // kApiVersion
    // The size the file's header claims, read without decoding; false when
    // the header cannot be parsed.
    bool (*size)(const unsigned char* bytes, std::size_t count, std::uint32_t* width, std::uint32_t* height);
    // The first frame; false when it cannot be decoded.
    bool (*decode)(const unsigned char* bytes, std::size_t count, Image* out);
};

}  // namespace strata::avif

// The module's one exported symbol: its Api (util/module.h says why as const void*).
extern "C" const void* strata_avif_api();
