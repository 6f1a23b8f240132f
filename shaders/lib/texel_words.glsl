// The packed texel words (BINDING_TEXELS, an R32UI texel view): every
// texture's texels (lib/textures.glsl) and, first when the scene has
// kFeatureSheen, the sheen albedo table (lib/sheen.glsl; pack/textures.cpp
// lays them out).
#ifndef STRATA_LIB_TEXEL_WORDS_GLSL
#define STRATA_LIB_TEXEL_WORDS_GLSL

#include "shared/bindings.h"

layout(set = 0, binding = BINDING_TEXELS) uniform usamplerBuffer texelWords;

#endif
