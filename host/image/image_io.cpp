#include "image/image_io.h"

#include <algorithm>
#include <array>
#include <limits>
#include <cstring>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>
#include <system_error>

#include <unistd.h>

#include "oiio/api.h"
#include "util/error.h"
#include "util/files.h"
#include "util/interrupt.h"
#include "util/module.h"

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

std::uint8_t srgb8(float linear) { return static_cast<std::uint8_t>(std::lround(linearToSrgb(linear) * 255.0f)); }

Srgb8Table::Srgb8Table() {
    // srgb8 never falls as x grows: each step is the first float in [0, 1]
    // where it reaches k, found by bisecting the floats' bit patterns.
    steps_[0] = -std::numeric_limits<float>::infinity();
    for (int k = 1; k < 256; ++k) {
        std::uint32_t lo = 0, hi = 0x3f800000u;  // 0 and 1.0f: srgb8(1) = 255
        while (lo < hi) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            float x;
            std::memcpy(&x, &mid, sizeof x);
            if (srgb8(x) >= k) hi = mid;
            else lo = mid + 1;
        }
        std::memcpy(&steps_[std::size_t(k)], &lo, sizeof lo);
    }
}

std::uint8_t Srgb8Table::operator()(float linear) const {
    if (!(linear > 0.0f)) return 0;  // NaN too
    return static_cast<std::uint8_t>(std::upper_bound(steps_.begin() + 1, steps_.end(), linear) - steps_.begin() - 1);
}

namespace {

void writeOne(const std::string& path, const std::string& tmp, int w, int h, const std::vector<float>& rgb,
              const ExtraChannels& extra) {
    const oiio::Api& module = imageModule(path);
    std::string error;
    if (outputFormat(path) == ImageFormat::Exr) {
        error = module.writeExr(path, tmp, w, h, rgb.data(), extra);
    } else {
        std::vector<std::uint8_t> bytes(rgb.size());
        for (std::size_t i = 0; i < rgb.size(); ++i)
            bytes[i] = srgb8(rgb[i]);
        error = module.writePng(path, tmp, w, h, bytes.data());
    }
    if (!error.empty()) fail(path, error);
}

}  // namespace

bool imageSupportBuilt() { return std::string_view(STRATA_OIIO_MODULE) != ""; }

void requireImageSupport(const std::string& path) {
    if (!imageSupportBuilt() && !std::getenv("STRATA_OIIO_MODULE"))
        fail(path, "cannot read or write images: strata was built without OpenImageIO (cmake -DSTRATA_OIIO=OFF)");
}

const oiio::Api& imageModule(const std::string& path) {
    static std::string error;
    static const auto* api = static_cast<const oiio::Api*>(loadModuleApi(
        {"STRATA_OIIO_MODULE", STRATA_OIIO_MODULE, "libstrata_oiio.so", "strata_oiio_api", oiio::kApiVersion,
         "strata was built without OpenImageIO (cmake -DSTRATA_OIIO=OFF)", "image module"},
        error));
    if (!api) fail(path, "image support (OpenImageIO) could not be loaded: " + error);
    return *api;
}

namespace {

// Each of `paths` written by write(path, tmp) under a temporary name beside
// it, then renamed: all of them, or none.
void writeAll(const std::vector<std::string>& paths,
              const std::function<void(const std::string&, const std::string&)>& write) {
    std::vector<std::string> temps;
    std::vector<std::unique_ptr<TempFileGuard>> guards;  // removed by a second SIGINT or SIGTERM
    auto cleanup = [&] {
        std::error_code ec;
        for (const auto& t : temps) fs::remove(t, ec);
    };
    try {
        for (const auto& path : paths) {
            fs::path p(path);
            std::string name = ".";
            name += p.stem().string();
            name += ".tmp" + std::to_string(::getpid());
            name += p.extension().string();
            const fs::path tmp = p.parent_path() / name;
            temps.push_back(tmp.string());
            guards.push_back(std::make_unique<TempFileGuard>(tmp.string()));
            write(path, tmp.string());
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

}  // namespace

void writeImages(const std::vector<std::string>& paths, int width, int height,
                 const std::vector<float>& rgb, const ExtraChannels& extra) {
    writeAll(paths, [&](const std::string& path, const std::string& tmp) {
        writeOne(path, tmp, width, height, rgb, extra);
    });
}

void writePng8(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (outputFormat(path) != ImageFormat::Png) fail(path, "not a .png file");
    writeAll({path}, [&](const std::string& p, const std::string& tmp) {
        const std::string error = imageModule(p).writePng(p, tmp, width, height, rgb.data());
        if (!error.empty()) fail(p, error);
    });
}

Image readImage(const std::string& path) {
    // Named here rather than in the image library's words ("could not find a
    // format reader", "RGBE read error -- early end of file").
    if (const Unusable u = unusableInput(path); u != Unusable::No)
        fail(path, u == Unusable::Directory ? "cannot read image: is a directory" : "cannot read image: empty file");
    Image img;
    const std::string error = imageModule(path).read(path, img);
    if (!error.empty()) fail(path, error);
    return img;
}

RgbImage readReference(const std::string& path) {
    RgbImage img = readRgb(path);
    for (std::size_t i = 0; i < img.rgb.size(); ++i) {
        if (std::isfinite(img.rgb[i])) continue;
        const std::size_t pixel = i / 3;
        fail(path, "reference pixel (" + std::to_string(pixel % std::size_t(img.width)) + ", " +
                       std::to_string(pixel / std::size_t(img.width)) + ") has a non-finite value (NaN or Inf)");
    }
    return img;
}

RgbImage readRgb(const std::string& path) {
    const Image img = readImage(path);
    const int r = img.channel("R"), g = img.channel("G"), b = img.channel("B");
    if (r < 0 || g < 0 || b < 0) fail(path, "image has no R, G and B channels");
    const int vr = img.channel("variance.R"), vg = img.channel("variance.G"), vb = img.channel("variance.B");
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
