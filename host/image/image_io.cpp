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
              const std::vector<float>& rgb, const std::vector<float>* variance) {
    auto out = OIIO::ImageOutput::create(path);  // format chosen by the real name
    if (!out) fail(path, "cannot create an image writer: " + OIIO::geterror());
    const ImageFormat format = outputFormat(path);
    bool ok;
    if (format == ImageFormat::Exr && variance) {
        OIIO::ImageSpec spec(w, h, 6, OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
        spec.attribute("compression", "zip");
        std::vector<float> six(rgb.size() * 2);
        for (std::size_t i = 0; i < rgb.size() / 3; ++i)
            for (int c = 0; c < 3; ++c) {
                six[i * 6 + c] = rgb[i * 3 + c];
                six[i * 6 + 3 + c] = (*variance)[i * 3 + c];
            }
        ok = out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, six.data());
    } else if (format == ImageFormat::Exr) {
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
                 const std::vector<float>& rgb, const std::vector<float>* variance) {
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
            writeOne(path, tmp.string(), width, height, rgb, variance);
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

RgbImage readRgb(const std::string& path) {
    const Image img = readImage(path);
    auto channel = [&](const std::string& name) {
        for (int c = 0; c < img.channels; ++c)
            if (img.channelNames[c] == name) return c;
        return -1;
    };
    const int r = channel("R"), g = channel("G"), b = channel("B");
    if (r < 0 || g < 0 || b < 0) fail(path, "image has no R, G and B channels");
    const int vr = channel("variance.R"), vg = channel("variance.G"), vb = channel("variance.B");
    const bool hasVariance = vr >= 0 && vg >= 0 && vb >= 0;
    RgbImage out;
    out.width = img.width;
    out.height = img.height;
    const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
    out.rgb.resize(n * 3);
    if (hasVariance) out.variance.resize(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = &img.pixels[i * img.channels];
        out.rgb[i * 3 + 0] = p[r];
        out.rgb[i * 3 + 1] = p[g];
        out.rgb[i * 3 + 2] = p[b];
        if (hasVariance) {
            out.variance[i * 3 + 0] = p[vr];
            out.variance[i * 3 + 1] = p[vg];
            out.variance[i * 3 + 2] = p[vb];
        }
    }
    return out;
}

}  // namespace strata
