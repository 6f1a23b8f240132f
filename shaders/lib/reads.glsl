// How scene arrays are read (SPEC_TEXEL_FETCH, kReads* in shared/types.h):
// storage buffers, or RGBA32UI texel views over the same VkBuffers. Texel
// views are faster for divergent loads on lavapipe and reach
// maxTexelBufferElements texels (2 GiB there) where a storage descriptor
// reaches maxStorageBufferRange (128 MiB there).
#ifndef STRATA_LIB_READS_GLSL
#define STRATA_LIB_READS_GLSL

#include "shared/types.h"
#include "shared/bindings.h"

layout(constant_id = SPEC_TEXEL_FETCH) const uint kTexelFetch = kReadsStorage;
const bool kTexelBvh = kTexelFetch != kReadsStorage;  // nodes and triangle vertices
const bool kTexelAll = kTexelFetch == kReadsTexelAll; // every per-triangle array and the emitters

// Element i of an array of 3-texel or 5-texel elements: its texels. A
// decoder declares its array as `uvec4 t[k*Texels]` (shared/texel_layout.h),
// so a struct that changes size no longer compiles with the wrong one.
uvec4[3] texels3(usamplerBuffer view, uint i) {
    int base = int(3u * i);
    return uvec4[3](texelFetch(view, base), texelFetch(view, base + 1), texelFetch(view, base + 2));
}

uvec4[5] texels5(usamplerBuffer view, uint i) {
    int base = int(5u * i);
    return uvec4[5](texelFetch(view, base), texelFetch(view, base + 1), texelFetch(view, base + 2),
                    texelFetch(view, base + 3), texelFetch(view, base + 4));
}

// The field at word k (a k*Word* constant of shared/texel_layout.h, so the
// indices fold) of an element's texels t: a uint or float, or the vec3,
// vec4 or uvec4 that starts at word k (k % 4 == 0, asserted there).
#define TEXEL_UINT(t, k) (t)[(k) / kTexelWords][(k) % kTexelWords]
#define TEXEL_FLOAT(t, k) uintBitsToFloat(TEXEL_UINT(t, k))
#define TEXEL_UVEC4(t, k) (t)[(k) / kTexelWords]
#define TEXEL_VEC4(t, k) uintBitsToFloat(TEXEL_UVEC4(t, k))
#define TEXEL_VEC3(t, k) uintBitsToFloat(TEXEL_UVEC4(t, k).xyz)

#endif
