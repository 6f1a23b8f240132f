// Line charts drawn with OpenImageIO (measure/plot.h; host/oiio/api.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "oiio/api.h"

namespace strata::oiio {
namespace {

namespace IBA = OIIO::ImageBufAlgo;

constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr int kMarginLeft = 78, kMarginRight = 16, kMarginTop = 34, kMarginBottom = 52;

struct Axis {
    bool log = true;
    double lo = 0.0, hi = 1.0;  // in axis units (log10 when log)
    double map(double v) const { return log ? std::log10(v) : v; }
};

Axis makeAxis(const std::vector<const std::vector<double>*>& data, bool log) {
    double lo = 1e300, hi = -1e300;
    for (const auto* values : data)
        for (double v : *values) {
            if (!std::isfinite(v)) continue;
            if (log && v <= 0.0) throw std::runtime_error("chart: a log axis got the value " + std::to_string(v));
            const double m = log ? std::log10(v) : v;
            lo = std::min(lo, m);
            hi = std::max(hi, m);
        }
    if (lo > hi) lo = 0.0, hi = 1.0;
    if (log) {
        lo = std::floor(lo);
        hi = std::ceil(hi);
        if (hi <= lo) hi = lo + 1.0;
    } else {
        const double pad = (hi - lo) * 0.05 + (hi == lo ? 0.5 : 0.0);
        lo -= pad;
        hi += pad;
    }
    return {log, lo, hi};
}

std::string tickLabel(double v, bool log) {
    char buf[32];
    if (log) std::snprintf(buf, sizeof buf, "1e%d", static_cast<int>(std::lround(v)));
    else std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

void text(OIIO::ImageBuf& img, int x, int y, const std::string& s, int size,
          std::array<float, 3> c = {0.1f, 0.1f, 0.1f},
          IBA::TextAlignX ax = IBA::TextAlignX::Left) {
    IBA::render_text(img, x, y, s, size, kFont, {c[0], c[1], c[2]}, ax);
}

void line(OIIO::ImageBuf& img, int x0, int y0, int x1, int y1, std::array<float, 3> c) {
    IBA::render_line(img, x0, y0, x1, y1, {c[0], c[1], c[2]}, true);
}

void drawPanel(OIIO::ImageBuf& img, const Panel& p, int ox, int w, int h) {
    std::vector<const std::vector<double>*> xs, ys;
    for (const auto& s : p.series) xs.push_back(&s.x), ys.push_back(&s.y);
    const Axis ax = makeAxis(xs, p.logX), ay = makeAxis(ys, p.logY);
    const int x0 = ox + kMarginLeft, x1 = ox + w - kMarginRight;
    const int y0 = kMarginTop, y1 = h - kMarginBottom;  // y0 top, y1 bottom
    auto px = [&](double v) { return x0 + (ax.map(v) - ax.lo) / (ax.hi - ax.lo) * (x1 - x0); };
    auto py = [&](double v) { return y1 - (ay.map(v) - ay.lo) / (ay.hi - ay.lo) * (y1 - y0); };
    const std::array<float, 3> grid{0.88f, 0.88f, 0.88f}, axisColor{0.2f, 0.2f, 0.2f};

    // Grid and ticks: every decade on log axes, 5 divisions on linear ones.
    auto ticks = [](const Axis& a) {
        std::vector<double> t;
        if (a.log)
            for (double d = a.lo; d <= a.hi + 1e-9; d += 1.0) t.push_back(d);
        else
            for (int i = 0; i <= 5; ++i) t.push_back(a.lo + (a.hi - a.lo) * i / 5.0);
        return t;
    };
    for (double t : ticks(ax)) {
        const int x = static_cast<int>(std::lround(x0 + (t - ax.lo) / (ax.hi - ax.lo) * (x1 - x0)));
        line(img, x, y0, x, y1, grid);
        text(img, x, y1 + 18, tickLabel(t, ax.log), 13, axisColor, IBA::TextAlignX::Center);
    }
    for (double t : ticks(ay)) {
        const int y = static_cast<int>(std::lround(y1 - (t - ay.lo) / (ay.hi - ay.lo) * (y1 - y0)));
        line(img, x0, y, x1, y, grid);
        text(img, x0 - 6, y + 5, tickLabel(t, ay.log), 13, axisColor, IBA::TextAlignX::Right);
    }
    line(img, x0, y1, x1, y1, axisColor);
    line(img, x0, y0, x0, y1, axisColor);
    text(img, (x0 + x1) / 2, 22, p.title, 15, axisColor, IBA::TextAlignX::Center);
    text(img, (x0 + x1) / 2, h - 12, p.xLabel, 14, axisColor, IBA::TextAlignX::Center);
    text(img, ox + 6, y0 - 10, p.yLabel, 14, axisColor);

    int legendY = y0 + 18;
    for (const auto& s : p.series) {
        int prevX = 0, prevY = 0;
        bool havePrev = false;
        for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
            const int x = static_cast<int>(std::lround(px(s.x[i])));
            const int y = static_cast<int>(std::lround(py(s.y[i])));
            if (havePrev) {
                if (s.dashed) {
                    const int steps = std::max(1, static_cast<int>(std::hypot(x - prevX, y - prevY) / 6));
                    for (int k = 0; k < steps; k += 2) {
                        const double a = static_cast<double>(k) / steps, b = std::min(1.0, (k + 1.0) / steps);
                        line(img, prevX + static_cast<int>((x - prevX) * a), prevY + static_cast<int>((y - prevY) * a),
                             prevX + static_cast<int>((x - prevX) * b), prevY + static_cast<int>((y - prevY) * b),
                             s.color);
                    }
                } else {
                    line(img, prevX, prevY, x, y, s.color);
                }
            }
            if (s.markers && !s.dashed)
                IBA::fill(img, {s.color[0], s.color[1], s.color[2]}, OIIO::ROI(x - 2, x + 3, y - 2, y + 3));
            prevX = x, prevY = y, havePrev = true;
        }
        if (!s.label.empty()) {
            line(img, x1 - 190, legendY - 5, x1 - 165, legendY - 5, s.color);
            text(img, x1 - 158, legendY, s.label, 13, axisColor);
            legendY += 18;
        }
    }
}

}  // namespace

std::string drawChart(const std::vector<Panel>& panels, int w, int h, std::vector<float>& rgb) {
    try {
        const int width = w * static_cast<int>(std::max<std::size_t>(1, panels.size()));
        OIIO::ImageBuf img(OIIO::ImageSpec(width, h, 3, OIIO::TypeDesc::FLOAT));
        IBA::fill(img, {1.0f, 1.0f, 1.0f});
        for (std::size_t i = 0; i < panels.size(); ++i) drawPanel(img, panels[i], static_cast<int>(i) * w, w, h);
        if (!std::filesystem::exists(kFont))
            return std::string("chart: font ") + kFont + " is missing (fonts-dejavu-core)";
        rgb.resize(static_cast<std::size_t>(width) * h * 3);
        img.get_pixels(OIIO::ROI(0, width, 0, h, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, rgb.data());
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

}  // namespace strata::oiio
