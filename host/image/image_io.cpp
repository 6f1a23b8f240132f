#include "image/image_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <system_error>

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "util/error.h"

namespace strata {
namespace fs = std::filesystem;

ImageFormat outputFormat(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".exr") return ImageFormat::Exr;
    if (ext == ".png") return ImageFormat::Png;
    fail(path, "unsupported output format '" + ext + "' (use .exr or .png)");
}

float linearToSrgb(float x) {
    if (!(x > 0.0f)) return 0.0f;  // also maps NaN to 0
    if (x >= 1.0f) return 1.0f;
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

namespace {

void writeOne(const std::string& path, const std::string& tmp, int w, int h,
              const std::vector<float>& rgb) {
    auto out = OIIO::ImageOutput::create(path);  // format chosen by the real name
    if (!out) fail(path, "cannot create an image writer: " + OIIO::geterror());
    const ImageFormat format = outputFormat(path);
    bool ok;
    if (format == ImageFormat::Exr) {
        OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        ok = out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, rgb.data());
    } else {
        std::vector<std::uint8_t> bytes(rgb.size());
        for (std::size_t i = 0; i < rgb.size(); ++i)
            bytes[i] = static_cast<std::uint8_t>(std::lround(linearToSrgb(rgb[i]) * 255.0f));
        OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        ok = out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    }
    std::string err = ok ? "" : out->geterror();
    if (!out->close() && ok) ok = false, err = out->geterror();
    if (!ok) fail(path, "cannot write image: " + err);
}

}  // namespace

void writeImages(const std::vector<std::string>& paths, int width, int height,
                 const std::vector<float>& rgb) {
    std::vector<std::string> temps;
    auto cleanup = [&] {
        std::error_code ec;
        for (const auto& t : temps) fs::remove(t, ec);
    };
    try {
        for (const auto& path : paths) {
            fs::path p(path);
            fs::path tmp = p.parent_path() /
                           ("." + p.stem().string() + ".tmp" + std::to_string(::getpid()) +
                            p.extension().string());
            temps.push_back(tmp.string());
            writeOne(path, tmp.string(), width, height, rgb);
        }
        for (std::size_t i = 0; i < paths.size(); ++i) {
            std::error_code ec;
            fs::rename(temps[i], paths[i], ec);
            if (ec) fail(paths[i], "cannot rename the finished image into place: " + ec.message());
        }
    } catch (...) {
        cleanup();
        throw;
    }
}

Image readImage(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string err = OIIO::geterror();
        std::replace(err.begin(), err.end(), '\n', ' ');
        fail(path, "cannot read image: " + err);
    }
    const OIIO::ImageSpec& spec = in->spec();
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.channelNames = spec.channelnames;
    img.pixels.resize(static_cast<std::size_t>(img.width) * img.height * img.channels);
    if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
        fail(path, "cannot read image: " + in->geterror());
    in->close();
    return img;
}

}  // namespace strata
