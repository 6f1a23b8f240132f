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

// Element i of an array of 48-byte elements: its three RGBA32 texels.
void texels3(usamplerBuffer view, uint i, out uvec4 a, out uvec4 b, out uvec4 c) {
    int base = int(3u * i);
    a = texelFetch(view, base);
    b = texelFetch(view, base + 1);
    c = texelFetch(view, base + 2);
}

#endif
