// `strata view`: the scene loaded through the stages render uses, then the
// render loop (render/renderer.h) run progressively into a window, with a
// camera the mouse and keys move; the window, its swapchain and its panel
// are the module of view/api.h.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "render/command.h"

namespace strata {

// One step of --script (tests, demos): when the accumulation shown reaches
// `spp`, do `action` ("orbit DX DY", "pan DX DY", "zoom STEPS",
// "resize W H", "screenshot FILE" (the image), "window FILE" (the window as
// shown, panel included), "view NAME" (colour, albedo, normal, depth,
// denoised), "camera", "print" (the render command of the view, as P
// prints it), "close").
struct ViewScriptStep {
    std::uint32_t spp = 0;
    std::string action;
    std::vector<std::string> args;
};

// Parses --script's "SPP ACTION [ARGS]; ...": throws strata::Error (one
// line) on a word it does not know.
std::vector<ViewScriptStep> parseViewScript(const std::string& text);

struct ViewCommand : RenderCommand {
    std::uint32_t exitAfterSpp = 0;  // --exit-after-spp: exit 0 once the image has N spp
    std::string screenshot;          // --screenshot FILE.png: what the window shows, written at exit
    std::vector<ViewScriptStep> script;  // --script
    double frameSeconds = 0.05;      // a submission's time budget (RenderTuning::submitSeconds)
    std::vector<std::string> args;   // the words after 'view', for the printed render command
};

// The process's exit status: 0 when the window closed (or --exit-after-spp
// was reached). Throws strata::Error for bad input (before the window
// opens), for no display or a device that cannot present to it.
int runView(const ViewCommand& cmd);

}  // namespace strata
