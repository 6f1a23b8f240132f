// The scene's feature bits (kFeature*, shared/types.h) as a specialization
// constant: `if (hasFeature(kFeatureX))` folds to false, and the code under
// it disappears, for a scene without feature X.
#ifndef STRATA_LIB_FEATURES_GLSL
#define STRATA_LIB_FEATURES_GLSL

layout(constant_id = SPEC_FEATURES) const uint kFeatures = 0u;

bool hasFeature(uint bits) { return (kFeatures & bits) != 0u; }

#endif
