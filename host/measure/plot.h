// Line charts drawn by strata itself with OpenImageIO (lines, markers, text
// in DejaVu Sans from fonts-dejavu-core), written as PNG. One image holds one
// or more panels side by side.
#pragma once
#include <string>
#include <vector>

#include "oiio/chart.h"

namespace strata {

// Throws strata::Error (naming `path`) when the file cannot be written or a
// log axis gets a value <= 0.
void writeChart(const std::string& path, const std::vector<Panel>& panels, int panelWidth = 600,
                int panelHeight = 440);

}  // namespace strata
