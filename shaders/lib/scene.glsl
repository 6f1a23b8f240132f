// Scene buffers of descriptor set 0, the fetch functions and alpha test the
// BVH traversal uses. SPEC_TEXEL_FETCH (lib/reads.glsl) picks texel-view reads
// (fast on lavapipe, where a divergent storage-buffer load becomes a scalar
// loop; and the only way past maxStorageBufferRange) or storage reads.
#ifndef STRATA_LIB_SCENE_GLSL
#define STRATA_LIB_SCENE_GLSL

#include "shared/types.h"
#include "shared/bindings.h"
#include "lib/reads.glsl"

layout(constant_id = SPEC_BVH_REGS) const uint kBvhRegs = 16u;
#include "lib/features.glsl"

layout(std430, set = 0, binding = BINDING_NODES) readonly buffer NodeBuffer { uvec4 nodeWords[]; };
layout(std430, set = 0, binding = BINDING_TRIS) readonly buffer TriBuffer { TriVerts tris[]; };
layout(set = 0, binding = BINDING_NODES_TEXEL) uniform usamplerBuffer nodesTexel;
layout(set = 0, binding = BINDING_TRIS_TEXEL) uniform usamplerBuffer trisTexel;
layout(std430, set = 0, binding = BINDING_SHADING) readonly buffer ShadingBuffer { TriShading shading[]; };
layout(set = 0, binding = BINDING_SHADING_TEXEL) uniform usamplerBuffer shadingTexel;
layout(std430, set = 0, binding = BINDING_MATERIALS) readonly buffer MaterialBuffer { Material materials[]; };
layout(set = 0, binding = BINDING_MATERIALS_TEXEL) uniform usamplerBuffer materialsTexel;
layout(std430, set = 0, binding = BINDING_TEXCOORDS) readonly buffer TexcoordBuffer { TriTexcoords texcoords[]; };
layout(set = 0, binding = BINDING_TEXCOORDS_TEXEL) uniform usamplerBuffer texcoordsTexel;
layout(std430, set = 0, binding = BINDING_TANGENTS) readonly buffer TangentBuffer { TriTangents tangents[]; };
layout(set = 0, binding = BINDING_TANGENTS_TEXEL) uniform usamplerBuffer tangentsTexel;

uvec4 bvhNodeWord(uint index) {
    return kTexelBvh ? texelFetch(nodesTexel, int(index)) : nodeWords[index];
}

BvhNode bvhFetchNode(uint index) {
    uvec4 a = bvhNodeWord(2u * index);
    uvec4 b = bvhNodeWord(2u * index + 1u);
    return BvhNode(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w);
}

BvhNode4 bvhFetchNode4(uint index) {
    uint base = 7u * index;
    return BvhNode4(uintBitsToFloat(bvhNodeWord(base)), uintBitsToFloat(bvhNodeWord(base + 1u)),
                    uintBitsToFloat(bvhNodeWord(base + 2u)), uintBitsToFloat(bvhNodeWord(base + 3u)),
                    uintBitsToFloat(bvhNodeWord(base + 4u)), uintBitsToFloat(bvhNodeWord(base + 5u)),
                    bvhNodeWord(base + 6u));
}

TriVerts bvhFetchTri(uint index) {
    if (kTexelBvh) {
        uvec4 a, b, c;
        texels3(trisTexel, index, a, b, c);
        return TriVerts(uintBitsToFloat(a), uintBitsToFloat(b), uintBitsToFloat(c));
    }
    return tris[index];
}

// Per-triangle arrays in BVH order, through texel views with kTexelAll.
TriShading sceneShading(uint triangle) {
    if (kTexelAll) {
        uvec4 a, b, c;
        texels3(shadingTexel, triangle, a, b, c);
        return TriShading(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w, uintBitsToFloat(c.xyz), c.w);
    }
    return shading[triangle];
}

TriTexcoords sceneTexcoords(uint triangle) {
    if (!kTexelAll) return texcoords[triangle];
    uvec4 a, b, c;
    texels3(texcoordsTexel, triangle, a, b, c);
    return TriTexcoords(uintBitsToFloat(a), uintBitsToFloat(b), uintBitsToFloat(c));
}

TriTangents sceneTangents(uint triangle) {
    if (!kTexelAll) return tangents[triangle];
    uvec4 a, b, c;
    texels3(tangentsTexel, triangle, a, b, c);
    return TriTangents(uintBitsToFloat(a), uintBitsToFloat(b), uintBitsToFloat(c));
}

// materials[i], through its RGBA32UI texel view (five texels) with kTexelAll:
// on lavapipe a storage-buffer load with a different index per lane is a
// loop over the lanes for each of the struct's 20 words.
Material sceneMaterial(uint i) {
    if (!kTexelAll) return materials[i];
    int base = int(5u * i);
    uvec4 a = texelFetch(materialsTexel, base), b = texelFetch(materialsTexel, base + 1),
          c = texelFetch(materialsTexel, base + 2), d = texelFetch(materialsTexel, base + 3),
          e = texelFetch(materialsTexel, base + 4);
    return Material(uintBitsToFloat(a), uintBitsToFloat(b.xyz), uintBitsToFloat(b.w), uintBitsToFloat(c.x),
                    uintBitsToFloat(c.y), c.z, uintBitsToFloat(c.w), uintBitsToFloat(d.x), uintBitsToFloat(d.y),
                    uintBitsToFloat(d.z), d.w, e.x, e.y, e.z, e.w);
}

#include "lib/sampling.glsl"
#include "lib/material.glsl"

// The alpha test of lib/bvh.glsl (compiled in when kFeatureAlphaTest is set).
uint bvhRayHash(vec3 origin, vec3 dir) { return alphaRayHash(origin, dir); }
bool bvhIsHole(uint triangle, float u, float v, uint rayHash) { return alphaHole(triangle, vec2(u, v), rayHash); }

#include "lib/bvh.glsl"

#endif
