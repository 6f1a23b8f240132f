// An image as float pixels with named channels: what the OpenImageIO module
// (oiio/api.h) reads into. Plain data; includes nothing of strata's.
#pragma once
#include <string>
#include <vector>

namespace strata {

struct Image {
    int width = 0, height = 0;  // pixels
    int channels = 0;
    std::vector<std::string> channelNames;
    std::vector<float> pixels;  // row-major, interleaved channels, row 0 at the top
};

}  // namespace strata
