// Line charts drawn by strata itself with OpenImageIO (lines, markers, text
// in DejaVu Sans from fonts-dejavu-core), written as PNG. One image holds one
// or more panels side by side.
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

// Throws strata::Error (naming `path`) when the file cannot be written or a
// log axis gets a value <= 0.
void writeChart(const std::string& path, const std::vector<Panel>& panels, int panelWidth = 600,
                int panelHeight = 440);

}  // namespace strata
