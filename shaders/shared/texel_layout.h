// How the shaders decode the structs of types.h from RGBA32UI texel views
// (lib/scene.glsl, lib/emitters.glsl, lib/textures.glsl): texels per element
// (k*Texels, 16 bytes each) and each field's first 32-bit word in the struct
// (k*Word*; word k is component k % 4 of texel k / 4). A vec3 or vec4 field
// starts a texel. The C++ side asserts every figure against the struct, so a
// struct reordered or resized without its decoder does not compile.
// Included at the end of types.h.
#ifndef STRATA_SHARED_TEXEL_LAYOUT_H
#define STRATA_SHARED_TEXEL_LAYOUT_H

#include "types.h"

#ifdef __cplusplus
#include <cstddef>
namespace strata::gpu {
#endif

// 32-bit words per RGBA32 texel.
STRATA_CONST(uint, kTexelWords, 4u);

STRATA_CONST(uint, kBvhNodeTexels, 2u);
STRATA_CONST(uint, kBvhNodeWordBmin, 0u);
STRATA_CONST(uint, kBvhNodeWordLeftOrFirst, 3u);
STRATA_CONST(uint, kBvhNodeWordBmax, 4u);
STRATA_CONST(uint, kBvhNodeWordCount, 7u);

STRATA_CONST(uint, kInstanceTexels, 7u);
STRATA_CONST(uint, kInstanceWordRoot4, 24u);
STRATA_CONST(uint, kInstanceWordRoot2, 25u);
STRATA_CONST(uint, kInstanceWordMotionFirst, 26u);
STRATA_CONST(uint, kInstanceWordMotionCount, 27u);
STRATA_CONST(uint, kBvhNode4Texels, 7u);
STRATA_CONST(uint, kBvhNode4WordMinX, 0u);
STRATA_CONST(uint, kBvhNode4WordMaxX, 4u);
STRATA_CONST(uint, kBvhNode4WordMinY, 8u);
STRATA_CONST(uint, kBvhNode4WordMaxY, 12u);
STRATA_CONST(uint, kBvhNode4WordMinZ, 16u);
STRATA_CONST(uint, kBvhNode4WordMaxZ, 20u);
STRATA_CONST(uint, kBvhNode4WordChild, 24u);

STRATA_CONST(uint, kTriVertsTexels, 3u);
STRATA_CONST(uint, kTriVertsWordV0, 0u);
STRATA_CONST(uint, kTriVertsWordV1, 4u);
STRATA_CONST(uint, kTriVertsWordV2, 8u);

STRATA_CONST(uint, kTriShadingTexels, 3u);
STRATA_CONST(uint, kTriShadingWordN0, 0u);
STRATA_CONST(uint, kTriShadingWordMaterial, 3u);
STRATA_CONST(uint, kTriShadingWordN1, 4u);
STRATA_CONST(uint, kTriShadingWordLight, 7u);
STRATA_CONST(uint, kTriShadingWordN2, 8u);
STRATA_CONST(uint, kTriShadingWordPad0, 11u);

STRATA_CONST(uint, kMaterialTexels, 16u);
STRATA_CONST(uint, kMaterialWordBaseColor, 0u);
STRATA_CONST(uint, kMaterialWordEmission, 4u);
STRATA_CONST(uint, kMaterialWordMetallic, 7u);
STRATA_CONST(uint, kMaterialWordRoughness, 8u);
STRATA_CONST(uint, kMaterialWordIor, 9u);
STRATA_CONST(uint, kMaterialWordFlags, 10u);
STRATA_CONST(uint, kMaterialWordAlphaCutoff, 11u);
STRATA_CONST(uint, kMaterialWordTransmission, 12u);
STRATA_CONST(uint, kMaterialWordSpecular, 13u);
STRATA_CONST(uint, kMaterialWordNormalScale, 14u);
STRATA_CONST(uint, kMaterialWordBaseColorTex, 15u);
STRATA_CONST(uint, kMaterialWordMetallicRoughnessTex, 16u);
STRATA_CONST(uint, kMaterialWordNormalTex, 17u);
STRATA_CONST(uint, kMaterialWordEmissiveTex, 18u);
STRATA_CONST(uint, kMaterialWordTransmissionTex, 19u);
STRATA_CONST(uint, kMaterialWordAttenuation, 20u);
STRATA_CONST(uint, kMaterialWordThickness, 23u);
STRATA_CONST(uint, kMaterialWordClearcoat, 24u);
STRATA_CONST(uint, kMaterialWordClearcoatRoughness, 25u);
STRATA_CONST(uint, kMaterialWordClearcoatTex, 26u);
STRATA_CONST(uint, kMaterialWordClearcoatRoughnessTex, 27u);
STRATA_CONST(uint, kMaterialWordClearcoatNormalTex, 28u);
STRATA_CONST(uint, kMaterialWordClearcoatNormalScale, 29u);
STRATA_CONST(uint, kMaterialWordSheenRoughness, 30u);
STRATA_CONST(uint, kMaterialWordSheenRoughnessTex, 31u);
STRATA_CONST(uint, kMaterialWordSheenColor, 32u);
STRATA_CONST(uint, kMaterialWordSheenColorTex, 35u);
STRATA_CONST(uint, kMaterialWordSpecularColor, 36u);
STRATA_CONST(uint, kMaterialWordSpecularColorTex, 39u);
STRATA_CONST(uint, kMaterialWordSpecularTex, 40u);
STRATA_CONST(uint, kMaterialWordIridescence, 41u);
STRATA_CONST(uint, kMaterialWordIridescenceIor, 42u);
STRATA_CONST(uint, kMaterialWordIridescenceTex, 43u);
STRATA_CONST(uint, kMaterialWordIridescenceThicknessMin, 44u);
STRATA_CONST(uint, kMaterialWordIridescenceThicknessMax, 45u);
STRATA_CONST(uint, kMaterialWordIridescenceThicknessTex, 46u);
STRATA_CONST(uint, kMaterialWordPad0, 47u);
STRATA_CONST(uint, kMaterialWordDiffuseTransmissionColor, 48u);
STRATA_CONST(uint, kMaterialWordDiffuseTransmission, 51u);
STRATA_CONST(uint, kMaterialWordDiffuseTransmissionTex, 52u);
STRATA_CONST(uint, kMaterialWordDiffuseTransmissionColorTex, 53u);
STRATA_CONST(uint, kMaterialWordPad1, 54u);
STRATA_CONST(uint, kMaterialWordPad2, 55u);
STRATA_CONST(uint, kMaterialWordAnisotropyStrength, 56u);
STRATA_CONST(uint, kMaterialWordAnisotropyRotation, 57u);
STRATA_CONST(uint, kMaterialWordAnisotropyTex, 58u);
STRATA_CONST(uint, kMaterialWordDispersion, 59u);
STRATA_CONST(uint, kMaterialWordScatterAlbedo, 60u);
STRATA_CONST(uint, kMaterialWordScatterAnisotropy, 63u);

STRATA_CONST(uint, kTriTexcoordsTexels, 3u);
STRATA_CONST(uint, kTriTexcoordsWordUv0, 0u);
STRATA_CONST(uint, kTriTexcoordsWordUv1, 4u);
STRATA_CONST(uint, kTriTexcoordsWordUv2, 8u);

STRATA_CONST(uint, kTriColorsTexels, 3u);
STRATA_CONST(uint, kTriColorsWordC0, 0u);
STRATA_CONST(uint, kTriColorsWordC1, 4u);
STRATA_CONST(uint, kTriColorsWordC2, 8u);

STRATA_CONST(uint, kTriTangentsTexels, 3u);
STRATA_CONST(uint, kTriTangentsWordT0, 0u);
STRATA_CONST(uint, kTriTangentsWordT1, 4u);
STRATA_CONST(uint, kTriTangentsWordT2, 8u);

STRATA_CONST(uint, kTextureRefTexels, 3u);
STRATA_CONST(uint, kTextureRefWordOffset, 0u);
STRATA_CONST(uint, kTextureRefWordWidth, 1u);
STRATA_CONST(uint, kTextureRefWordHeight, 2u);
STRATA_CONST(uint, kTextureRefWordFlags, 3u);
STRATA_CONST(uint, kTextureRefWordRow0, 4u);
STRATA_CONST(uint, kTextureRefWordRow1, 8u);

STRATA_CONST(uint, kEmitterTexels, 5u);
STRATA_CONST(uint, kEmitterWordV0, 0u);
STRATA_CONST(uint, kEmitterWordTriangle, 3u);
STRATA_CONST(uint, kEmitterWordE1, 4u);
STRATA_CONST(uint, kEmitterWordArea, 7u);
STRATA_CONST(uint, kEmitterWordE2, 8u);
STRATA_CONST(uint, kEmitterWordPmf, 11u);
STRATA_CONST(uint, kEmitterWordRadiance, 12u);
STRATA_CONST(uint, kEmitterWordFlags, 15u);
STRATA_CONST(uint, kEmitterWordAliasProb, 16u);
STRATA_CONST(uint, kEmitterWordAlias, 17u);
STRATA_CONST(uint, kEmitterWordKind, 18u);
STRATA_CONST(uint, kEmitterWordTrail, 19u);

STRATA_CONST(uint, kLightNodeTexels, 3u);
STRATA_CONST(uint, kLightNodeWordCentre, 0u);
STRATA_CONST(uint, kLightNodeWordRadius, 3u);
STRATA_CONST(uint, kLightNodeWordAxis, 4u);
STRATA_CONST(uint, kLightNodeWordPower, 7u);
STRATA_CONST(uint, kLightNodeWordCosThetaO, 8u);
STRATA_CONST(uint, kLightNodeWordSinThetaO, 9u);
STRATA_CONST(uint, kLightNodeWordCosThetaE, 10u);
STRATA_CONST(uint, kLightNodeWordLink, 11u);

#ifdef __cplusplus
// STRATA_TEXELS: the struct is exactly its texels. STRATA_WORD: the field
// starts at its word. STRATA_TEXEL_WORD: ... and starts a texel (a vec3 or
// vec4 field, read as one texel's xyz or xyzw).
#define STRATA_TEXELS(T, texels) static_assert(sizeof(T) == 16 * (texels), #T ": texels")
#define STRATA_WORD(T, field, word) static_assert(offsetof(T, field) == 4 * (word), #T "." #field ": word")
#define STRATA_TEXEL_WORD(T, field, word) \
    STRATA_WORD(T, field, word);          \
    static_assert((word) % kTexelWords == 0, #T "." #field ": starts a texel")

// One list per struct, each repeating its struct's fields in order: the
// repetition is the check (a list of the same shape as the next, by design).
STRATA_TEXELS(BvhNode, kBvhNodeTexels);
STRATA_TEXEL_WORD(BvhNode, bmin, kBvhNodeWordBmin);
STRATA_WORD(BvhNode, leftOrFirst, kBvhNodeWordLeftOrFirst);
STRATA_TEXEL_WORD(BvhNode, bmax, kBvhNodeWordBmax);
STRATA_WORD(BvhNode, count, kBvhNodeWordCount);

STRATA_TEXELS(Instance, kInstanceTexels);
STRATA_WORD(Instance, root4, kInstanceWordRoot4);
STRATA_WORD(Instance, root2, kInstanceWordRoot2);
STRATA_WORD(Instance, motionFirst, kInstanceWordMotionFirst);
STRATA_WORD(Instance, motionCount, kInstanceWordMotionCount);

STRATA_TEXELS(BvhNode4, kBvhNode4Texels);
STRATA_TEXEL_WORD(BvhNode4, minX, kBvhNode4WordMinX);
STRATA_TEXEL_WORD(BvhNode4, maxX, kBvhNode4WordMaxX);
STRATA_TEXEL_WORD(BvhNode4, minY, kBvhNode4WordMinY);
STRATA_TEXEL_WORD(BvhNode4, maxY, kBvhNode4WordMaxY);
STRATA_TEXEL_WORD(BvhNode4, minZ, kBvhNode4WordMinZ);
STRATA_TEXEL_WORD(BvhNode4, maxZ, kBvhNode4WordMaxZ);
STRATA_TEXEL_WORD(BvhNode4, child, kBvhNode4WordChild);

STRATA_TEXELS(TriVerts, kTriVertsTexels);
STRATA_TEXEL_WORD(TriVerts, v0, kTriVertsWordV0);
STRATA_TEXEL_WORD(TriVerts, v1, kTriVertsWordV1);
STRATA_TEXEL_WORD(TriVerts, v2, kTriVertsWordV2);

STRATA_TEXELS(TriShading, kTriShadingTexels);
STRATA_TEXEL_WORD(TriShading, n0, kTriShadingWordN0);
STRATA_WORD(TriShading, material, kTriShadingWordMaterial);
STRATA_TEXEL_WORD(TriShading, n1, kTriShadingWordN1);
STRATA_WORD(TriShading, light, kTriShadingWordLight);
STRATA_TEXEL_WORD(TriShading, n2, kTriShadingWordN2);
STRATA_WORD(TriShading, pad0, kTriShadingWordPad0);

STRATA_TEXELS(Material, kMaterialTexels);
STRATA_TEXEL_WORD(Material, baseColor, kMaterialWordBaseColor);
STRATA_TEXEL_WORD(Material, emission, kMaterialWordEmission);
STRATA_WORD(Material, metallic, kMaterialWordMetallic);
STRATA_WORD(Material, roughness, kMaterialWordRoughness);
STRATA_WORD(Material, ior, kMaterialWordIor);
STRATA_WORD(Material, flags, kMaterialWordFlags);
STRATA_WORD(Material, alphaCutoff, kMaterialWordAlphaCutoff);
STRATA_WORD(Material, transmission, kMaterialWordTransmission);
STRATA_WORD(Material, specular, kMaterialWordSpecular);
STRATA_WORD(Material, normalScale, kMaterialWordNormalScale);
STRATA_WORD(Material, baseColorTex, kMaterialWordBaseColorTex);
STRATA_WORD(Material, metallicRoughnessTex, kMaterialWordMetallicRoughnessTex);
STRATA_WORD(Material, normalTex, kMaterialWordNormalTex);
STRATA_WORD(Material, emissiveTex, kMaterialWordEmissiveTex);
STRATA_WORD(Material, transmissionTex, kMaterialWordTransmissionTex);
STRATA_TEXEL_WORD(Material, attenuation, kMaterialWordAttenuation);
STRATA_WORD(Material, thickness, kMaterialWordThickness);
STRATA_WORD(Material, clearcoat, kMaterialWordClearcoat);
STRATA_WORD(Material, clearcoatRoughness, kMaterialWordClearcoatRoughness);
STRATA_WORD(Material, clearcoatTex, kMaterialWordClearcoatTex);
STRATA_WORD(Material, clearcoatRoughnessTex, kMaterialWordClearcoatRoughnessTex);
STRATA_WORD(Material, clearcoatNormalTex, kMaterialWordClearcoatNormalTex);
STRATA_WORD(Material, clearcoatNormalScale, kMaterialWordClearcoatNormalScale);
STRATA_WORD(Material, sheenRoughness, kMaterialWordSheenRoughness);
STRATA_WORD(Material, sheenRoughnessTex, kMaterialWordSheenRoughnessTex);
STRATA_TEXEL_WORD(Material, sheenColor, kMaterialWordSheenColor);
STRATA_WORD(Material, sheenColorTex, kMaterialWordSheenColorTex);
STRATA_TEXEL_WORD(Material, specularColor, kMaterialWordSpecularColor);
STRATA_WORD(Material, specularColorTex, kMaterialWordSpecularColorTex);
STRATA_WORD(Material, specularTex, kMaterialWordSpecularTex);
STRATA_WORD(Material, iridescence, kMaterialWordIridescence);
STRATA_WORD(Material, iridescenceIor, kMaterialWordIridescenceIor);
STRATA_WORD(Material, iridescenceTex, kMaterialWordIridescenceTex);
STRATA_WORD(Material, iridescenceThicknessMin, kMaterialWordIridescenceThicknessMin);
STRATA_WORD(Material, iridescenceThicknessMax, kMaterialWordIridescenceThicknessMax);
STRATA_WORD(Material, iridescenceThicknessTex, kMaterialWordIridescenceThicknessTex);
STRATA_WORD(Material, pad0, kMaterialWordPad0);
STRATA_TEXEL_WORD(Material, diffuseTransmissionColor, kMaterialWordDiffuseTransmissionColor);
STRATA_WORD(Material, diffuseTransmission, kMaterialWordDiffuseTransmission);
STRATA_WORD(Material, diffuseTransmissionTex, kMaterialWordDiffuseTransmissionTex);
STRATA_WORD(Material, diffuseTransmissionColorTex, kMaterialWordDiffuseTransmissionColorTex);
STRATA_WORD(Material, pad1, kMaterialWordPad1);
STRATA_WORD(Material, pad2, kMaterialWordPad2);
STRATA_WORD(Material, anisotropyStrength, kMaterialWordAnisotropyStrength);
STRATA_WORD(Material, anisotropyRotation, kMaterialWordAnisotropyRotation);
STRATA_WORD(Material, anisotropyTex, kMaterialWordAnisotropyTex);
STRATA_WORD(Material, dispersion, kMaterialWordDispersion);
STRATA_TEXEL_WORD(Material, scatterAlbedo, kMaterialWordScatterAlbedo);
STRATA_WORD(Material, scatterAnisotropy, kMaterialWordScatterAnisotropy);

STRATA_TEXELS(TriTexcoords, kTriTexcoordsTexels);
STRATA_TEXEL_WORD(TriTexcoords, uv0, kTriTexcoordsWordUv0);
STRATA_TEXEL_WORD(TriTexcoords, uv1, kTriTexcoordsWordUv1);
STRATA_TEXEL_WORD(TriTexcoords, uv2, kTriTexcoordsWordUv2);

STRATA_TEXELS(TriColors, kTriColorsTexels);
STRATA_TEXEL_WORD(TriColors, c0, kTriColorsWordC0);
STRATA_TEXEL_WORD(TriColors, c1, kTriColorsWordC1);
STRATA_TEXEL_WORD(TriColors, c2, kTriColorsWordC2);

STRATA_TEXELS(TriTangents, kTriTangentsTexels);
STRATA_TEXEL_WORD(TriTangents, t0, kTriTangentsWordT0);
STRATA_TEXEL_WORD(TriTangents, t1, kTriTangentsWordT1);
STRATA_TEXEL_WORD(TriTangents, t2, kTriTangentsWordT2);

STRATA_TEXELS(TextureRef, kTextureRefTexels);
STRATA_WORD(TextureRef, offset, kTextureRefWordOffset);
STRATA_WORD(TextureRef, width, kTextureRefWordWidth);
STRATA_WORD(TextureRef, height, kTextureRefWordHeight);
STRATA_WORD(TextureRef, flags, kTextureRefWordFlags);
STRATA_TEXEL_WORD(TextureRef, row0, kTextureRefWordRow0);
STRATA_TEXEL_WORD(TextureRef, row1, kTextureRefWordRow1);

STRATA_TEXELS(Emitter, kEmitterTexels);
STRATA_TEXEL_WORD(Emitter, v0, kEmitterWordV0);
STRATA_WORD(Emitter, triangle, kEmitterWordTriangle);
STRATA_TEXEL_WORD(Emitter, e1, kEmitterWordE1);
STRATA_WORD(Emitter, area, kEmitterWordArea);
STRATA_TEXEL_WORD(Emitter, e2, kEmitterWordE2);
STRATA_WORD(Emitter, pmf, kEmitterWordPmf);
STRATA_TEXEL_WORD(Emitter, radiance, kEmitterWordRadiance);
STRATA_WORD(Emitter, flags, kEmitterWordFlags);
STRATA_WORD(Emitter, aliasProb, kEmitterWordAliasProb);
STRATA_WORD(Emitter, alias, kEmitterWordAlias);
STRATA_WORD(Emitter, kind, kEmitterWordKind);
STRATA_WORD(Emitter, trail, kEmitterWordTrail);

STRATA_TEXELS(LightNode, kLightNodeTexels);
STRATA_TEXEL_WORD(LightNode, centre, kLightNodeWordCentre);
STRATA_WORD(LightNode, radius, kLightNodeWordRadius);
STRATA_TEXEL_WORD(LightNode, axis, kLightNodeWordAxis);
STRATA_WORD(LightNode, power, kLightNodeWordPower);
STRATA_WORD(LightNode, cosTheta_o, kLightNodeWordCosThetaO);
STRATA_WORD(LightNode, sinTheta_o, kLightNodeWordSinThetaO);
STRATA_WORD(LightNode, cosTheta_e, kLightNodeWordCosThetaE);
STRATA_WORD(LightNode, link, kLightNodeWordLink);

#undef STRATA_TEXELS
#undef STRATA_WORD
#undef STRATA_TEXEL_WORD
}  // namespace strata::gpu
#endif

#endif
