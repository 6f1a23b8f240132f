// The scene's feature bits (kFeature*, shared/types.h) as a specialization
// constant: `if (hasFeature(kFeatureX))` folds to false, and the code under
// it disappears, for a scene without feature X.
//
// The material layers (kFeaturesLayers: KHR_materials_clearcoat, _sheen and
// _specular's colour) are also compiled out of the SPIR-V itself unless
// STRATA_LAYERS is defined: the *_layers variants of the path tracers
// (integrate/kernels.cpp picks them for a scene with one), so the driver
// compiles the path tracer of a scene without them as it did before them.
#ifndef STRATA_LIB_FEATURES_GLSL
#define STRATA_LIB_FEATURES_GLSL

layout(constant_id = SPEC_FEATURES) const uint kFeatures = 0u;

bool hasFeature(uint bits) { return (kFeatures & bits) != 0u; }

#endif
