// The flag groups the commands share (the path, the traversal, the
// environment, the scene, the device) and the helpers that build a
// command's table from them, for cli/commands.cpp.
#pragma once
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/flags.h"
#include "settings/filter.h"
#include "render/sampler_kind.h"
#include "spirv/cache.h"
#include "util/files.h"

namespace strata::cli {

// The member a flag sets, for a command and for a const one.
#define STRATA_FIELD(member) [](auto& c) -> auto& { return c.member; }

template <class T>
std::vector<Flag<T>> concat(std::initializer_list<std::vector<Flag<T>>> groups) {
    std::vector<Flag<T>> all;
    for (const auto& g : groups) all.insert(all.end(), g.begin(), g.end());
    return all;
}

inline std::vector<std::string> samplerNames() {
    std::vector<std::string> names;
    for (const SamplerInfo& s : samplers()) names.push_back(s.name);
    return names;
}

inline constexpr const char* kSamplerHelp =
    "the pixel sampler; regular, rotated and stratified need a square spp, bluenoise a power of two";

inline std::vector<std::string> filterNames() {
    std::vector<std::string> names;
    for (FilterKind k : {FilterKind::Box, FilterKind::Tent, FilterKind::Gaussian, FilterKind::BlackmanHarris})
        names.push_back(filterName(k));
    return names;
}

// "box 0.5, tent 1, ...": each filter's own radius.
inline std::string filterRadii() {
    std::vector<std::string> radii;
    for (const std::string& name : filterNames()) radii.push_back(name + " " + numberText(filterByName(name).radius));
    return joined(radii, ", ");
}

// The spec of the command `text` names, made on first use from its flags
// and its starting value (the command struct's own without `init`) and kept:
// the parser and the help share it.
template <const CommandText& text, class T>
const CommandSpec<T>& kept(std::vector<Flag<T>> (*flags)(), T (*init)() = nullptr) {
    static const CommandSpec<T> spec = makeSpec<T>(text, flags(), init ? init() : T{});
    return spec;
}

// Every name of the flags (aliases, old names), or of the tuning flags alone.
template <class T>
std::vector<std::string> flagNames(const CommandSpec<T>& spec, bool tuningOnly) {
    std::vector<std::string> names;
    for (const Flag<T>& f : spec.flags)
        if (f.tuning || !tuningOnly)
            for (const std::string* n : {&f.alias, &f.name, &f.oldName})
                if (!n->empty()) names.push_back(*n);
    return names;
}

template <class T>
CommandInfo command(const CommandSpec<T>& spec, std::function<int(const std::vector<std::string>&)> run) {
    return {spec.name,
            spec.summary,
            [&spec] { return helpText(spec); },
            [&spec] { return hasTuning(flagTexts(spec)) ? helpText(spec, HelpPart::Tuning) : std::string(); },
            [&spec] { return flagNames(spec, false); },
            [&spec] { return flagNames(spec, true); },
            [&spec, run](const std::vector<std::string>& args) {
                const HelpPart part = helpRequested(flagTexts(spec), args);
                if (part != HelpPart::None) {
                    std::fputs(helpText(spec, part).c_str(), stdout);
                    return 0;
                }
                return run(args);
            }};
}

// --sampler, --filter, --filter-radius (render, view).
template <class T>
std::vector<Flag<T>> pixelFlags() {
    return {
        flag<T>(
            "--sampler", joined(samplerNames(), "|"), kSamplerHelp,
            [](T& c, const std::string&, const std::string& v) { c.settings.sampler = samplerByName(v).kind; },
            [](const T& c) { return std::string(samplerByKind(c.settings.sampler).name); }),
        flag<T>(
            "--filter", joined(filterNames(), "|"),
            "the pixel reconstruction filter, sampled by importance: each sample weighs 1",
            // With its own radius; --filter-radius, applied last, overrides it.
            [](T& c, const std::string&, const std::string& v) { c.settings.filter = filterByName(v); },
            [](const T& c) { return std::string(filterName(c.settings.filter.kind)); }),
        positive<T>("--filter-radius", "PIXELS", "the filter's radius, in pixels", 16, "a radius in pixels",
                    STRATA_FIELD(settings.filter.radius))
            .withDefault(filterRadii())
            .appliedLast(),
    };
}

// The groups render and view share after their own flags: the pixel, path,
// trace, environment, scene and device flags.
template <class T, class Settings>
std::vector<Flag<T>> renderGroups(Settings settings);

// The shared groups. `settings` gives the command's RenderSettings, which
// holds seed, maxDepth and the traversal choices.
template <class T, class Settings>
Flag<T> seedFlag(Settings settings) {
    return integer<T>("--seed", "S", "seed of the sample sequences", 0, 0xffffffffu,
                      [settings](auto& c) -> auto& { return settings(c).seed; });
}

// --camera, --look-from, --look-at, --up, --fov, --seed, --max-depth.
template <class T, class Settings>
std::vector<Flag<T>> pathFlags(Settings settings) {
    return {
        integer<T>("--camera", "I", "view through camera I, counting the scene's nodes with a camera in order", 0,
                   1u << 20,
                   STRATA_FIELD(view.camera)),
        flag<T>("--look-from", "X,Y,Z", "view from this point instead of the scene's camera; needs --look-at",
                [](T& c, const std::string& given, const std::string& v) { c.view.lookFrom = parsePoint(given, v); }),
        flag<T>("--look-at", "X,Y,Z", "the point the --look-from view looks at",
                [](T& c, const std::string& given, const std::string& v) { c.view.lookAt = parsePoint(given, v); }),
        flag<T>("--up", "X,Y,Z", "the up direction of the --look-from view",
                [](T& c, const std::string& given, const std::string& v) { c.view.up = parsePoint(given, v); })
            .withDefault("0,1,0"),
        flag<T>("--fov", "DEGREES", "vertical field of view, in (0, 179]",
                [](T& c, const std::string& given, const std::string& v) {
                    c.view.fovDegrees = float(parsePositive(given, v, 179.0, "degrees"));
                })
            .withDefault("the scene camera's, else 40"),
        seedFlag<T>(settings),
        integer<T>("--max-depth", "D",
                   "scattering events per path (pbrt's count): 0 shows emitters only, 1 is direct lighting", 0, 1024,
                   [settings](auto& c) -> auto& { return settings(c).maxDepth; }),
        flag<T>("--lens-radius", "R",
                "a thin lens of radius R (world units) for depth of field; 0 is a pinhole",
                [settings](T& c, const std::string& given, const std::string& v) {
                    const double r = parseFinite(given, v);
                    if (r < 0.0) badFlag(given + " must be 0 or more (a radius), got '" + v + "'");
                    settings(c).lensRadius = static_cast<float>(r);
                })
            .withDefault("0"),
        positive<T>("--focus-distance", "D", "the distance along the view direction that the lens keeps sharp",
                    1e30, "a distance", [settings](auto& c) -> auto& { return settings(c).focusDistance; })
            .withDefault("1"),
        integer<T>("--aperture-blades", "N", "a polygonal aperture of N blades (3 or more); 0 is round", 0, 64,
                   [settings](auto& c) -> auto& { return settings(c).apertureBlades; }),
        flag<T>("--shutter", "OPEN,CLOSE",
                "pose the scene by its animation at OPEN (seconds on its timeline); OPEN < CLOSE blurs the motion "
                "over the interval (a box shutter); without it the nodes keep their static transforms",
                [settings](T& c, const std::string& given, const std::string& v) {
                    const std::size_t comma = v.find(',');
                    if (comma == std::string::npos) badFlag(given + " takes OPEN,CLOSE (two times in seconds), got '" + v + "'");
                    const double open = parseFinite(given, v.substr(0, comma));
                    const double close = parseFinite(given, v.substr(comma + 1));
                    if (close < open) badFlag(given + ": CLOSE must not precede OPEN, got '" + v + "'");
                    settings(c).shutter = true;
                    settings(c).shutterOpen = open;
                    settings(c).shutterClose = close;
                }),
        text<T>("--animation", "NAME|INDEX", "the glTF animation --shutter plays (default: the first)",
                [settings](auto& c) -> auto& { return settings(c).animation; }),
        choice<T, LightSampler>("--light-sampler",
                                "how a light is chosen for each shadow ray: tree, the light tree over every "
                                "emitter (by bounds, power and orientation at the shading point), or power, in "
                                "proportion to estimated power alone; auto: the tree where the lights form 16 or more spatial "
                                "clusters",
                                {{"auto", LightSampler::Auto}, {"tree", LightSampler::Tree}, {"power", LightSampler::Power}},
                                [settings](auto& c) -> auto& { return settings(c).lightSampler; }),
        integer<T>("--light-candidates", "N",
                   "with the light tree: each shadow ray's light is one of N descents of the tree, kept in "
                   "proportion to its bound at the shading point over its probability (resampled importance "
                   "sampling); 1: one descent (default 2; not with --light-sampler power)",
                   1, 8, [settings](auto& c) -> auto& { return settings(c).lightCandidates; }),
        choice<T, bool>("--texture-lod",
                        "on: each texture lookup reads the mip level of its ray cone's footprint (one level or the "
                        "next at random, bilinear within it); off: every lookup at full resolution",
                        {{"on", true}, {"off", false}},
                        [settings](auto& c) -> auto& { return settings(c).textureLod; }),
        positive<T>("--noise-threshold", "T",
                    "adaptive sampling: an 8x8 block of pixels stops once each pixel's standard error is within T "
                    "of sqrt(mean^2 + 0.01) (its relMSE term within T^2), checked every 16 samples; --spp is the cap",
                    1e30, "a threshold", [settings](auto& c) -> auto& { return settings(c).noiseThreshold; })
            .withDefault("off"),
        integer<T>("--min-spp", "N", "adaptive sampling: no block stops before N samples (default 16)", 1, 1u << 30,
                   [settings](auto& c) -> auto& { return settings(c).minSpp; }),
    };
}

// --bvh, --bvh-stack, --reads (formerly --traversal), --integrator. The
// first three change how the scene is traversed and read, not the image:
// with `tuning` they are lab knobs, listed by --help-tuning (render), else
// in the help (bench, which measures them).
template <class T, class Settings>
std::vector<Flag<T>> traceFlags(Settings settings, bool tuning) {
    return {
        choice<T, int>("--bvh", "traverse the four-wide BVH, or the binary one it is collapsed from; the same hits",
                       {{"2", 2}, {"4", 4}}, [settings](auto& c) -> auto& { return settings(c).bvhWidth; })
            .inTuning(tuning),
        choice<T, BvhStack>("--bvh-stack",
                            "the four-wide traversal's stack: registers, or memory (an array, the children entered "
                            "nearest first); the same hits; auto: registers on CPU devices, memory elsewhere",
                            {{"auto", BvhStack::Auto},
                             {"registers", BvhStack::Registers},
                             {"memory", BvhStack::Memory}},
                            [settings](auto& c) -> auto& { return settings(c).bvhStack; })
            .inTuning(tuning),
        choice<T, ReadMode>("--reads",
                             "how the scene arrays are read: texel (the BVH through texel views, the rest through "
                             "storage buffers) or storage (every array through storage buffers); auto: every array "
                             "through texel views on CPU devices, storage buffers elsewhere, texel views for a scene "
                             "past the storage range",
                             {{"auto", ReadMode::Auto}, {"texel", ReadMode::Texel}, {"storage", ReadMode::Storage}},
                             [settings](auto& c) -> auto& { return settings(c).reads; })
            .withOldName("--traversal")
            .inTuning(tuning),
        choice<T, IntegratorKind>("--integrator",
                              "one pixel per invocation, its paths one after another (megakernel), or "
                              "stages with ray lists on the device (wavefront); the same image",
                              {{"megakernel", IntegratorKind::Megakernel}, {"wavefront", IntegratorKind::Wavefront}},
                              [settings](auto& c) -> auto& { return settings(c).integrator; }),
    };
}

// --env, --env-color, --env-intensity, --env-rotate (cmd.env).
template <class T>
std::vector<Flag<T>> envFlags() {
    return {
        text<T>("--env", "MAP.hdr|MAP.exr",
                "light the scene with an equirectangular map: +Y up, the image centre at -Z, u towards +X",
                STRATA_FIELD(env.file)),
        flag<T>("--env-color", "R,G,B",
                "light the scene with a constant radiance: three numbers in [0, 1e+30], not all 0; excludes --env",
                [](T& c, const std::string& given, const std::string& v) {
                    c.env.color = parseColor(given, v);
                    c.env.hasColor = true;
                }),
        positive<T>("--env-intensity", "S", "scale the radiance of --env or --env-color", 1e30, "a factor",
                    STRATA_FIELD(env.intensity)),
        finite<T>("--env-rotate", "DEGREES",
                  "turn the environment about +Y, counter-clockwise seen from above; any finite angle",
                  STRATA_FIELD(env.rotateDegrees)),
    };
}

// --variant (the scene's materials), --instancing (its meshes), --texture-max-size (its textures),
// --restrict-paths (its files).
template <class T>
std::vector<Flag<T>> sceneFlags() {
    return {text<T>("--variant", "NAME",
                    "give each primitive its material for this KHR_materials_variants variant; --stats lists them",
                    STRATA_FIELD(variant)),
            choice<T, Instancing>("--instancing",
                                  "a mesh placed by several nodes or by EXT_mesh_gpu_instancing: stored once and "
                                  "placed by instances (on), or flattened into world-space triangles (off); auto: "
                                  "instanced when its placements hold more than 2^20 triangles",
                                  {{"auto", Instancing::Auto}, {"on", Instancing::On}, {"off", Instancing::Off}},
                                  [](auto& c) -> auto& { return c.instancing; }),
            integer<T>("--texture-max-size", "N",
                       "halve each texture (in linear light for colour, normal maps renormalised) until neither "
                       "side exceeds N texels; --stats lists each texture's size and bytes",
                       1, 1 << 16, [](auto& c) -> auto& { return c.textureMaxSize; })
                .withDefault("none: every texture whole"),
            text<T>("--restrict-paths", "DIR",
                    "refuse a scene, an environment map, or a file the scene names that resolves (symlinks "
                    "followed) outside DIR: for rendering files from elsewhere",
                    STRATA_FIELD(restrictPaths))};
}

// --shader-cache DIR|off: where the compiled shader modules are kept
// (spirv/cache.h); process-wide, set as the flag is read.
template <class T>
Flag<T> shaderCacheFlag() {
    return flag<T>("--shader-cache", "DIR|off",
                   "keep the compiled shaders in DIR, or 'off' to compile them in memory only",
                   [](T&, const std::string& name, const std::string& v) {
                       if (v.empty()) badFlag(name + " needs a folder or 'off'");
                       spirv::setShaderCache(v);
                   })
        .withDefault("$XDG_CACHE_HOME/strata/shaders, else ~/.cache/strata/shaders");
}

// --device, --validation, --shader-cache.
template <class T>
std::vector<Flag<T>> deviceFlags() {
    return {
        integer<T>("--device", "I", "run on device I of 'strata devices'", 0, 1024, STRATA_FIELD(device))
            .withDefault("a discrete GPU, else an integrated one, else the CPU"),
        toggle<T>("--validation", "turn on the Vulkan validation layers, as STRATA_VALIDATION=1 does",
                  [](T& c) { c.validation = true; }),
        shaderCacheFlag<T>(),
    };
}

// -o, --output FILE, repeatable: a FILE.state goes to the command's states,
// any other to its images (render, merge).
template <class T>
Flag<T> outputFlag(std::string help) {
    return flag<T>("--output", "FILE", std::move(help),
                   [](T& c, const std::string&, const std::string& v) {
                       (lowerExtension(v) == ".state" ? c.states : c.outputs).push_back(v);
                   })
        .withAlias("-o");
}

template <class T>
CommandSpec<T> makeSpec(CommandText text, std::vector<Flag<T>> flags, T init = {}) {
    CommandSpec<T> spec;
    static_cast<CommandText&>(spec) = std::move(text);
    spec.flags = std::move(flags);
    spec.init = std::move(init);
    return spec;
}

template <class T, class Settings>
std::vector<Flag<T>> renderGroups(Settings settings) {
    return concat<T>({pixelFlags<T>(), pathFlags<T>(settings), traceFlags<T>(settings, true), envFlags<T>(),
                      sceneFlags<T>(), deviceFlags<T>()});
}

}  // namespace strata::cli
