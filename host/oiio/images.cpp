// Image files through OpenImageIO (host/oiio/api.h).
#include <algorithm>
#include <exception>

#include <OpenImageIO/imageio.h>

#include "oiio/api.h"
#include "util/limits.h"

namespace strata::oiio {
namespace {

std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

std::string write(const std::string& path, const std::string& tmp, const OIIO::ImageSpec& spec,
                  OIIO::TypeDesc type, const void* pixels) {
    auto out = OIIO::ImageOutput::create(path);  // format chosen by the real name
    if (!out) return "cannot create an image writer: " + oneLine(OIIO::geterror());
    bool ok = out->open(tmp, spec) && out->write_image(type, pixels);
    std::string err = ok ? "" : out->geterror();
    if (!out->close() && ok) ok = false, err = out->geterror();
    return ok ? "" : "cannot write image: " + oneLine(err);
}

std::string writeExr(const std::string& path, const std::string& tmp, int w, int h, const float* rgb,
                     const ExtraChannels& extra) {
    const std::size_t pixels = static_cast<std::size_t>(w) * h, channels = 3 + extra.names.size();
    OIIO::ImageSpec spec(w, h, static_cast<int>(channels), OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B"};
    spec.channelnames.insert(spec.channelnames.end(), extra.names.begin(), extra.names.end());
    spec.attribute("compression", "zip");
    for (const auto& [name, value] : extra.attributes) spec.attribute(name, value);
    if (extra.names.empty()) return write(path, tmp, spec, OIIO::TypeDesc::FLOAT, rgb);
    std::vector<float> all(pixels * channels);
    for (std::size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) all[i * channels + c] = rgb[i * 3 + c];
        for (std::size_t c = 0; c < extra.names.size(); ++c) all[i * channels + 3 + c] = extra.planes[c * pixels + i];
    }
    return write(path, tmp, spec, OIIO::TypeDesc::FLOAT, all.data());
}

std::string writePng(const std::string& path, const std::string& tmp, int w, int h, const std::uint8_t* rgb) {
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    return write(path, tmp, spec, OIIO::TypeDesc::UINT8, rgb);
}

// "cannot read image: " and OpenImageIO's reason, or ours when it gives none
// (a truncated PFM reads as a failure with an empty message).
std::string readFailure(const std::string& why) {
    return "cannot read image: " + (why.empty() ? std::string("the file is truncated or corrupt") : why);
}

std::string read(const std::string& path, Image& img) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return readFailure(oneLine(OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.channelNames = spec.channelnames;
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        if (p.name().string().rfind("strata:", 0) == 0 && p.type() == OIIO::TypeDesc::INT)
            img.attributes.emplace_back(p.name().string(), p.get_int());
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) return "cannot read image: it has no pixels";
    if (const std::string tooLarge = limits::imageSizeProblem(std::uint64_t(spec.width), std::uint64_t(spec.height));
        !tooLarge.empty())
        return "image of " + tooLarge;
    const std::uint64_t floats = std::uint64_t(spec.width) * std::uint64_t(spec.height) * std::uint64_t(spec.nchannels);
    if (floats > limits::kImageFloats)
        return "cannot read image: " + std::to_string(spec.nchannels) + " channels of " + std::to_string(spec.width) +
               "x" + std::to_string(spec.height) + " pixels are over the limit of " + std::to_string(limits::kImageFloats) +
               " values (refused before decoding)";
    img.pixels.resize(static_cast<std::size_t>(img.width) * img.height * img.channels);
    if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
        return readFailure(oneLine(in->geterror()));
    in->close();
    return "";
}

}  // namespace

std::string drawChart(const std::vector<Panel>& panels, int panelWidth, int height, std::vector<float>& rgb);

}  // namespace strata::oiio

extern "C" const void* strata_oiio_api() {
    static const strata::oiio::Api api{strata::oiio::kApiVersion, strata::oiio::writeExr, strata::oiio::writePng,
                                       strata::oiio::read, strata::oiio::drawChart};
    return &api;
}
