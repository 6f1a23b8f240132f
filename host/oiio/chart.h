// A line chart as data: panels of series, drawn by the OpenImageIO module
// (oiio/api.h, oiio/chart.cpp) for measure/plot.h. Plain data; includes
// nothing of strata's.
#pragma once
#include <array>
#include <string>
#include <vector>

namespace strata {

struct Series {
    std::string label;
    std::vector<double> x, y;
    std::array<float, 3> color{0.1f, 0.3f, 0.8f};
    bool dashed = false;   // dashed line, no markers (reference lines)
    bool markers = true;
};

struct Panel {
    std::string title;
    std::string xLabel, yLabel;
    bool logX = true, logY = true;  // log axes show decades
    std::vector<Series> series;
};

}  // namespace strata
