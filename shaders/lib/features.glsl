// The scene's feature bits (kFeature*, shared/types.h) as a specialization
// constant: `if (hasFeature(kFeatureX))` folds to false, and the code under
// it disappears, for a scene without feature X.
//
// Larger features are also compiled out of the SPIR-V itself: each is an
// axis of the feature table (host/spirv/features.cpp) with a define, e.g.
// STRATA_LAYERS for the material layers (kFeaturesLayers), compiled in only
// for a scene with one, so the driver compiles the path tracer of a scene
// without them as it did before them.
#ifndef STRATA_LIB_FEATURES_GLSL
#define STRATA_LIB_FEATURES_GLSL

layout(constant_id = SPEC_FEATURES) const uint kFeatures = 0u;

bool hasFeature(uint bits) { return (kFeatures & bits) != 0u; }

#endif
