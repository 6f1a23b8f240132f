#include "spirv/features.h"

#include <stdexcept>

#include "../../shaders/shared/types.h"

namespace strata::spirv {
namespace {

constexpr std::uint32_t bit(KernelId k) { return 1u << static_cast<unsigned>(k); }

constexpr KernelInfo kKernels[] = {
    {KernelId::Pathtrace, "pathtrace", "pathtrace.comp"},
    {KernelId::Trace, "trace", "trace.comp"},
    {KernelId::Wavefront, "wavefront", "wavefront.comp"},
    {KernelId::SampleTest, "sample_test", "sample_test.comp"},
    {KernelId::DenoiseNfor, "denoise_nfor", "denoise/denoise_nfor.comp"},
    {KernelId::DenoiseSelect, "denoise_select", "denoise/denoise_select.comp"},
    {KernelId::DenoiseAtrous, "denoise_atrous", "denoise/denoise_atrous.comp"},
    {KernelId::DenoiseFeatures, "denoise_features", "denoise/denoise_features.comp"},
};
static_assert(std::size(kKernels) == kKernelCount);

constexpr std::uint32_t kTraversing = bit(KernelId::Pathtrace) | bit(KernelId::Trace);
constexpr std::uint32_t kShading = bit(KernelId::Pathtrace) | bit(KernelId::Wavefront);

// Axis indices, for implies and excludes.
enum : std::uint32_t { kBvh2 = 1u << 0, kBvh4m = 1u << 1, kLayers = 1u << 2, kInst = 1u << 4 };

// The table. The order is the order of the parts of a module's name and of
// its defines.
const Axis kAxes[] = {
    {"bvh2", "STRATA_BVH2", kTraversing, 0, kBvh4m, [](const VariantInputs& in) { return !in.wide; },
     "the BVH2 traversal: `--bvh 2`, or a four-wide tree deeper than the register stack",
     "the four-wide traversal instead (lib/bvh4.glsl)"},
    {"bvh4m", "STRATA_BVH4_MEMSTACK", kTraversing, 0, kBvh2,
     [](const VariantInputs& in) { return in.wide && in.memoryStack; },
     "the four-wide traversal's array stack: GPUs (`--bvh-stack auto`), `--bvh-stack memory`",
     "the register stack (lavapipe's fastest)"},
    {"layers", "STRATA_LAYERS", kShading, 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeaturesLayers) != 0u; },
     "a material with clearcoat, sheen, specular colour or iridescence (`kFeaturesLayers`)",
     "the layered BSDF's code (lib/bsdf.glsl, lib/bsdf_layers.glsl, lib/sheen.glsl): pipeline creation as without layers"},
    {"iridescence", "STRATA_IRIDESCENCE", kShading, kLayers, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureIridescence) != 0u; },
     "a KHR_materials_iridescence material (`kFeatureIridescence`)",
     "the thin film's Fresnel (lib/thin_film.glsl)"},
    {"inst", "STRATA_INSTANCING", kTraversing | bit(KernelId::Wavefront), 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureInstancing) != 0u; },
     "instanced meshes (`kFeatureInstancing`)",
     "the top level's loop and the instance transforms (lib/bvh.glsl, lib/scene.glsl)"},
    {"motion", "STRATA_MOTION", bit(KernelId::Pathtrace), 0, 0,
     [](const VariantInputs& in) { return in.cameraEffects; },
     "a lens (`--lens-radius`) or a shutter interval (`--shutter`, `--frames`)",
     "the ray time, the thin lens and the instance poses (lib/camera.glsl, lib/motion.glsl)"},
    {"aov", "STRATA_AOV", bit(KernelId::Pathtrace), 0, 0, [](const VariantInputs& in) { return in.aov; },
     "`--aov`, `--denoise`", "the AOV sums (lib/film.glsl `accumulateAov`)"},
    {"lighttree", "STRATA_LIGHT_TREE", bit(KernelId::Pathtrace) | bit(KernelId::Wavefront) | bit(KernelId::SampleTest), 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureLightTree) != 0u; },
     "lights chosen by the light tree (`kFeatureLightTree`: `--light-sampler tree`, or `auto` where the lights form 16 clusters or more)",
     "the tree's descent and probabilities (lib/light_tree.glsl): lights chosen by power alone"},
    {"texlod", "STRATA_TEXTURE_LOD", bit(KernelId::Pathtrace) | bit(KernelId::Wavefront), 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureTextureLod) != 0u; },
     "textures with mip chains (`kFeatureTextureLod`: `--texture-lod on`, the default, in a textured scene)",
     "the ray cones and the level choice (lib/material.glsl `textureLevel`): every lookup at full resolution"},
    {"movinglights", "STRATA_MOVING_LIGHTS", kShading, kInst, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureInstancedEmitters) != 0u; },
     "emitting meshes that move during the shutter (`kFeatureInstancedEmitters`)",
     "placing a light by its instance at the path's time (lib/lights.glsl `placeEmitter`)"},
    {"difftrans", "STRATA_DIFFUSE_TRANSMISSION", kShading | bit(KernelId::SampleTest), 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureDiffuseTransmission) != 0u; },
     "a KHR_materials_diffuse_transmission material (`kFeatureDiffuseTransmission`)",
     "the Lambertian transmission lobe (lib/bsdf.glsl)"},
    {"aniso", "STRATA_ANISOTROPY", kShading | bit(KernelId::SampleTest), 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureAnisotropy) != 0u; },
     "a KHR_materials_anisotropy material (`kFeatureAnisotropy`)",
     "the anisotropic GGX and its tangent frame (lib/ggx.glsl, lib/material.glsl)"},
    {"volscatter", "STRATA_VOLUME_SCATTER", kShading, 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureVolumeScatter) != 0u; },
     "a KHR_materials_volume_scatter material (`kFeatureVolumeScatter`)",
     "free flights, medium vertices and their phase function (lib/medium.glsl)"},
    {"dispersion", "STRATA_DISPERSION", kShading | bit(KernelId::SampleTest), 0, 0,
     [](const VariantInputs& in) { return (in.features & gpu::kFeatureDispersion) != 0u; },
     "a KHR_materials_dispersion material (`kFeatureDispersion`)",
     "the path's wavelength, its sampling and the spectral upsampling (lib/spectrum.glsl)"},
};

std::uint32_t kernelAxes(KernelId k) {
    std::uint32_t mask = 0;
    for (std::size_t i = 0; i < std::size(kAxes); ++i)
        if ((kAxes[i].kernelMask & bit(k)) != 0u) mask |= 1u << i;
    return mask;
}

// `axes` with what they imply.
std::uint32_t closure(std::uint32_t axes) {
    for (std::size_t i = 0; i < std::size(kAxes); ++i)
        if ((axes & (1u << i)) != 0u) axes |= kAxes[i].implies;
    return axes;
}

}  // namespace

std::span<const KernelInfo> kernels() { return kKernels; }

const KernelInfo& kernelInfo(KernelId id) { return kKernels[static_cast<unsigned>(id)]; }

std::span<const Axis> axes() { return kAxes; }

Variant chooseVariant(KernelId kernel, const VariantInputs& in) {
    Variant v{kernel, 0};
    const std::uint32_t applicable = kernelAxes(kernel);
    for (std::size_t i = 0; i < std::size(kAxes); ++i)
        if ((applicable & (1u << i)) != 0u && kAxes[i].detect(in)) v.axes |= 1u << i;
    v.axes = closure(v.axes);
    if (!allowed(v)) throw std::logic_error("spirv::chooseVariant: the table allows no " + variantName(v));
    return v;
}

std::string variantName(const Variant& v) {
    std::string name = kernelInfo(v.kernel).name;
    for (std::size_t i = 0; i < std::size(kAxes); ++i)
        if ((v.axes & (1u << i)) != 0u) name += std::string("_") + kAxes[i].name;
    return name;
}

std::vector<std::string> variantDefines(const Variant& v) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < std::size(kAxes); ++i) {
        if ((v.axes & (1u << i)) == 0u) continue;
        std::string list = kAxes[i].defines;
        for (std::size_t start = 0; start <= list.size();) {
            const std::size_t comma = std::min(list.find(',', start), list.size());
            out.push_back(list.substr(start, comma - start));
            start = comma + 1;
        }
    }
    return out;
}

bool allowed(const Variant& v) {
    if ((v.axes & ~kernelAxes(v.kernel)) != 0u) return false;
    if (closure(v.axes) != v.axes) return false;
    for (std::size_t i = 0; i < std::size(kAxes); ++i)
        if ((v.axes & (1u << i)) != 0u && (v.axes & kAxes[i].excludes) != 0u) return false;
    return true;
}

std::vector<Variant> allVariants() {
    std::vector<Variant> out;
    for (const KernelInfo& k : kKernels) {
        const std::uint32_t applicable = kernelAxes(k.id);
        // Every subset of the applicable axes, in increasing order.
        for (std::uint32_t s = 0;; s = (s - applicable) & applicable) {
            if (allowed({k.id, s})) out.push_back({k.id, s});
            if (s == applicable) break;
        }
    }
    return out;
}

std::vector<Variant> coveringVariants() {
    std::vector<Variant> out;
    auto add = [&](Variant v) {
        for (const Variant& o : out)
            if (o == v) return;
        out.push_back(v);
    };
    for (const KernelInfo& k : kKernels) {
        const std::uint32_t applicable = kernelAxes(k.id);
        add({k.id, 0});
        std::uint32_t all = 0;
        for (std::size_t i = 0; i < std::size(kAxes); ++i) {
            if ((applicable & (1u << i)) == 0u) continue;
            add({k.id, closure(1u << i)});
            if ((all & kAxes[i].excludes) == 0u) all |= 1u << i;
        }
        add({k.id, closure(all)});
    }
    return out;
}

std::string featureTableMarkdown() {
    std::string t = "| axis | define | kernels | compiled in for | what a render without it saves |\n"
                    "|---|---|---|---|---|\n";
    for (const Axis& a : kAxes) {
        std::string ks;
        for (const KernelInfo& k : kKernels)
            if ((a.kernelMask & bit(k.id)) != 0u) ks += (ks.empty() ? "" : ", ") + std::string(k.name);
        std::string defines = a.defines;
        for (std::size_t p = 0; (p = defines.find(',', p)) != std::string::npos; p += 2) defines.replace(p, 1, ", ");
        t += "| `" + std::string(a.name) + "` | " + defines + " | " + ks + " | " + a.detectedBy + " | " + a.whenOff +
             " |\n";
    }
    return t;
}

}  // namespace strata::spirv
