// strata command line. Errors: one line on stderr; exit 2 for bad input
// (scene, flags, files), 3 for device failures, 1 for anything else.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "render/command.h"
#include "util/error.h"
#include "vk/check.h"
#include "vk/context.h"

namespace {

using strata::Error;

constexpr const char* kUsage =
    "usage: strata render SCENE.gltf|.glb [-o OUT.exr|OUT.png]... [--spp N] [--seed S]\n"
    "                     [--max-depth D] [--width W] [--height H] [--camera I] [--device I]\n"
    "                     [--time SECONDS] [--traversal auto|texel|storage] [--quiet]\n"
    "                     [--stats] [--stats-json FILE] [--validation]\n"
    "       strata devices\n"
    "  -o may be given more than once (e.g. -o out.exr -o out.png); default: SCENE.exr and\n"
    "  SCENE.png in the current directory. --max-depth counts scattering events (pbrt):\n"
    "  0 shows emitters only, 1 is direct lighting; default 16.\n";

[[noreturn]] void badFlag(const std::string& what) { throw Error("strata: error: " + what); }

unsigned long parseUnsigned(const std::string& flag, const std::string& value, unsigned long min,
                            unsigned long max) {
    errno = 0;
    char* end = nullptr;
    const unsigned long v = std::strtoul(value.c_str(), &end, 10);
    if (value.empty() || value[0] == '-' || *end != '\0' || errno == ERANGE || v < min || v > max)
        badFlag(flag + " expects an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                "], got '" + value + "'");
    return v;
}

double parsePositive(const std::string& flag, const std::string& value) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !(v > 0.0) || v > 1e9)
        badFlag(flag + " expects a positive number of seconds, got '" + value + "'");
    return v;
}

strata::RenderCommand parseRender(const std::vector<std::string>& args) {
    strata::RenderCommand cmd;
    cmd.settings.progress = true;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) badFlag(a + " needs a value");
            return args[++i];
        };
        if (a == "-o" || a == "--output") cmd.outputs.push_back(value());
        else if (a == "--spp") cmd.settings.spp = parseUnsigned(a, value(), 1, 1u << 30);
        else if (a == "--seed") cmd.settings.seed = parseUnsigned(a, value(), 0, 0xffffffffu);
        else if (a == "--max-depth") cmd.settings.maxDepth = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--width") cmd.settings.width = parseUnsigned(a, value(), 1, 16384);
        else if (a == "--height") cmd.settings.height = parseUnsigned(a, value(), 1, 16384);
        else if (a == "--camera") cmd.camera = parseUnsigned(a, value(), 0, 1u << 20);
        else if (a == "--device") cmd.device = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--time") cmd.settings.timeLimit = parsePositive(a, value());
        else if (a == "--quiet") cmd.quiet = true, cmd.settings.progress = false;
        else if (a == "--stats") cmd.stats = true;
        else if (a == "--stats-json") cmd.statsJson = value();
        else if (a == "--validation") cmd.validation = true;
        else if (a == "--traversal") {
            const std::string& v = value();
            if (v == "auto") cmd.settings.traversal = strata::Traversal::Auto;
            else if (v == "texel") cmd.settings.traversal = strata::Traversal::Texel;
            else if (v == "storage") cmd.settings.traversal = strata::Traversal::Storage;
            else badFlag("--traversal expects auto, texel or storage, got '" + v + "'");
        } else if (!a.empty() && a[0] == '-') badFlag("unknown option '" + a + "' (see 'strata --help')");
        else if (cmd.scene.empty()) cmd.scene = a;
        else badFlag("unexpected argument '" + a + "' (one scene per render)");
    }
    if (cmd.scene.empty()) badFlag("render needs a scene file (see 'strata --help')");
    if (cmd.outputs.empty()) {
        const std::string stem = std::filesystem::path(cmd.scene).stem().string();
        cmd.outputs = {stem + ".exr", stem + ".png"};
    }
    return cmd;
}

int listDevices() {
    for (const auto& d : strata::vk::listDevices())
        std::printf("%u: %s | %s | %s | Vulkan %s\n", d.index, d.name.c_str(), d.type.c_str(),
                    d.driver.c_str(), d.apiVersion.c_str());
    return 0;
}

int run(const std::vector<std::string>& args) {
    if (args.empty() || args[0] == "-h" || args[0] == "--help" || args[0] == "help") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    const std::string& command = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (command == "render") return strata::runRender(parseRender(rest));
    if (command == "devices") {
        if (!rest.empty()) badFlag("devices takes no arguments");
        return listDevices();
    }
    badFlag("unknown command '" + command + "' (commands: render, devices)");
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const strata::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const strata::vk::DeviceError& e) {
        std::fprintf(stderr, "strata: error: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strata: error: %s\n", e.what());
        return 1;
    }
}
