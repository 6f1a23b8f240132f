// Material evaluation at a surface point: glTF factors times their textures
// (and baseColor times the COLOR_0 vertex colour)
// (baseColor and emissive sRGB; metallicRoughness G = roughness, B =
// metallic; transmission R; clearcoat R, clearcoatRoughness G; sheenColor
// sRGB RGB, sheenRoughness A; specularColor sRGB RGB, specular A;
// diffuseTransmission A, diffuseTransmissionColor sRGB RGB), the
// tangent-space normal maps (the base's and the coat's), and the alpha
// test the BVH traversal uses to skip holes. Code for textures, normal maps
// and alpha is compiled out by the kFeature* bits of SPEC_FEATURES when the
// scene has none. Needs materials[], sceneShading, sceneTexcoords and
// sceneTangents (lib/scene.glsl declares them).
#ifndef STRATA_LIB_MATERIAL_GLSL
#define STRATA_LIB_MATERIAL_GLSL

#include "lib/rng.glsl"
#include "lib/textures.glsl"

struct SurfacePoint {
    vec3 baseColor;      // linear
    float alpha;
    float metallic;
    float roughness;     // perceptual
    float transmission;
    float ior;
    float specular;
    vec3 emission;       // radiance
    vec3 ns;             // unit shading normal on the incoming side (n's side)
    uint flags;          // kMaterial* bits
#ifdef STRATA_LAYERS
    // KHR_materials_clearcoat (kFeatureClearcoat; clearcoat 0 otherwise)
    float clearcoat;
    float clearcoatRoughness;  // perceptual
    vec3 coatNormal;           // unit, world space, on n's side: clearcoatNormalTexture's,
                               // else the interpolated normal (not the base's normal map)
    // KHR_materials_sheen (kFeatureSheen; sheenColor 0 otherwise)
    vec3 sheenColor;           // linear
    float sheenRoughness;
    vec3 specularColor;        // KHR_materials_specular (kFeatureSpecularColor; 1 otherwise)
#ifdef STRATA_IRIDESCENCE
    // KHR_materials_iridescence (kFeatureIridescence; iridescence 0 otherwise)
    float iridescence;
    float iridescenceIor;
    float iridescenceThickness;  // nanometres
#endif
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
    // KHR_materials_diffuse_transmission (kFeatureDiffuseTransmission; 0 otherwise)
    float diffuseTransmission;
    vec3 diffuseTransmissionColor;  // linear
#endif
};

// (TEXCOORD_0.xy, TEXCOORD_1.xy) at barycentrics (u, v) of vertices 1 and 2.
vec4 texcoordsAt(uint triangle, vec2 bary) {
    TriTexcoords tc = sceneTexcoords(triangle);
    return (1.0 - bary.x - bary.y) * tc.uv0 + bary.x * tc.uv1 + bary.y * tc.uv2;
}

// COLOR_0 at barycentrics (u, v) of vertices 1 and 2; white without
// kFeatureVertexColor.
vec4 vertexColorAt(uint triangle, vec2 bary) {
    if (!hasFeature(kFeatureVertexColor)) return vec4(1.0);
    TriColors tc = sceneColors(triangle);
    return (1.0 - bary.x - bary.y) * tc.c0 + bary.x * tc.c1 + bary.y * tc.c2;
}

#ifdef STRATA_TEXTURE_LOD
// Texture level of detail (the texlod axis, kFeatureTextureLod): the ray
// cone's footprint at the hit being shaded (Akenine-Moller et al., "Improved
// Shader and Texture Level of Detail Using Ray Cones", JCGT 2021). gTexLod:
// per texture-coordinate set, log2 of the cone's width at the hit times the
// uv units per world unit there (sqrt of the triangle's uv area over its
// area), plus the sample's bias (lodScale2ForSample); kNoLod while nothing is
// being shaded (the first level). The width is the footprint's minor axis:
// at a grazing angle the footprint stretches by 1/|cos| along the view, and
// the pixel's own samples integrate that axis, so an isotropic level at the
// major axis only blurs (docs/experiments/textures.md). A lookup's level is
// that plus log2 of the texture's texels per uv unit; a fractional level
// reads one of the two levels around it at random (stochastic trilinear: the
// expectation of the trilinear blend).
const float kNoLod = -1.0e30;

// The level bias of the pixel's sample `s` (shared/types.h), bias(s) =
// max(kLodBiasMin, kLodBiasFirst - kLodBiasPerDoubling log2(s + 1)): a
// quarter level blurrier than the footprint for the first sample, a quarter
// level sharper each time the sample index doubles, down to two and a half
// levels sharper (from sample 2,047 on). A few samples cannot average a
// texture's detail and gain from a wide filter; many can, and the blur
// would then be most of their error. The pixel's mean is over samples of
// decreasing blur, so at any spp it weighs noise against blur about as the
// best fixed bias for that spp would (measured: docs/experiments/textures.md,
// "The level bias by sample index"). A function of the sample index alone:
// shards, resume and merge keep their bits. Returned as exp2(2 bias(s)), a
// factor of the squared footprint inside texLodAt's one logarithm: with a
// quarter level a doubling, sqrt(2) (s + 1)^(-1/2) (shared/types.h asserts
// the constant).
float lodScale2ForSample(uint s) {
    return max(exp2(2.0 * kLodBiasMin), exp2(2.0 * kLodBiasFirst) * inversesqrt(float(s) + 1.0));
}
vec2 gTexLod = vec2(kNoLod);
uint gTexLodHash = 0u;

// The curvature of a triangle (vertices tv, vertex normals sh) seen from
// the side of `n`: the mean over its edges of the normals' change along the
// edge over its length (exactly 1/R for a sphere's vertices and normals);
// positive where convex. A cone reflected there spreads by 2 x this x its
// width (Akenine-Moller et al. 2021).
float triCurvature(TriVerts tv, TriShading sh, vec3 n) {
    vec3 d01 = tv.v1.xyz - tv.v0.xyz, d02 = tv.v2.xyz - tv.v0.xyz, d12 = tv.v2.xyz - tv.v1.xyz;
    float k = dot(sh.n1 - sh.n0, d01) / dot(d01, d01) + dot(sh.n2 - sh.n0, d02) / dot(d02, d02) +
              dot(sh.n2 - sh.n1, d12) / dot(d12, d12);
    return (dot(sh.n0 + sh.n1 + sh.n2, n) < 0.0 ? -k : k) / 3.0;
}

// The hit at `t`, barycentrics `bary`, on `triangle` (world edges e1, e2),
// reached by a cone `width` wide (negative past a focus: its size is |width|),
// for the pixel's sample `sampleIndex`.
void texLodAt(uint triangle, vec3 e1, vec3 e2, float width, float t, vec2 bary, uint sampleIndex) {
    vec3 c = cross(e1, e2);
    TriTexcoords tc = sceneTexcoords(triangle);
    vec4 d1 = tc.uv1 - tc.uv0, d2 = tc.uv2 - tc.uv0;
    vec2 uvArea2 = abs(vec2(d1.x * d2.y - d1.y * d2.x, d1.z * d2.w - d1.w * d2.z));
    gTexLod = 0.5 * log2(width * width * lodScale2ForSample(sampleIndex) * inversesqrt(dot(c, c)) * uvArea2);
    gTexLodHash = hashMix(hashMix(hashMix(triangle, floatBitsToUint(t)), floatBitsToUint(bary.x)),
                          floatBitsToUint(bary.y));
}

// The level of `r` a lookup at footprint `base` (gTexLod) reads: its offset
// and size in r (the levels follow the image, sides halved rounding up).
TextureRef textureLevel(TextureRef r, float base) {
    uint levels = r.flags >> kTexLevelsShift;
    float lambda = base + r.row0.w;  // log2 of its texels per uv unit (pack/textures.cpp setTexelDensity)
    if (levels <= 1u || !(lambda > 0.0)) return r;
    float top = float(levels - 1u);
    float l = min(floor(lambda), top);
    gTexLodHash = hashMix(gTexLodHash, r.offset);
    if (l < top && uintToUnit(gTexLodHash) < lambda - l) l += 1.0;
    uint level = uint(l), words = (r.flags & kTex16Bit) != 0u ? 2u : 1u;
    for (uint k = 0u; k < level; ++k) {
        r.offset += r.width * r.height * words;
        r.width = (r.width + 1u) / 2u;
        r.height = (r.height + 1u) / 2u;
    }
    return r;
}
#endif

// Texture slot `ref` (an index into textureRefs[]) at interpolated texture
// coordinates `uvs` (texcoordsAt); with texture LOD at the level gTexLod asks for.
vec4 materialTexture(uint ref, vec4 uvs) {
    TextureRef r = textureRefAt(ref);
    bool second = (r.flags & kTexCoord1) != 0u;
#ifdef STRATA_TEXTURE_LOD
    r = textureLevel(r, second ? gTexLod.y : gTexLod.x);
#endif
    return sampleTextureRef(r, second ? uvs.zw : uvs.xy);
}

// The tangent frame at a hit (`n`, `nsInterpolated` as normalMapped takes
// them): the interpolated tangent T made orthogonal to the front face's
// interpolated normal N, B = w cross(N, T); `side` -1 where n is the back.
float tangentFrame(uint triangle, vec2 bary, vec3 n, vec3 nsInterpolated, out vec3 T, out vec3 B, out vec3 N) {
    TriVerts tv = shadeTri(triangle);
    float side = dot(cross(tv.v1.xyz - tv.v0.xyz, tv.v2.xyz - tv.v0.xyz), n) >= 0.0 ? 1.0 : -1.0;
    N = side * nsInterpolated;
    TriTangents tg = shadeTangents(triangle);
    vec4 t4 = (1.0 - bary.x - bary.y) * tg.t0 + bary.x * tg.t1 + bary.y * tg.t2;
    T = t4.xyz - N * dot(N, t4.xyz);
    if (dot(T, T) > 1.0e-12) {
        T = normalize(T);
    } else {
        basis(N, T, B);
    }
    B = (t4.w < 0.0 ? -1.0 : 1.0) * cross(N, T);
    return side;
}

// The shading normal mapped by texture slot `tex` with scale `scale`
// (normalTexture, clearcoatNormalTexture). The tangent frame is built on the front
// face (the triangle's counter-clockwise side): the interpolated tangent,
// Gram-Schmidt against the normal, bitangent w * cross(n, t); the mapped
// normal is normalize(T x + B y + N z) with xy scaled by normalScale (glTF
// 2.0 3.9.3), and is reversed on a back face as the spec reverses normals.
// A mapped normal below the geometric horizon is lifted just above it.
vec3 normalMapped(uint tex, float scale, uint triangle, vec2 bary, vec4 uvs, vec3 n, vec3 nsInterpolated) {
    vec3 m = materialTexture(tex, uvs).xyz * 2.0 - 1.0;
    m.xy *= scale;
    vec3 T, B, N;
    float side = tangentFrame(triangle, bary, n, nsInterpolated, T, B, N);
    vec3 ns = side * normalize(m.x * T + m.y * B + m.z * N);
    const float kMinCos = 1.0e-3;
    float c = dot(ns, n);
    if (c < kMinCos) ns = normalize(ns + (kMinCos - c) * n);
    return ns;
}

#ifdef STRATA_ANISOTROPY
// KHR_materials_anisotropy at a hit (`n`, `nsInterpolated` as normalMapped
// takes them): the strength (anisotropyStrength x the texture's B) and, in
// `dir`, the direction in world space: the texture's RG (else the tangent)
// in the tangent frame, turned by anisotropyRotation towards the bitangent.
float anisotropyAt(Material mat, uint triangle, vec2 bary, vec3 n, vec3 nsInterpolated, out vec3 dir) {
    float strength = mat.anisotropyStrength;
    vec2 d = vec2(1.0, 0.0);
    if ((kFeatures & kFeatureTextures) != 0u && mat.anisotropyTex != kNoTexture) {
        vec3 a = materialTexture(mat.anisotropyTex, texcoordsAt(triangle, bary)).rgb;
        d = a.rg * 2.0 - 1.0;
        strength *= a.b;
    }
    float c = cos(mat.anisotropyRotation), s = sin(mat.anisotropyRotation);
    d = vec2(c * d.x - s * d.y, s * d.x + c * d.y);
    vec3 T, B, N;
    tangentFrame(triangle, bary, n, nsInterpolated, T, B, N);
    dir = d.x * T + d.y * B;
    return strength;
}
#endif

#ifdef STRATA_LAYERS
// KHR_materials_clearcoat at a point of a coated material: clearcoat x its
// texture (R) and the coat's normal, clearcoatNormalTexture's or else the
// interpolated normal (normalMapped's n and nsInterpolated).
float coatAt(Material mat, uint triangle, vec2 bary, vec3 n, vec3 nsInterpolated, out vec3 coatNormal) {
    float clearcoat = mat.clearcoat;
    coatNormal = nsInterpolated;
    if ((kFeatures & kFeatureTextures) == 0u) return clearcoat;
    vec4 uvs = texcoordsAt(triangle, bary);
    if (mat.clearcoatTex != kNoTexture) clearcoat *= materialTexture(mat.clearcoatTex, uvs).r;
    if ((kFeatures & kFeatureNormalMap) != 0u && mat.clearcoatNormalTex != kNoTexture)
        coatNormal = normalMapped(mat.clearcoatNormalTex, mat.clearcoatNormalScale, triangle, bary, uvs, n,
                                  nsInterpolated);
    return clearcoat;
}
#endif

// The material at a hit: `bary` = barycentrics of vertices 1 and 2, `n` the
// geometric normal on the incoming side, `nsInterpolated` the interpolated
// vertex normal flipped to n's side.
SurfacePoint surfacePoint(Material mat, uint triangle, vec2 bary, vec3 n, vec3 nsInterpolated) {
    SurfacePoint sp;
    sp.baseColor = mat.baseColor.rgb;
    sp.alpha = mat.baseColor.a;
    sp.metallic = mat.metallic;
    sp.roughness = mat.roughness;
    sp.transmission = mat.transmission;
    sp.ior = mat.ior;
    sp.specular = mat.specular;
    sp.emission = mat.emission;
    sp.ns = nsInterpolated;
    sp.flags = mat.flags;
    if (hasFeature(kFeatureVertexColor)) {
        vec4 c = vertexColorAt(triangle, bary);
        sp.baseColor *= c.rgb;
        sp.alpha *= c.a;
    }
#ifdef STRATA_LAYERS
    sp.clearcoat = 0.0;
    sp.clearcoatRoughness = 0.0;
    sp.coatNormal = nsInterpolated;
    bool coat = hasFeature(kFeatureClearcoat) && (mat.flags & kMaterialClearcoat) != 0u;
    if (coat) {
        sp.clearcoat = coatAt(mat, triangle, bary, n, nsInterpolated, sp.coatNormal);
        sp.clearcoatRoughness = mat.clearcoatRoughness;
    }
    sp.sheenColor = vec3(0.0);
    sp.sheenRoughness = 0.0;
    bool sheen = hasFeature(kFeatureSheen) && (mat.flags & kMaterialSheen) != 0u;
    if (sheen) {
        sp.sheenColor = mat.sheenColor;
        sp.sheenRoughness = mat.sheenRoughness;
    }
    sp.specularColor = vec3(1.0);
    bool tinted = hasFeature(kFeatureSpecularColor) && (mat.flags & kMaterialSpecularColor) != 0u;
    if (tinted) sp.specularColor = mat.specularColor;
#ifdef STRATA_IRIDESCENCE
    sp.iridescence = 0.0;
    sp.iridescenceIor = 1.3;
    sp.iridescenceThickness = 0.0;
    bool film = hasFeature(kFeatureIridescence) && (mat.flags & kMaterialIridescence) != 0u;
    if (film) {
        sp.iridescence = mat.iridescence;
        sp.iridescenceIor = mat.iridescenceIor;
        sp.iridescenceThickness = mat.iridescenceThicknessMax;
    }
#endif
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
    sp.diffuseTransmission = 0.0;
    sp.diffuseTransmissionColor = vec3(1.0);
    bool translucent = hasFeature(kFeatureDiffuseTransmission) && (mat.flags & kMaterialDiffuseTransmission) != 0u;
    if (translucent) {
        sp.diffuseTransmission = mat.diffuseTransmission;
        sp.diffuseTransmissionColor = mat.diffuseTransmissionColor;
    }
#endif
    if ((kFeatures & kFeatureTextures) == 0u) return sp;
    vec4 uvs = texcoordsAt(triangle, bary);
    if (mat.baseColorTex != kNoTexture) {
        vec4 c = materialTexture(mat.baseColorTex, uvs);
        sp.baseColor *= c.rgb;
        sp.alpha *= c.a;
    }
    if (mat.metallicRoughnessTex != kNoTexture) {
        vec4 c = materialTexture(mat.metallicRoughnessTex, uvs);
        sp.roughness *= c.g;
        sp.metallic *= c.b;
    }
    if (mat.emissiveTex != kNoTexture) sp.emission *= materialTexture(mat.emissiveTex, uvs).rgb;
    if (mat.transmissionTex != kNoTexture) sp.transmission *= materialTexture(mat.transmissionTex, uvs).r;
    if ((kFeatures & kFeatureNormalMap) != 0u && mat.normalTex != kNoTexture)
        sp.ns = normalMapped(mat.normalTex, mat.normalScale, triangle, bary, uvs, n, nsInterpolated);
#ifdef STRATA_LAYERS
    if (coat && mat.clearcoatRoughnessTex != kNoTexture)
        sp.clearcoatRoughness *= materialTexture(mat.clearcoatRoughnessTex, uvs).g;
    if (sheen) {
        if (mat.sheenColorTex != kNoTexture) sp.sheenColor *= materialTexture(mat.sheenColorTex, uvs).rgb;
        if (mat.sheenRoughnessTex != kNoTexture) sp.sheenRoughness *= materialTexture(mat.sheenRoughnessTex, uvs).a;
    }
    if (tinted) {
        if (mat.specularColorTex != kNoTexture) sp.specularColor *= materialTexture(mat.specularColorTex, uvs).rgb;
        if (mat.specularTex != kNoTexture) sp.specular *= materialTexture(mat.specularTex, uvs).a;
    }
#ifdef STRATA_IRIDESCENCE
    if (film) {
        if (mat.iridescenceTex != kNoTexture) sp.iridescence *= materialTexture(mat.iridescenceTex, uvs).r;
        if (mat.iridescenceThicknessTex != kNoTexture)
            sp.iridescenceThickness = mix(mat.iridescenceThicknessMin, mat.iridescenceThicknessMax,
                                          materialTexture(mat.iridescenceThicknessTex, uvs).g);
    }
#endif
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
    if (translucent) {
        if (mat.diffuseTransmissionTex != kNoTexture)
            sp.diffuseTransmission *= materialTexture(mat.diffuseTransmissionTex, uvs).a;
        if (mat.diffuseTransmissionColorTex != kNoTexture)
            sp.diffuseTransmissionColor *= materialTexture(mat.diffuseTransmissionColorTex, uvs).rgb;
    }
#endif
    return sp;
}

// KHR_materials_unlit: what an unlit surface shows, baseColorFactor times
// the baseColor texture.
vec3 unlitColor(Material mat, uint triangle, vec2 bary) {
    vec3 base = mat.baseColor.rgb;
    if (hasFeature(kFeatureVertexColor)) base *= vertexColorAt(triangle, bary).rgb;
    if ((kFeatures & kFeatureTextures) == 0u || mat.baseColorTex == kNoTexture) return base;
    return base * materialTexture(mat.baseColorTex, texcoordsAt(triangle, bary)).rgb;
}

// Emitted radiance of material `materialIndex` at a point of `triangle`
// (next-event estimation on textured emitters).
vec3 emissionAt(uint materialIndex, uint triangle, vec2 bary) {
    Material mat = sceneMaterial(materialIndex);
    if ((kFeatures & kFeatureTextures) == 0u || mat.emissiveTex == kNoTexture) return mat.emission;
    return mat.emission * materialTexture(mat.emissiveTex, texcoordsAt(triangle, bary)).rgb;
}

// The emission `le` of material `materialIndex` at a point of `triangle`
// as it leaves towards `toViewer` (unit): under KHR_materials_clearcoat's
// coat it is darkened by the coat's Fresnel, le (1 - clearcoat
// Schlick(0.04, |toViewer . coat normal|)), as the extension specifies. The
// path's emission hits and next-event estimation both take it from here.
// `instance`: the record that places the triangle (an emitter of a moving
// mesh, kFeatureInstancedEmitters), else kNoInstance (stored in world space).
vec3 coatedEmission(uint materialIndex, uint triangle, vec2 bary, vec3 le, vec3 toViewer, uint instance) {
#ifdef STRATA_LAYERS
    if (!hasFeature(kFeatureClearcoat)) return le;
    Material mat = sceneMaterial(materialIndex);
    if ((mat.flags & kMaterialClearcoat) == 0u) return le;
    // The emitter's triangle in world space: stored so, or placed by its
    // instance (moving lights; the tangents too, through gInstance).
#ifdef STRATA_INSTANCING
    uint shaded = gInstance;
    gInstance = kNoInstance;
#endif
#ifdef STRATA_MOVING_LIGHTS
    gInstance = instance;
    TriVerts tv = shadeTri(triangle);
    TriShading sh = shadeShading(triangle);
#else
    TriVerts tv = bvhFetchTri(triangle);
    TriShading sh = sceneShading(triangle);
#endif
    vec3 n = normalize(cross(tv.v1.xyz - tv.v0.xyz, tv.v2.xyz - tv.v0.xyz));
    if (dot(n, toViewer) < 0.0) n = -n;
    vec3 ns = normalize((1.0 - bary.x - bary.y) * sh.n0 + bary.x * sh.n1 + bary.y * sh.n2);
    if (dot(ns, n) < 0.0) ns = -ns;
    vec3 coatNormal;
    float clearcoat = min(coatAt(mat, triangle, bary, n, ns, coatNormal), 1.0);
#ifdef STRATA_INSTANCING
    gInstance = shaded;
#endif
    float m = 1.0 - min(abs(dot(toViewer, coatNormal)), 1.0);
    float m2 = m * m;
    return le * (1.0 - clearcoat * (0.04 + 0.96 * (m2 * m2 * m)));
#else
    return le;
#endif
}

// Per-ray hash for stochastic transparency: a pure function of the ray's
// bits, so the closest-hit and any-hit traversals of one ray make the same
// decisions, and a render is deterministic per seed.
uint alphaRayHash(vec3 origin, vec3 dir) {
    uvec3 o = floatBitsToUint(origin), d = floatBitsToUint(dir);
    return hash4(hash4(o.x, o.y, o.z, d.x), d.y, d.z, 0x9e3779b9u);
}

// True when the ray (hash `rayHash`) passes through `triangle` at `bary`:
// MASK: alpha < alphaCutoff; BLEND: with probability 1 - alpha. alpha =
// baseColorFactor.a times the baseColor texture's alpha.
bool alphaHole(uint triangle, vec2 bary, uint rayHash) {
    uint materialIndex = sceneShading(triangle).material;
    uint flags = sceneMaterial(materialIndex).flags;
    if ((flags & (kMaterialAlphaMask | kMaterialAlphaBlend)) == 0u) return false;
    Material mat = sceneMaterial(materialIndex);
    float alpha = mat.baseColor.a;
    if (hasFeature(kFeatureVertexColor)) alpha *= vertexColorAt(triangle, bary).a;
    if ((kFeatures & kFeatureTextures) != 0u && mat.baseColorTex != kNoTexture) {
#ifdef STRATA_TEXTURE_LOD
        // The traversal's cut-outs at the first level: their coverage exact.
        vec2 lod = gTexLod;
        gTexLod = vec2(kNoLod);
#endif
        alpha *= materialTexture(mat.baseColorTex, texcoordsAt(triangle, bary)).a;
#ifdef STRATA_TEXTURE_LOD
        gTexLod = lod;
#endif
    }
    if ((flags & kMaterialAlphaMask) != 0u) return alpha < mat.alphaCutoff;
    return uintToUnit(hash4(rayHash, triangle, 0x85ebca6bu, 0xc2b2ae35u)) >= alpha;
}

#endif
