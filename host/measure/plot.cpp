#include "measure/plot.h"

#include <cmath>

#include "image/image_io.h"
#include "oiio/api.h"
#include "util/error.h"

namespace strata {

void writeChart(const std::string& path, const std::vector<Panel>& panels, int w, int h) {
    outputFormat(path);  // .png or .exr; anything else is an error
    std::vector<float> pixels;
    const std::string error = imageModule(path).chart(panels, w, h, pixels);
    if (!error.empty()) fail(path, error);
    // Chart colours are display values already; undo the PNG writer's sRGB encoding.
    for (float& v : pixels) v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    writeImages({path}, w * static_cast<int>(std::max<std::size_t>(1, panels.size())), h, pixels);
}

}  // namespace strata
