// `strata view`'s flags (cli/commands.cpp lists the command): the render
// flags that a progressive view can use, and its own.
#include "cli/checks.h"
#include "cli/flag_groups.h"
#include "cli/flags.h"
#include "image/image_io.h"
#include "view/viewer.h"

namespace strata::cli {
namespace {

const CommandText kViewText{"view", "SCENE.gltf|.glb [options]",
    "Watch a scene converge in a window, moving the camera with the mouse and keys.",
    "Left drag orbits, right or middle drag pans, the wheel zooms, W/A/S/D/Q/E fly, R resets\n"
    "the view, C switches cameras, F2 (or Ctrl+S) saves SCENE-view-Nspp.exr and .png, P prints\n"
    "the 'strata render' command of the view, Esc closes. Any change restarts the\n"
    "accumulation. --spp is where it stops.\n"};

std::vector<Flag<ViewCommand>> viewFlags() {
    using C = ViewCommand;
    const auto settings = [](auto& c) -> auto& { return c.settings; };
    return concat<C>({
        {
            integer<C>("--spp", "N", "stop accumulating at N samples per pixel", 1, 1u << 30,
                       STRATA_FIELD(settings.spp))
                .withDefault("4096"),
            integer<C>("--width", "W", "the window's width in pixels (the image follows the window)", 1, 16384,
                       STRATA_FIELD(settings.width))
                .withDefault("640"),
            integer<C>("--height", "H", "the window's height in pixels", 1, 16384, STRATA_FIELD(settings.height))
                .withDefault("360"),
            integer<C>("--exit-after-spp", "N", "exit once the image has N samples per pixel (scripts, tests)", 1,
                       1u << 30, STRATA_FIELD(exitAfterSpp))
                .withDefault("never"),
            text<C>("--screenshot", "FILE.png", "at exit, write what the window shows (the image, no panel) to FILE",
                    STRATA_FIELD(screenshot)),
            flag<C>("--script", "'SPP ACTION [ARGS]; ...'",
                    "when the image reaches SPP, do ACTION: orbit DX DY, pan DX DY, zoom STEPS, resize W H, camera, "
                    "view colour|albedo|normal|depth|denoised, print (the render command), screenshot FILE (the "
                    "image), window FILE (with the panel), close (tests, demos); each step run is printed",
                    [](C& c, const std::string&, const std::string& v) { c.script = parseViewScript(v); }),
            toggle<C>("--quiet", "print no device line", [](C& c) { c.quiet = true; }),
            toggle<C>("--stats", "print how long the first image, and each after a change, took to show",
                      [](C& c) { c.stats = true; }),
        },
        renderGroups<C>(settings),
    });
}

ViewCommand viewInit() {
    ViewCommand c;
    c.settings.width = 640;
    c.settings.height = 360;
    c.settings.spp = 4096;
    return c;
}

const CommandSpec<ViewCommand>& viewSpec() { return kept<kViewText>(viewFlags, viewInit); }

}  // namespace

ViewCommand parseView(const std::vector<std::string>& args) {
    ViewCommand cmd = viewSpec().init;
    const Parsed parsed = parseFlags(viewSpec(), args, cmd);
    if (parsed.positional.size() > 1) badFlag("unexpected argument '" + parsed.positional[1] + "' (one scene per view)");
    if (parsed.positional.empty()) badFlag("view needs a scene file (see 'strata view --help')");
    cmd.scene = parsed.positional[0];
    // The same spp as the render it stands for: --exit-after-spp N alone is --spp N.
    if (cmd.exitAfterSpp && !parsed.has("--spp")) cmd.settings.spp = cmd.exitAfterSpp;
    if (cmd.exitAfterSpp > cmd.settings.spp)
        badFlag("--exit-after-spp " + std::to_string(cmd.exitAfterSpp) + " is above --spp " +
                std::to_string(cmd.settings.spp));
    if (!cmd.screenshot.empty() && outputFormat(cmd.screenshot) != ImageFormat::Png)
        badFlag("--screenshot takes a .png file, got '" + cmd.screenshot + "'");
    checkRenderFlags(parsed, cmd);
    cmd.args = args;
    return cmd;
}

CommandInfo viewCommand() {
    return command(viewSpec(), [](const auto& a) { return runView(parseView(a)); });
}

}  // namespace strata::cli
