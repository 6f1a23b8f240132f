#include "measure/compare.h"

#include <cstdio>
#include <fstream>

#include "image/image_io.h"
#include "util/error.h"
#include "util/files.h"

namespace strata {

nlohmann::json metricsJson(const ErrorMetrics& m) {
    return {{"rmse", m.rmse},       {"relmse", m.relMse}, {"relmse_trimmed", m.relMseTrimmed},
            {"mape", m.mape},       {"smape", m.smape},   {"max_abs", m.maxAbs},
            {"non_finite", m.nonFinite}, {"values", m.values}, {"eps", m.eps}};
}

ErrorMetrics compareFiles(const std::string& image, const std::string& reference) {
    const RgbImage a = readRgb(image);
    const RgbImage b = readRgb(reference);
    if (a.width != b.width || a.height != b.height)
        fail(image, "size " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                        " differs from the reference " + reference + " (" + std::to_string(b.width) +
                        "x" + std::to_string(b.height) + ")");
    return compareImages(a.rgb.data(), b.rgb.data(), a.rgb.size());
}

int runCompare(const std::string& image, const std::string& reference, const std::string& json) {
    if (!json.empty()) checkOutputPath(json);
    const ErrorMetrics m = compareFiles(image, reference);
    if (!json.empty()) writeTextAtomically(json, metricsJson(m).dump(2) + "\n");
    std::fputs(metricsText(m).c_str(), stdout);
    return 0;
}

}  // namespace strata
