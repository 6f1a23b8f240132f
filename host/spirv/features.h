// The shader feature table: every axis along which a kernel's SPIR-V is
// compiled with or without a part of its GLSL (a define), what picks it for
// a render, and what it costs when it is off. Everything else derives from
// this one list: the modules a render compiles (spirv/cache.h), the host's
// choice of module (integrate/kernels.cpp), the modules the tests validate
// (tests/test_spirv.cpp) and the table in docs/architecture.md (checked
// against featureTableMarkdown() by a test). Adding an axis is one entry in
// kAxes (features.cpp) plus its GLSL under #ifdef.
//
// Choices that only fold code away (the scene's kFeature* bits, the
// sampler, the MIS mode, ...) are specialization constants instead
// (lib/features.glsl, shared/bindings.h): no axis, no new module.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace strata::spirv {

// The compute shaders (shaders/*.comp). Each is one kernel; its variants
// are its axes' combinations.
enum class KernelId : std::uint8_t {
    Pathtrace,        // pathtrace.comp: the megakernel
    Trace,            // trace.comp: one ray in, one hit out
    Wavefront,        // wavefront.comp: the wavefront integrator's stages
    SampleTest,       // sample_test.comp: the sampling routines (chi-square tests)
    DenoiseNfor,      // denoise/denoise_nfor.comp
    DenoiseSelect,    // denoise/denoise_select.comp
    DenoiseAtrous,    // denoise/denoise_atrous.comp
    DenoiseFeatures,  // denoise/denoise_features.comp
};
inline constexpr int kKernelCount = 8;

struct KernelInfo {
    KernelId id;
    const char* name;    // the module name's first part
    const char* source;  // path under shaders/
};
std::span<const KernelInfo> kernels();
const KernelInfo& kernelInfo(KernelId id);

// What a module is chosen from: the uploaded scene's traversal and feature
// bits, and the render's settings (integrate/kernels.cpp fills it in).
struct VariantInputs {
    std::uint32_t features = 0;  // gpu::kFeature* (SceneFeatures::bits)
    bool wide = true;            // the four-wide BVH (DeviceScene::wide); else the BVH2
    bool memoryStack = false;    // with `wide`: the array stack (DeviceScene::memoryStack)
    bool aov = false;            // --aov (RenderSettings::aov)
    bool cameraEffects = false;  // a lens or a shutter interval (RenderSettings::cameraEffects)
};

// One axis: a define compiled into the kernels of `kernelMask` when
// `detect` holds.
struct Axis {
    const char* name;         // in module names: pathtrace_bvh2_layers_inst
    const char* defines;      // -D names, comma-separated
    std::uint32_t kernelMask; // 1 << KernelId
    std::uint32_t implies;    // other axes (1 << index) always on with this one
    std::uint32_t excludes;   // axes never on with this one
    bool (*detect)(const VariantInputs&);
    const char* detectedBy;   // for the docs: what turns it on
    const char* whenOff;      // for the docs: what a render without it saves
};
std::span<const Axis> axes();

// A module: a kernel and the axes compiled into it (1 << axis index).
struct Variant {
    KernelId kernel = KernelId::Pathtrace;
    std::uint32_t axes = 0;
    bool operator==(const Variant&) const = default;
};

// The module for `kernel` with these inputs: every axis of the kernel whose
// detect holds, with the axes they imply.
Variant chooseVariant(KernelId kernel, const VariantInputs& in);
// kernel name, then each axis's name in table order: "pathtrace_bvh2_inst".
std::string variantName(const Variant& v);
// The -D names of the variant's axes, in table order.
std::vector<std::string> variantDefines(const Variant& v);
// Whether the table allows the combination (its axes apply to the kernel,
// implied axes present, no excluded pair).
bool allowed(const Variant& v);
// Every combination the table allows, for every kernel (what `strata
// shaders --all` compiles).
std::vector<Variant> allVariants();
// Per kernel: no axis, each axis alone (with what it implies), and every
// axis at once where the table allows (one of each excluded pair): the
// modules the tests validate, linear in the number of axes.
std::vector<Variant> coveringVariants();

// The table as Markdown (docs/architecture.md holds it verbatim).
std::string featureTableMarkdown();

}  // namespace strata::spirv
