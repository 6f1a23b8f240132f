// The emitter buffer (Emitter[], shared/types.h) and emitterAt(), which reads
// it through its RGBA32UI texel view (shared/texel_layout.h) with kTexelAll.
// Its decoder has the shape of lib/scene.glsl's sceneMaterial: each names
// its own struct's fields and words.
#ifndef STRATA_LIB_EMITTERS_GLSL
#define STRATA_LIB_EMITTERS_GLSL

#include "lib/reads.glsl"

layout(std430, set = 0, binding = BINDING_EMITTERS) readonly buffer EmitterBuffer { Emitter emitters[]; };
layout(set = 0, binding = BINDING_EMITTERS_TEXEL) uniform usamplerBuffer emittersTexel;

Emitter emitterAt(uint i) {
    if (kTexelAll) {
        uvec4 t[kEmitterTexels] = texels5(emittersTexel, i);
        return Emitter(TEXEL_VEC3(t, kEmitterWordV0), TEXEL_UINT(t, kEmitterWordTriangle),
                       TEXEL_VEC3(t, kEmitterWordE1), TEXEL_FLOAT(t, kEmitterWordArea),
                       TEXEL_VEC3(t, kEmitterWordE2), TEXEL_FLOAT(t, kEmitterWordPmf),
                       TEXEL_VEC3(t, kEmitterWordRadiance), TEXEL_UINT(t, kEmitterWordFlags),
                       TEXEL_FLOAT(t, kEmitterWordAliasProb), TEXEL_UINT(t, kEmitterWordAlias),
                       TEXEL_UINT(t, kEmitterWordKind), TEXEL_UINT(t, kEmitterWordTrail));
    }
    return emitters[i];
}

#endif
