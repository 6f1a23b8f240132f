// The OpenImageIO side of strata, built as a module (libstrata_oiio.so) that
// image/image_io.cpp loads on the first image read or written, so that
// commands touching no image do not run the static initialisers of the
// libraries Debian's OpenImageIO pulls in
// (docs/experiments/scale-and-startup.md). The interface is plain data
// (oiio/image.h, oiio/chart.h) and function pointers: the module and
// strata share no other header.
//
// Functions return "" on success, else the error (one line, no file name).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "oiio/chart.h"
#include "oiio/image.h"

namespace strata::oiio {

inline constexpr int kApiVersion = 3;

struct Api {
    int version = kApiVersion;
    // Linear float RGB and the `extra` channels after them, zip-compressed,
    // with extra's attributes in the header, written to `tmp` in the format
    // `path` names (EXR).
    std::string (*writeExr)(const std::string& path, const std::string& tmp, int width, int height,
                            const float* rgb, const ExtraChannels& extra);
    // sRGB-encoded 8-bit RGB written to `tmp` in the format `path` names (PNG).
    std::string (*writePng)(const std::string& path, const std::string& tmp, int width, int height,
                            const std::uint8_t* rgb);
    // Any image OpenImageIO reads, as float, with its channel names and its
    // header's integer attributes named "strata:...".
    std::string (*read)(const std::string& path, Image& out);
    // Draws the panels side by side (panelWidth x height each) as display
    // RGB floats, row 0 at the top.
    std::string (*chart)(const std::vector<Panel>& panels, int panelWidth, int height, std::vector<float>& rgb);
};

}  // namespace strata::oiio

// The module's one exported symbol: its Api (util/module.h says why as const void*).
extern "C" const void* strata_oiio_api();
