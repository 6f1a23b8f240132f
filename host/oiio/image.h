// An image as float pixels with named channels: what the OpenImageIO module
// (oiio/api.h) reads into. Plain data; includes nothing of strata's.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace strata {

struct Image {
    int width = 0, height = 0;  // pixels
    int channels = 0;
    std::vector<std::string> channelNames;
    std::vector<float> pixels;  // row-major, interleaved channels, row 0 at the top
    // The header's integer attributes named "strata:..." (ExrAttributes).
    std::vector<std::pair<std::string, int>> attributes;

    // The index of the channel named `name`, or -1.
    int channel(const std::string& name) const {
        for (int c = 0; c < channels; ++c)
            if (channelNames[c] == name) return c;
        return -1;
    }
};

// Channels an EXR gets after R, G, B (variance.R, albedo.R, ...): their
// names, and their values one channel after another (channel c of pixel i
// at c * pixels + i).
struct ExtraChannels {
    std::vector<std::string> names;
    std::vector<float> planes;
    // Integer attributes of the EXR header, named "strata:..." (the samples
    // per pixel a render reached and asked for).
    std::vector<std::pair<std::string, int>> attributes;

    // Appends channels `layer`.`suffix[k]` from an image with suffix.size()
    // interleaved channels per pixel.
    void add(const std::string& layer, const std::string& suffix, const std::vector<float>& interleaved) {
        const std::size_t n = suffix.size(), pixels = interleaved.size() / n;
        for (std::size_t k = 0; k < n; ++k) {
            names.push_back(layer + "." + suffix[k]);
            for (std::size_t i = 0; i < pixels; ++i) planes.push_back(interleaved[i * n + k]);
        }
    }
};

}  // namespace strata
