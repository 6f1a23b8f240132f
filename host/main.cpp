// strata command line. Errors: one line on stderr; exit 2 for bad input
// (scene, flags, files), 3 for device failures, 1 for anything else.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "measure/bench.h"
#include "measure/compare.h"
#include "measure/converge.h"
#include "measure/edges.h"
#include "image/image_io.h"
#include "render/command.h"
#include "render/sampler_kind.h"
#include "scene/environment.h"
#include "util/error.h"
#include "vk/check.h"
#include "vk/context.h"

namespace {

using strata::Error;

constexpr const char* kUsage =
    "usage: strata render SCENE.gltf|.glb [-o OUT.exr|OUT.png]... [--spp N] [--seed S]\n"
    "                     [--max-depth D] [--width W] [--height H] [--camera I] [--device I]\n"
    "                     [--time SECONDS] [--traversal auto|texel|storage] [--bvh 2|4] [--quiet]\n"
    "                     [--bvh-stack auto|registers|memory] [--integrator megakernel|wavefront]\n"
    "                     [--sampler independent|regular|rotated|stratified|sobol|bluenoise]\n"
    "                     [--filter box|tent|gaussian|blackman-harris] [--filter-radius PIXELS]\n"
    "                     [--mis power|bsdf|light]\n"
    "                     [--stats] [--stats-json FILE] [--validation]\n"
    "                     [--env MAP.hdr|MAP.exr | --env-color R,G,B] [--env-intensity S]\n"
    "                     [--env-rotate DEGREES]\n"
    "       strata reference SCENE --spp N -o REF.exr [render options]\n"
    "       strata compare IMAGE.exr REFERENCE.exr [--json FILE]\n"
    "       strata converge SCENE --reference REF.exr -o REPORT.csv|.json [--spp 1,2,4,...]\n"
    "                       [--seeds K] [--plot PLOT.png] [--seed S] [--max-depth D] [--camera I]\n"
    "                       [--sampler NAME|all] [--env ... (as render)]\n"
    "       strata edges [--spp 64] [--sampler NAME|all] [--seed S] [-o TABLE.csv] [--plot PLOT.png]\n"
    "       strata bench SCENE [--width W] [--height H] [--spp N] [--reference REF.exr] [--seed S]\n"
    "                    [--max-depth D] [--reps R] [--camera I] [--device I] [--quick] [--only traversal]\n"
    "                    [--bvh 2|4] [--bvh-stack auto|registers|memory] [--traversal auto|texel|storage]\n"
    "                    [--integrator megakernel|wavefront]\n"
    "                    [--env ... (as render)] [--json FILE]\n"
    "       strata devices\n"
    "  -o may be given more than once (e.g. -o out.exr -o out.png); default: SCENE.exr and\n"
    "  SCENE.png in the current directory. --max-depth counts scattering events (pbrt):\n"
    "  0 shows emitters only, 1 is direct lighting; default 16.\n"
    "  reference writes EXR with variance.R/G/B channels (variance of each pixel's mean).\n"
    "  relMSE = mean (x - r)^2 / (r^2 + 0.01).\n"
    "  --env: equirectangular map, +Y up, image centre -Z, u towards +X; --env-color:\n"
    "  constant radiance; both scaled by --env-intensity and turned about +Y by --env-rotate.\n";

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

int parseBvhWidth(const std::string& value) {
    if (value != "2" && value != "4") badFlag("--bvh expects 2 or 4, got '" + value + "'");
    return value == "2" ? 2 : 4;
}

strata::ReadMode parseTraversal(const std::string& v) {
    if (v == "auto") return strata::ReadMode::Auto;
    if (v == "texel") return strata::ReadMode::Texel;
    if (v == "storage") return strata::ReadMode::Storage;
    badFlag("--traversal expects auto, texel or storage, got '" + v + "'");
}

strata::BvhStack parseBvhStack(const std::string& v) {
    if (v == "auto") return strata::BvhStack::Auto;
    if (v == "registers") return strata::BvhStack::Registers;
    if (v == "memory") return strata::BvhStack::Memory;
    badFlag("--bvh-stack expects auto, registers or memory, got '" + v + "'");
}

strata::IntegratorKind parseIntegrator(const std::string& v) {
    if (v == "megakernel") return strata::IntegratorKind::Megakernel;
    if (v == "wavefront") return strata::IntegratorKind::Wavefront;
    badFlag("--integrator expects megakernel or wavefront, got '" + v + "'");
}

// 16, 1000000000, 1e+30: integers as integers up to 1e15, the rest as %g.
std::string numberText(double v) {
    if (v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

double parsePositive(const std::string& flag, const std::string& value, double max, const char* what) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !(v > 0.0) || v > max)
        badFlag(flag + " expects " + what + " in (0, " + numberText(max) + "], got '" + value + "'");
    return v;
}

double parseFinite(const std::string& flag, const std::string& value) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v))
        badFlag(flag + " expects a finite number, got '" + value + "'");
    return v;
}

// --env-color R,G,B: three numbers in [0, 1e30], not all 0.
glm::vec3 parseColor(const std::string& flag, const std::string& value) {
    double c[3];
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = value.find(',', start);
        if ((k < 2) != (comma != std::string::npos)) badFlag(flag + " expects R,G,B, got '" + value + "'");
        const std::string item = value.substr(start, k < 2 ? comma - start : std::string::npos);
        char* end = nullptr;
        c[k] = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(c[k]) || c[k] < 0.0 || c[k] > 1e30)
            badFlag(flag + " expects R,G,B, three numbers in [0, 1e+30], got '" + value + "'");
        start = comma + 1;
    }
    if (c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0)
        badFlag(flag + " is black; leave out --env-color for no environment");
    return glm::vec3(c[0], c[1], c[2]);
}

// The environment flags shared by render, reference and converge; true when
// `a` is one of them.
template <class Value>
bool parseEnvFlag(const std::string& a, Value&& value, strata::EnvironmentOptions& env) {
    if (a == "--env") env.file = value();
    else if (a == "--env-color") env.color = parseColor(a, value()), env.hasColor = true;
    else if (a == "--env-intensity") env.intensity = static_cast<float>(parsePositive(a, value(), 1e30, "a factor"));
    else if (a == "--env-rotate") env.rotateDegrees = parseFinite(a, value());
    else return false;
    return true;
}

void checkEnvFlags(const std::vector<std::string>& args, const strata::EnvironmentOptions& env) {
    if (!env.file.empty() && env.hasColor) badFlag("--env and --env-color exclude each other");
    for (const auto& a : args)
        if ((a == "--env-intensity" || a == "--env-rotate") && !env.given())
            badFlag(a + " needs --env or --env-color");
}

strata::RenderCommand parseRender(const std::vector<std::string>& args) {
    strata::RenderCommand cmd;
    cmd.settings.progress = true;
    bool radiusGiven = false;
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
        else if (a == "--time") cmd.settings.timeLimit = parsePositive(a, value(), 1e9, "seconds");
        else if (a == "--quiet") cmd.quiet = true, cmd.settings.progress = false;
        else if (a == "--stats") cmd.stats = true;
        else if (a == "--stats-json") cmd.statsJson = value();
        else if (a == "--validation") cmd.validation = true;
        else if (a == "--sampler") cmd.settings.sampler = strata::samplerByName(value()).kind;
        else if (parseEnvFlag(a, value, cmd.env)) continue;
        else if (a == "--mis") {
            const std::string& v = value();
            if (v == "power") cmd.settings.mis = strata::gpu::kMisPower;
            else if (v == "bsdf") cmd.settings.mis = strata::gpu::kMisBsdf;
            else if (v == "light") cmd.settings.mis = strata::gpu::kMisLight;
            else badFlag("--mis expects power, bsdf or light, got '" + v + "'");
        }
        else if (a == "--filter") {
            const float radius = cmd.settings.filter.radius;
            const bool customRadius = radiusGiven;
            cmd.settings.filter = strata::filterByName(value());
            if (customRadius) cmd.settings.filter.radius = radius;
        } else if (a == "--filter-radius") {
            cmd.settings.filter.radius = static_cast<float>(parsePositive(a, value(), 16, "a radius in pixels"));
            radiusGiven = true;
        } else if (a == "--bvh") {
            cmd.settings.bvhWidth = parseBvhWidth(value());
        } else if (a == "--traversal") {
            cmd.settings.reads = parseTraversal(value());
        } else if (a == "--bvh-stack") {
            cmd.settings.bvhStack = parseBvhStack(value());
        } else if (a == "--integrator") {
            cmd.settings.integrator = parseIntegrator(value());
        } else if (!a.empty() && a[0] == '-') badFlag("unknown option '" + a + "' (see 'strata --help')");
        else if (cmd.scene.empty()) cmd.scene = a;
        else badFlag("unexpected argument '" + a + "' (one scene per render)");
    }
    if (cmd.scene.empty()) badFlag("render needs a scene file (see 'strata --help')");
    checkEnvFlags(args, cmd.env);
    if (cmd.outputs.empty()) {
        const std::string stem = std::filesystem::path(cmd.scene).stem().string();
        cmd.outputs = {stem + ".exr", stem + ".png"};
    }
    return cmd;
}

std::vector<std::uint32_t> parseSppList(const std::string& value) {
    std::vector<std::uint32_t> out;
    std::size_t start = 0;
    while (start <= value.size()) {
        const std::size_t comma = value.find(',', start);
        const std::string item = value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const auto v = static_cast<std::uint32_t>(parseUnsigned("--spp", item, 1, 1u << 30));
        if (!out.empty() && v <= out.back()) badFlag("--spp values must be ascending, got '" + value + "'");
        out.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

int runReference(const std::vector<std::string>& args) {
    strata::RenderCommand cmd = parseRender(args);
    bool sppGiven = false, exrGiven = false;
    for (const auto& a : args) sppGiven |= a == "--spp";
    for (const auto& o : cmd.outputs) exrGiven |= strata::outputFormat(o) == strata::ImageFormat::Exr;
    if (!sppGiven) badFlag("reference needs --spp N (a high sample count)");
    if (!exrGiven) badFlag("reference needs an .exr output (-o REF.exr) to store the variance");
    cmd.variance = true;
    return strata::runRender(cmd);
}

int runCompare(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    std::string json;
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--json") {
            if (i + 1 >= args.size()) badFlag("--json needs a value");
            json = args[++i];
        } else if (!args[i].empty() && args[i][0] == '-') {
            badFlag("unknown option '" + args[i] + "' (see 'strata --help')");
        } else {
            files.push_back(args[i]);
        }
    }
    if (files.size() != 2) badFlag("compare needs IMAGE and REFERENCE");
    return strata::runCompare(files[0], files[1], json);
}

int runConverge(const std::vector<std::string>& args) {
    strata::ConvergeCommand cmd;
    for (std::uint32_t s = 1; s <= 256; s *= 2) cmd.spp.push_back(s);
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) badFlag(a + " needs a value");
            return args[++i];
        };
        if (a == "-o" || a == "--output") cmd.report = value();
        else if (a == "--reference") cmd.reference = value();
        else if (a == "--spp") cmd.spp = parseSppList(value());
        else if (a == "--seeds") cmd.seeds = parseUnsigned(a, value(), 1, 1000);
        else if (a == "--sampler") {
            const std::string& v = value();
            if (v == "all") cmd.allSamplers = true;
            else cmd.settings.sampler = strata::samplerByName(v).kind;
        } else if (a == "--plot") cmd.plot = value();
        else if (a == "--seed") cmd.settings.seed = parseUnsigned(a, value(), 0, 0xffffffffu);
        else if (a == "--max-depth") cmd.settings.maxDepth = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--camera") cmd.camera = parseUnsigned(a, value(), 0, 1u << 20);
        else if (a == "--device") cmd.device = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--validation") cmd.validation = true;
        else if (a == "--quiet") cmd.quiet = true;
        else if (parseEnvFlag(a, value, cmd.env)) continue;
        else if (!a.empty() && a[0] == '-') badFlag("unknown option '" + a + "' (see 'strata --help')");
        else if (cmd.scene.empty()) cmd.scene = a;
        else badFlag("unexpected argument '" + a + "'");
    }
    if (cmd.scene.empty()) badFlag("converge needs a scene file");
    checkEnvFlags(args, cmd.env);
    if (cmd.reference.empty()) badFlag("converge needs --reference REF.exr");
    if (cmd.report.empty()) badFlag("converge needs -o REPORT.csv or REPORT.json");
    return strata::runConverge(cmd);
}

int runEdgesCommand(const std::vector<std::string>& args) {
    strata::EdgesCommand cmd;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) badFlag(a + " needs a value");
            return args[++i];
        };
        if (a == "-o" || a == "--output") cmd.table = value();
        else if (a == "--plot") cmd.plot = value();
        else if (a == "--spp") cmd.settings.spp = parseUnsigned(a, value(), 1, 1u << 16);
        else if (a == "--seed") cmd.settings.seed = parseUnsigned(a, value(), 0, 0xffffffffu);
        else if (a == "--sampler") {
            const std::string& v = value();
            cmd.settings.samplers.clear();
            if (v != "all") cmd.settings.samplers.push_back(strata::samplerByName(v).kind);
        } else if (a == "--device") cmd.device = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--validation") cmd.validation = true;
        else if (!a.empty() && a[0] == '-') badFlag("unknown option '" + a + "' (see 'strata --help')");
        else badFlag("unexpected argument '" + a + "'");
    }
    return strata::runEdges(cmd);
}

int runBenchCommand(const std::vector<std::string>& args) {
    strata::BenchCommand cmd;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) badFlag(a + " needs a value");
            return args[++i];
        };
        if (a == "--width") cmd.width = parseUnsigned(a, value(), 1, 16384);
        else if (a == "--height") cmd.height = parseUnsigned(a, value(), 1, 16384);
        else if (a == "--reps") cmd.reps = parseUnsigned(a, value(), 1, 1000);
        else if (a == "--spp") cmd.spp = parseUnsigned(a, value(), 1, 1u << 20);
        else if (a == "--seed") cmd.seed = parseUnsigned(a, value(), 0, 0xffffffffu);
        else if (a == "--max-depth") cmd.maxDepth = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--reference") cmd.reference = value();
        else if (parseEnvFlag(a, value, cmd.env)) continue;
        else if (a == "--quick") cmd.quick = true;
        else if (a == "--bvh") cmd.bvhWidth = parseBvhWidth(value());
        else if (a == "--traversal") cmd.reads = parseTraversal(value());
        else if (a == "--bvh-stack") cmd.bvhStack = parseBvhStack(value());
        else if (a == "--integrator") cmd.integrator = parseIntegrator(value());
        else if (a == "--only") {
            cmd.only = value();
            if (cmd.only != "traversal") badFlag("--only takes 'traversal' (got '" + cmd.only + "')");
        }
        else if (a == "--camera") cmd.camera = parseUnsigned(a, value(), 0, 1u << 20);
        else if (a == "--device") cmd.device = parseUnsigned(a, value(), 0, 1024);
        else if (a == "--json") cmd.json = value();
        else if (a == "--validation") cmd.validation = true;
        else if (!a.empty() && a[0] == '-') badFlag("unknown option '" + a + "' (see 'strata --help')");
        else if (cmd.scene.empty()) cmd.scene = a;
        else badFlag("unexpected argument '" + a + "'");
    }
    if (cmd.scene.empty()) badFlag("bench needs a scene file");
    checkEnvFlags(args, cmd.env);
    return strata::runBench(cmd);
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
    if (command == "reference") return runReference(rest);
    if (command == "compare") return runCompare(rest);
    if (command == "converge") return runConverge(rest);
    if (command == "edges") return runEdgesCommand(rest);
    if (command == "bench") return runBenchCommand(rest);
    if (command == "devices") {
        if (!rest.empty()) badFlag("devices takes no arguments");
        return listDevices();
    }
    badFlag("unknown command '" + command + "' (commands: render, reference, compare, converge, edges, bench, devices)");
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
