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
layout(std430, set = 0, binding = BINDING_COLORS) readonly buffer ColorBuffer { TriColors colors[]; };
layout(set = 0, binding = BINDING_COLORS_TEXEL) uniform usamplerBuffer colorsTexel;
#ifdef STRATA_INSTANCING
layout(std430, set = 0, binding = BINDING_INSTANCES) readonly buffer InstanceBuffer { uvec4 instanceWords[]; };
layout(set = 0, binding = BINDING_INSTANCES_TEXEL) uniform usamplerBuffer instancesTexel;
#endif

uvec4 bvhNodeWord(uint index) {
    return kTexelBvh ? texelFetch(nodesTexel, int(index)) : nodeWords[index];
}

// The decoders below read fields at the words of shared/texel_layout.h.
// A BvhNode from its two texels (the scene's BVH2 and the top level).
BvhNode bvhNodeFromTexels(uvec4 t[kBvhNodeTexels]) {
    return BvhNode(TEXEL_VEC3(t, kBvhNodeWordBmin), TEXEL_UINT(t, kBvhNodeWordLeftOrFirst),
                   TEXEL_VEC3(t, kBvhNodeWordBmax), TEXEL_UINT(t, kBvhNodeWordCount));
}

BvhNode bvhFetchNode(uint index) {
    uint base = kBvhNodeTexels * index;
    return bvhNodeFromTexels(uvec4[](bvhNodeWord(base), bvhNodeWord(base + 1u)));
}

BvhNode4 bvhFetchNode4(uint index) {
    uint base = kBvhNode4Texels * index;
    uvec4 t[kBvhNode4Texels] = uvec4[](bvhNodeWord(base), bvhNodeWord(base + 1u), bvhNodeWord(base + 2u),
                                       bvhNodeWord(base + 3u), bvhNodeWord(base + 4u), bvhNodeWord(base + 5u),
                                       bvhNodeWord(base + 6u));
    return BvhNode4(TEXEL_VEC4(t, kBvhNode4WordMinX), TEXEL_VEC4(t, kBvhNode4WordMaxX),
                    TEXEL_VEC4(t, kBvhNode4WordMinY), TEXEL_VEC4(t, kBvhNode4WordMaxY),
                    TEXEL_VEC4(t, kBvhNode4WordMinZ), TEXEL_VEC4(t, kBvhNode4WordMaxZ),
                    TEXEL_UVEC4(t, kBvhNode4WordChild));
}

TriVerts bvhFetchTri(uint index) {
    if (kTexelBvh) {
        uvec4 t[kTriVertsTexels] = texels3(trisTexel, index);
        return TriVerts(TEXEL_VEC4(t, kTriVertsWordV0), TEXEL_VEC4(t, kTriVertsWordV1), TEXEL_VEC4(t, kTriVertsWordV2));
    }
    return tris[index];
}

#ifdef STRATA_INSTANCING
// The instances array (kFeatureInstancing; shared/types.h, Instance): the
// top-level BVH2's nodes, then the records.
uvec4 instanceWord(uint index) {
    return kTexelBvh ? texelFetch(instancesTexel, int(index)) : instanceWords[index];
}

BvhNode bvhFetchTopNode(uint index) {
    uint base = kBvhNodeTexels * index;
    return bvhNodeFromTexels(uvec4[](instanceWord(base), instanceWord(base + 1u)));
}

// The record starting at texel `first`: the two transforms' rows and the
// roots (with STRATA_MOTION a moving instance's rows at the path's time:
// lib/motion.glsl).
#ifdef STRATA_MOTION
#include "lib/motion.glsl"
#else
vec4 instanceRow(uint first, uint row) { return uintBitsToFloat(instanceWord(first + row)); }
#endif
uint instanceRoot(uint first) {
    uvec4 t = instanceWord(first + kInstanceWordRoot4 / kTexelWords);
#ifdef STRATA_BVH2
    return t[kInstanceWordRoot2 % kTexelWords];
#else
    return t[kInstanceWordRoot4 % kTexelWords];
#endif
}
vec3 rowsPoint(vec4 r0, vec4 r1, vec4 r2, vec3 p) {
    return vec3(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
}
vec3 rowsVector(vec4 r0, vec4 r1, vec4 r2, vec3 v) { return vec3(dot(r0.xyz, v), dot(r1.xyz, v), dot(r2.xyz, v)); }

// The instance of the hit being shaded (its record's first texel), or
// kNoInstance: the shading reads below give its triangle in world space.
uint gInstance = kNoInstance;

#endif

// Per-triangle arrays in BVH order, through texel views with kTexelAll.
TriShading sceneShading(uint triangle) {
    if (kTexelAll) {
        uvec4 t[kTriShadingTexels] = texels3(shadingTexel, triangle);
        return TriShading(TEXEL_VEC3(t, kTriShadingWordN0), TEXEL_UINT(t, kTriShadingWordMaterial),
                          TEXEL_VEC3(t, kTriShadingWordN1), TEXEL_UINT(t, kTriShadingWordLight),
                          TEXEL_VEC3(t, kTriShadingWordN2), TEXEL_UINT(t, kTriShadingWordPad0));
    }
    return shading[triangle];
}

// The per-triangle arrays of one vec4 per vertex (Type: TriTexcoords,
// TriTangents, TriColors; its words kType##Word##W0..W2 in texel_layout.h):
// `array` from storage, or through `view` with kTexelAll.
#define STRATA_TRI_VEC4_READER(Type, fn, array, view, W0, W1, W2)                                  \
    Type fn(uint triangle) {                                                                   \
        if (!kTexelAll) return array[triangle];                                                \
        uvec4 t[k##Type##Texels] = texels3(view, triangle);                                    \
        return Type(TEXEL_VEC4(t, k##Type##Word##W0), TEXEL_VEC4(t, k##Type##Word##W1),        \
                    TEXEL_VEC4(t, k##Type##Word##W2));                                         \
    }
STRATA_TRI_VEC4_READER(TriTexcoords, sceneTexcoords, texcoords, texcoordsTexel, Uv0, Uv1, Uv2)
STRATA_TRI_VEC4_READER(TriTangents, sceneTangents, tangents, tangentsTexel, T0, T1, T2)
STRATA_TRI_VEC4_READER(TriColors, sceneColors, colors, colorsTexel, C0, C1, C2)
#undef STRATA_TRI_VEC4_READER

// materials[i], through its RGBA32UI texel view with kTexelAll: on lavapipe
// a storage-buffer load with a different index per lane is a loop over the
// lanes for each of the struct's words. (lib/emitters.glsl's emitterAt has
// the same shape for its own struct.)
Material sceneMaterial(uint i) {
    if (!kTexelAll) return materials[i];
    // The texels of an extension only when a material of the scene has it
    // (volume: the sixth; clearcoat: the seventh and eighth; sheen: the
    // eighth and ninth; specular colour: the tenth and eleventh; iridescence:
    // the eleventh and twelfth; diffuse transmission: the thirteenth and
    // fourteenth; anisotropy and dispersion: the fifteenth; volume
    // scattering: the sixteenth). The last four are in the module only with
    // their axes (difftrans, aniso, dispersion, volscatter): without them the
    // decoder is the twelve- or fifteen-texel one, their fields constants.
    int base = int(kMaterialTexels * i);
#if defined(STRATA_VOLUME_SCATTER)
    uvec4 t[16] = uvec4[16](
#elif defined(STRATA_DIFFUSE_TRANSMISSION) || defined(STRATA_ANISOTROPY) || defined(STRATA_DISPERSION)
    uvec4 t[15] = uvec4[15](
#else
    uvec4 t[12] = uvec4[12](
#endif
        texelFetch(materialsTexel, base), texelFetch(materialsTexel, base + 1), texelFetch(materialsTexel, base + 2),
        texelFetch(materialsTexel, base + 3), texelFetch(materialsTexel, base + 4),
        hasFeature(kFeatureVolume) ? texelFetch(materialsTexel, base + 5) : uvec4(0u),
        hasFeature(kFeatureClearcoat) ? texelFetch(materialsTexel, base + 6) : uvec4(0u),
        hasFeature(kFeatureClearcoat | kFeatureSheen) ? texelFetch(materialsTexel, base + 7) : uvec4(0u),
        hasFeature(kFeatureSheen) ? texelFetch(materialsTexel, base + 8) : uvec4(0u),
        hasFeature(kFeatureSpecularColor) ? texelFetch(materialsTexel, base + 9) : uvec4(0u),
        hasFeature(kFeatureSpecularColor | kFeatureIridescence) ? texelFetch(materialsTexel, base + 10) : uvec4(0u),
        hasFeature(kFeatureIridescence) ? texelFetch(materialsTexel, base + 11) : uvec4(0u)
#if defined(STRATA_DIFFUSE_TRANSMISSION) || defined(STRATA_ANISOTROPY) || defined(STRATA_VOLUME_SCATTER) || \
    defined(STRATA_DISPERSION)
        , hasFeature(kFeatureDiffuseTransmission) ? texelFetch(materialsTexel, base + 12) : uvec4(0u),
        hasFeature(kFeatureDiffuseTransmission) ? texelFetch(materialsTexel, base + 13) : uvec4(0u),
        hasFeature(kFeatureAnisotropy | kFeatureDispersion) ? texelFetch(materialsTexel, base + 14) : uvec4(0u)
#endif
#if defined(STRATA_VOLUME_SCATTER)
        , hasFeature(kFeatureVolumeScatter) ? texelFetch(materialsTexel, base + 15) : uvec4(0u)
#endif
    );
    return Material(TEXEL_VEC4(t, kMaterialWordBaseColor), TEXEL_VEC3(t, kMaterialWordEmission),
                    TEXEL_FLOAT(t, kMaterialWordMetallic), TEXEL_FLOAT(t, kMaterialWordRoughness),
                    TEXEL_FLOAT(t, kMaterialWordIor), TEXEL_UINT(t, kMaterialWordFlags),
                    TEXEL_FLOAT(t, kMaterialWordAlphaCutoff), TEXEL_FLOAT(t, kMaterialWordTransmission),
                    TEXEL_FLOAT(t, kMaterialWordSpecular), TEXEL_FLOAT(t, kMaterialWordNormalScale),
                    TEXEL_UINT(t, kMaterialWordBaseColorTex), TEXEL_UINT(t, kMaterialWordMetallicRoughnessTex),
                    TEXEL_UINT(t, kMaterialWordNormalTex), TEXEL_UINT(t, kMaterialWordEmissiveTex),
                    TEXEL_UINT(t, kMaterialWordTransmissionTex), TEXEL_VEC3(t, kMaterialWordAttenuation),
                    TEXEL_FLOAT(t, kMaterialWordThickness), TEXEL_FLOAT(t, kMaterialWordClearcoat),
                    TEXEL_FLOAT(t, kMaterialWordClearcoatRoughness), TEXEL_UINT(t, kMaterialWordClearcoatTex),
                    TEXEL_UINT(t, kMaterialWordClearcoatRoughnessTex), TEXEL_UINT(t, kMaterialWordClearcoatNormalTex),
                    TEXEL_FLOAT(t, kMaterialWordClearcoatNormalScale), TEXEL_FLOAT(t, kMaterialWordSheenRoughness),
                    TEXEL_UINT(t, kMaterialWordSheenRoughnessTex), TEXEL_VEC3(t, kMaterialWordSheenColor),
                    TEXEL_UINT(t, kMaterialWordSheenColorTex), TEXEL_VEC3(t, kMaterialWordSpecularColor),
                    TEXEL_UINT(t, kMaterialWordSpecularColorTex), TEXEL_UINT(t, kMaterialWordSpecularTex),
                    TEXEL_FLOAT(t, kMaterialWordIridescence), TEXEL_FLOAT(t, kMaterialWordIridescenceIor),
                    TEXEL_UINT(t, kMaterialWordIridescenceTex), TEXEL_FLOAT(t, kMaterialWordIridescenceThicknessMin),
                    TEXEL_FLOAT(t, kMaterialWordIridescenceThicknessMax),
                    TEXEL_UINT(t, kMaterialWordIridescenceThicknessTex), TEXEL_UINT(t, kMaterialWordPad0),
#if defined(STRATA_DIFFUSE_TRANSMISSION) || defined(STRATA_ANISOTROPY) || defined(STRATA_VOLUME_SCATTER) || \
    defined(STRATA_DISPERSION)
                    TEXEL_VEC3(t, kMaterialWordDiffuseTransmissionColor),
                    TEXEL_FLOAT(t, kMaterialWordDiffuseTransmission),
                    TEXEL_UINT(t, kMaterialWordDiffuseTransmissionTex),
                    TEXEL_UINT(t, kMaterialWordDiffuseTransmissionColorTex), TEXEL_UINT(t, kMaterialWordPad1),
                    TEXEL_UINT(t, kMaterialWordPad2), TEXEL_FLOAT(t, kMaterialWordAnisotropyStrength),
                    TEXEL_FLOAT(t, kMaterialWordAnisotropyRotation), TEXEL_UINT(t, kMaterialWordAnisotropyTex),
                    TEXEL_FLOAT(t, kMaterialWordDispersion),
#else
                    vec3(0.0), 0.0, kNoTexture, kNoTexture, 0u, 0u, 0.0, 0.0, kNoTexture, 0.0,
#endif
#if defined(STRATA_VOLUME_SCATTER)
                    TEXEL_VEC3(t, kMaterialWordScatterAlbedo), TEXEL_FLOAT(t, kMaterialWordScatterAnisotropy)
#else
                    vec3(0.0), 0.0
#endif
    );
}

#include "lib/sampling.glsl"

#ifdef STRATA_INSTANCING
// Triangle `triangle` of the hit being shaded in world space: its vertices
// (by objectToWorld), vertex normals (by the inverse transpose: worldToObject's
// rows as columns) and tangents (by objectToWorld's linear part); for no
// instance (kNoInstance), the arrays as stored.
TriVerts shadeTri(uint triangle) {
    TriVerts tv = bvhFetchTri(triangle);
    if (gInstance == kNoInstance) return tv;
    vec4 r0 = instanceRow(gInstance, 3u), r1 = instanceRow(gInstance, 4u), r2 = instanceRow(gInstance, 5u);
    return TriVerts(vec4(rowsPoint(r0, r1, r2, tv.v0.xyz), 0.0), vec4(rowsPoint(r0, r1, r2, tv.v1.xyz), 0.0),
                    vec4(rowsPoint(r0, r1, r2, tv.v2.xyz), 0.0));
}

TriShading shadeShading(uint triangle) {
    TriShading sh = sceneShading(triangle);
    if (gInstance == kNoInstance) return sh;
    // The normal matrix is worldToObject's linear part transposed: its rows
    // as columns, which is what mat3() takes.
    mat3 normalMatrix = mat3(instanceRow(gInstance, 0u).xyz, instanceRow(gInstance, 1u).xyz,
                             instanceRow(gInstance, 2u).xyz);
    sh.n0 = normalize(normalMatrix * sh.n0);
    sh.n1 = normalize(normalMatrix * sh.n1);
    sh.n2 = normalize(normalMatrix * sh.n2);
    return sh;
}

TriTangents shadeTangents(uint triangle) {
    TriTangents tg = sceneTangents(triangle);
    if (gInstance == kNoInstance) return tg;
    vec4 r0 = instanceRow(gInstance, 3u), r1 = instanceRow(gInstance, 4u), r2 = instanceRow(gInstance, 5u);
    tg.t0.xyz = rowsVector(r0, r1, r2, tg.t0.xyz);
    tg.t1.xyz = rowsVector(r0, r1, r2, tg.t1.xyz);
    tg.t2.xyz = rowsVector(r0, r1, r2, tg.t2.xyz);
    return tg;
}

// What an instance's transforms add to the rounding error of a point on its
// triangle (spawnOrigin): the vertices' rounding to world space and a ray's
// origin's rounding back to object space, each gamma(3) of the terms'
// magnitudes, counted with a margin.
vec3 shadeSpawnError(TriVerts objectTri) {
    if (gInstance == kNoInstance) return vec3(0.0);
    vec4 r0 = instanceRow(gInstance, 3u), r1 = instanceRow(gInstance, 4u), r2 = instanceRow(gInstance, 5u);
    vec3 m = max(abs(objectTri.v0.xyz), max(abs(objectTri.v1.xyz), abs(objectTri.v2.xyz)));
    vec3 mag = vec3(dot(abs(r0.xyz), m) + abs(r0.w), dot(abs(r1.xyz), m) + abs(r1.w), dot(abs(r2.xyz), m) + abs(r2.w));
    return 4.0 * kGamma7 * mag;
}
#else
// Without instancing every triangle is stored in world space.
#define shadeTri bvhFetchTri
#define shadeShading sceneShading
#define shadeTangents sceneTangents
#endif

#include "lib/material.glsl"

// The alpha test of lib/bvh.glsl (compiled in when kFeatureAlphaTest is set).
uint bvhRayHash(vec3 origin, vec3 dir) { return alphaRayHash(origin, dir); }
bool bvhIsHole(uint triangle, float u, float v, uint rayHash) { return alphaHole(triangle, vec2(u, v), rayHash); }

#include "lib/bvh.glsl"

#endif
