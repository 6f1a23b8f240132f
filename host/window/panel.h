// The panel drawn over the image (window/panel.cpp): between ImGui's
// NewFrame and Render, its widgets read and write `panel`.
#pragma once
#include "view/api.h"

namespace strata::view {

void drawPanel(Panel& panel);

}  // namespace strata::view
