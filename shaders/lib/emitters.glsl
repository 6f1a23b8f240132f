// The emitter buffer (Emitter[], shared/types.h) and emitterAt(), which reads
// it through its RGBA32UI texel view (five texels per emitter) with kTexelAll.
#ifndef STRATA_LIB_EMITTERS_GLSL
#define STRATA_LIB_EMITTERS_GLSL

#include "lib/reads.glsl"

layout(std430, set = 0, binding = BINDING_EMITTERS) readonly buffer EmitterBuffer { Emitter emitters[]; };
layout(set = 0, binding = BINDING_EMITTERS_TEXEL) uniform usamplerBuffer emittersTexel;

Emitter emitterAt(uint i) {
    if (kTexelAll) {
        int base = int(5u * i);
        uvec4 a = texelFetch(emittersTexel, base), b = texelFetch(emittersTexel, base + 1),
              c = texelFetch(emittersTexel, base + 2), d = texelFetch(emittersTexel, base + 3),
              e = texelFetch(emittersTexel, base + 4);
        return Emitter(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), uintBitsToFloat(b.w),
                       uintBitsToFloat(c.xyz), uintBitsToFloat(c.w), uintBitsToFloat(d.xyz), d.w,
                       uintBitsToFloat(e.x), e.y, e.z, e.w);
    }
    return emitters[i];
}

#endif
