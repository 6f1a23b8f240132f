// Buffer structs shared byte-for-byte by C++ (GLM) and GLSL (std430).
// Every vec3 is paired with a 4-byte scalar so no member straddles padding.
// Declarations only: lists of constants before the struct they describe
// repeat one shape through the file, never logic.
#ifndef STRATA_SHARED_TYPES_H
#define STRATA_SHARED_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace strata::gpu {
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
#define STRATA_CONST(type, name, value) inline constexpr type name = value
#else
#define STRATA_CONST(type, name, value) const type name = value
#endif

// Flattened BVH2 node, depth-first: an interior node's left child is the next
// node (index + 1); its right child is `leftOrFirst`. A leaf (count > 0)
// holds triangles [leftOrFirst, leftOrFirst + count) of the reordered
// triangle arrays.
struct BvhNode {
    vec3 bmin;
    uint leftOrFirst;
    vec3 bmax;
    uint count;
};

// Four-wide node, collapsed from the BVH2 (host/bvh/wide.h): the boxes of up
// to four children as structure of arrays (child k's box is
// [minX[k], maxX[k]] x [minY[k], maxY[k]] x [minZ[k], maxZ[k]]), then their
// references: kBvhChildEmpty, an interior node's index, or for a leaf
// kBvhLeafBit | first << kBvhLeafCountBits | (count - 1), count <= 2^kBvhLeafCountBits.
// Seven RGBA32 words; node 0 is the root (also for an empty BVH or a leaf root).
struct BvhNode4 {
    vec4 minX;
    vec4 maxX;
    vec4 minY;
    vec4 maxY;
    vec4 minZ;
    vec4 maxZ;
    uvec4 child;
};

STRATA_CONST(uint, kBvhChildEmpty, 0xffffffffu);
STRATA_CONST(uint, kBvhLeafBit, 0x80000000u);
STRATA_CONST(uint, kBvhLeafCountBits, 5u);
// Deepest four-wide tree the shaders traverse (host/bvh/wide.h): the stack
// bound of the four-wide traversals; deeper trees take the BVH2.
STRATA_CONST(uint, kBvhMaxWideDepth, 32u);
// First triangle of a leaf reference: below this (kBvhChildEmpty stays unique).
STRATA_CONST(uint, kBvhMaxLeafFirst, (1u << (31u - kBvhLeafCountBits)) - 1u);

// Triangle vertices in world space, in BVH order (w unused, kept 0).
struct TriVerts {
    vec4 v0;
    vec4 v1;
    vec4 v2;
};

// Per-triangle shading data in BVH order. Vertex normals are world space and
// normalised; a triangle without normals repeats its geometric normal.
struct TriShading {
    vec3 n0;
    uint material;   // index into the material buffer
    vec3 n1;
    uint light;      // index into the emitter buffer, or kNoLight
    vec3 n2;
    uint pad0;
};

STRATA_CONST(uint, kNoLight, 0xffffffffu);

// One placement of a bottom-level BVH (kFeatureInstancing): a mesh used by
// several nodes, or by EXT_mesh_gpu_instancing, is stored and built once in
// its own space and placed by affine transforms (rows of the 3x4 matrices).
// The instances array (BINDING_INSTANCES) holds the top-level BVH2's nodes
// (kBvhNodeTexels texels each, node 0 the root), then the records: a top
// leaf has count 1 and leftOrFirst the first texel of its Instance.
struct Instance {
    vec4 worldToObject[3];
    vec4 objectToWorld[3];
    uint root4;   // the bottom level's root among the four-wide nodes
    uint root2;   // ... among the BVH2 nodes
    uint motionFirst;  // motion blur: the first texel of its MotionKeys in the
    uint motionCount;  // instances array, and their count (0: it does not move)
};

// One pose of a moving instance (motion blur, STRATA_MOTION): its
// object-to-world transform at `time` is T R S. The keys of an instance are
// in time order; between two the pose is interpolated (T and S linearly, R
// by slerp); two keys at one time are a jump (the pose before, then after).
struct MotionKey {
    float time;
    vec3 translation;
    vec4 rotation;     // unit quaternion xyzw
    vec3 scale;
    float pad;
};

STRATA_CONST(uint, kNoInstance, 0xffffffffu);
STRATA_CONST(uint, kMotionKeyTexels, 3u);   // a MotionKey in the instances array
STRATA_CONST(uint, kMaxCameraKeys, 16u);    // FrameUniforms::cameraKeys

// How the shaders read the scene's arrays (SPEC_TEXEL_FETCH). Every array
// that has a texel view is bound both ways; the storage descriptor or the
// view the shader does not read covers only what the device allows.
STRATA_CONST(uint, kReadsStorage, 0u);   // storage buffers
STRATA_CONST(uint, kReadsTexelBvh, 1u);  // BVH nodes and triangle vertices through RGBA32UI texel
                                         // views (faster on lavapipe: docs/architecture.md), the rest storage
STRATA_CONST(uint, kReadsTexelAll, 2u);  // every array: also shading, texture coordinates, tangents,
                                         // emitters, materials, texture references and environment
                                         // tables (CPU devices; scenes past maxStorageBufferRange)

// Samplers (SPEC_SAMPLER; host/render/sampler_kind.h names them).
STRATA_CONST(uint, kSamplerIndependent, 0u);
STRATA_CONST(uint, kSamplerRegular, 1u);
STRATA_CONST(uint, kSamplerRotated, 2u);
STRATA_CONST(uint, kSamplerStratified, 3u);
STRATA_CONST(uint, kSamplerSobol, 4u);
STRATA_CONST(uint, kSamplerBlueNoise, 5u);

// Scene features (SPEC_FEATURES bits): code for a feature the scene does not
// use is compiled out. The host detects them at pack time (gpu_scene.h).
STRATA_CONST(uint, kFeatureSpecular, 1u);      // a GGX reflection lobe (metal or dielectric)
STRATA_CONST(uint, kFeatureTransmission, 2u);  // KHR_materials_transmission > 0
STRATA_CONST(uint, kFeatureTextures, 4u);      // any texture slot in use
STRATA_CONST(uint, kFeatureNormalMap, 8u);     // a normalTexture
STRATA_CONST(uint, kFeatureAlphaTest, 16u);    // alphaMode MASK or BLEND
STRATA_CONST(uint, kFeaturePunctual, 32u);     // KHR_lights_punctual lights
STRATA_CONST(uint, kFeatureEnvironment, 64u);  // an environment light (constant or map)
STRATA_CONST(uint, kFeatureEnvMap, 128u);      // the environment is an image
STRATA_CONST(uint, kFeatureUnlit, 256u);       // KHR_materials_unlit
STRATA_CONST(uint, kFeatureVolume, 512u);      // KHR_materials_volume with attenuation
STRATA_CONST(uint, kFeatureVertexColor, 2048u);  // COLOR_0 vertex colours (TriColors)
STRATA_CONST(uint, kFeatureInstancing, 1024u);  // instances: a top-level BVH over placed bottom levels
STRATA_CONST(uint, kFeatureClearcoat, 4096u);  // KHR_materials_clearcoat: the coat lobe
STRATA_CONST(uint, kFeatureSheen, 8192u);      // KHR_materials_sheen: the Charlie sheen lobe
STRATA_CONST(uint, kFeatureSpecularColor, 16384u);  // KHR_materials_specular colour or textures
STRATA_CONST(uint, kFeatureIridescence, 32768u);    // KHR_materials_iridescence: a thin film on the Fresnel
STRATA_CONST(uint, kFeatureLightTree, 65536u);      // lights chosen through the light tree (LightNode),
                                                    // not by power alone (pack/light_tree.h)
STRATA_CONST(uint, kFeatureInstancedEmitters, 131072u);  // emitters of an instanced mesh (one that
                                                         // moves during the shutter): kEmitterInstanced
STRATA_CONST(uint, kFeatureTextureLod, 262144u);  // textures with mip levels, read at the level a
                                                  // ray cone's footprint asks for (--texture-lod)
STRATA_CONST(uint, kFeatureDiffuseTransmission, 524288u);  // KHR_materials_diffuse_transmission: a
                                                           // Lambertian lobe through the surface
STRATA_CONST(uint, kFeatureAnisotropy, 1048576u);  // KHR_materials_anisotropy: anisotropic GGX along
                                                   // a direction in the tangent frame
STRATA_CONST(uint, kFeatureVolumeScatter, 2097152u);  // KHR_materials_volume_scatter: a volume that
                                                      // scatters (lib/medium.glsl)
STRATA_CONST(uint, kFeatureDispersion, 4194304u);  // KHR_materials_dispersion: paths through it carry
                                                   // a wavelength (lib/spectrum.glsl)
// The material layers: compiled only into the modules with the layers axis
// (STRATA_LAYERS, lib/features.glsl).
STRATA_CONST(uint, kFeaturesLayers,
             kFeatureClearcoat | kFeatureSheen | kFeatureSpecularColor | kFeatureIridescence);

// Combination of the two techniques that find lights (SPEC_MIS): both by
// the power heuristic, or one alone (Veach's comparison; not for production).
STRATA_CONST(uint, kMisPower, 0u);
STRATA_CONST(uint, kMisBsdf, 1u);    // BSDF sampling only: no next-event estimation
STRATA_CONST(uint, kMisLight, 2u);   // light sampling only (emitters hit by BSDF rays count
                                     // only after delta lobes, which light sampling cannot do)

// Material flags.
STRATA_CONST(uint, kMaterialDoubleSided, 1u);
STRATA_CONST(uint, kMaterialAlphaMask, 2u);    // alphaMode MASK: alpha < alphaCutoff is a hole
STRATA_CONST(uint, kMaterialAlphaBlend, 4u);   // alphaMode BLEND: stochastic transparency
STRATA_CONST(uint, kMaterialUnlit, 8u);        // KHR_materials_unlit: shows baseColor, does not scatter
STRATA_CONST(uint, kMaterialVolume, 16u);      // KHR_materials_volume: attenuates paths inside
STRATA_CONST(uint, kMaterialClearcoat, 32u);   // KHR_materials_clearcoat: clearcoat > 0
STRATA_CONST(uint, kMaterialSheen, 64u);       // KHR_materials_sheen: sheenColorFactor > 0
STRATA_CONST(uint, kMaterialSpecularColor, 128u);  // KHR_materials_specular: a colour or texture
STRATA_CONST(uint, kMaterialIridescence, 256u);    // KHR_materials_iridescence: iridescenceFactor > 0
STRATA_CONST(uint, kMaterialDiffuseTransmission, 512u);  // KHR_materials_diffuse_transmission: factor > 0
STRATA_CONST(uint, kMaterialThinWalled, 1024u);  // ... and no volume (KHR_materials_volume thickness 0):
                                                 // its back face sees the outside's ior too
STRATA_CONST(uint, kMaterialAnisotropy, 2048u);  // KHR_materials_anisotropy: anisotropyStrength > 0
STRATA_CONST(uint, kMaterialVolumeScatter, 4096u);  // KHR_materials_volume_scatter: kMaterialVolume whose
                                                    // attenuation partly scatters
STRATA_CONST(uint, kMaterialIndexMatched, 8192u);   // ... whose boundary light crosses unchanged but for
                                                    // its colour: ior 1, transmission 1, smooth, no
                                                    // texture, layer or emission (pack/gpu_scene.cpp)
STRATA_CONST(uint, kMaterialDispersion, 16384u);   // KHR_materials_dispersion: dispersion > 0 on a
                                                   // refracting dielectric

STRATA_CONST(uint, kNoTexture, 0xffffffffu);

// glTF pbrMetallicRoughness factors and the extensions strata reads.
// `emission` is emissiveFactor times KHR_materials_emissive_strength (linear
// radiance, W sr^-1 m^-2 units). Texture slots index TextureRef[] (the
// texture, its sampler and KHR_texture_transform) or hold kNoTexture.
struct Material {
    vec4 baseColor;         // linear RGB + alpha
    vec3 emission;
    float metallic;
    float roughness;        // perceptual; GGX alpha = roughness^2
    float ior;              // KHR_materials_ior (1.5 default)
    uint flags;             // kMaterial* bits
    float alphaCutoff;
    float transmission;     // KHR_materials_transmission transmissionFactor
    float specular;         // KHR_materials_specular specularFactor (1 default)
    float normalScale;      // normalTexture.scale
    uint baseColorTex;
    uint metallicRoughnessTex;
    uint normalTex;
    uint emissiveTex;
    uint transmissionTex;
    // KHR_materials_volume (kMaterialVolume): the attenuation coefficient per
    // unit length, -ln(attenuationColor) / attenuationDistance.
    vec3 attenuation;
    float thickness;        // thicknessFactor (the shader takes lengths from the geometry)
    // KHR_materials_clearcoat (kMaterialClearcoat; the seventh and eighth
    // texels, read only under kFeatureClearcoat).
    float clearcoat;              // clearcoatFactor
    float clearcoatRoughness;     // clearcoatRoughnessFactor (perceptual; alpha = roughness^2)
    uint clearcoatTex;            // clearcoatTexture: R scales clearcoat
    uint clearcoatRoughnessTex;   // clearcoatRoughnessTexture: G scales clearcoatRoughness
    uint clearcoatNormalTex;      // clearcoatNormalTexture: the coat's own normal map
    float clearcoatNormalScale;   // its scale
    // KHR_materials_sheen (kMaterialSheen; the rest of the eighth texel and
    // the ninth, read under kFeatureSheen).
    float sheenRoughness;         // sheenRoughnessFactor (Charlie alpha = roughness^2)
    uint sheenRoughnessTex;       // sheenRoughnessTexture: A scales sheenRoughness
    vec3 sheenColor;              // sheenColorFactor, linear
    uint sheenColorTex;           // sheenColorTexture: sRGB RGB scales sheenColor
    // KHR_materials_specular's colour and textures (kMaterialSpecularColor;
    // the tenth and eleventh texels, read under kFeatureSpecularColor).
    vec3 specularColor;           // specularColorFactor, linear (may exceed 1)
    uint specularColorTex;        // specularColorTexture: sRGB RGB scales specularColor
    uint specularTex;             // specularTexture: A scales specular
    // KHR_materials_iridescence (kMaterialIridescence; the rest of the
    // eleventh texel and the twelfth, read under kFeatureIridescence).
    float iridescence;            // iridescenceFactor
    float iridescenceIor;         // the film's index
    uint iridescenceTex;          // iridescenceTexture: R scales iridescence
    float iridescenceThicknessMin;  // nanometres
    float iridescenceThicknessMax;
    uint iridescenceThicknessTex;   // iridescenceThicknessTexture: G mixes min to max
    uint pad0;
    // KHR_materials_diffuse_transmission (kMaterialDiffuseTransmission; the
    // thirteenth and fourteenth texels, read under kFeatureDiffuseTransmission).
    vec3 diffuseTransmissionColor;  // diffuseTransmissionColorFactor, linear
    float diffuseTransmission;      // diffuseTransmissionFactor
    uint diffuseTransmissionTex;    // diffuseTransmissionTexture: A scales the factor
    uint diffuseTransmissionColorTex;  // diffuseTransmissionColorTexture: sRGB RGB scales the colour
    uint pad1;
    uint pad2;
    // KHR_materials_anisotropy (kMaterialAnisotropy; the fifteenth texel,
    // read under kFeatureAnisotropy), and KHR_materials_dispersion's number
    // (kMaterialDispersion; read under kFeatureDispersion).
    float anisotropyStrength;
    float anisotropyRotation;       // radians, counter-clockwise from the tangent
    uint anisotropyTex;             // anisotropyTexture: RG direction, B scales the strength
    float dispersion;               // 20 / the Abbe number (0: none)
    // KHR_materials_volume_scatter (kMaterialVolumeScatter; the sixteenth
    // texel, read under kFeatureVolumeScatter): scattering = attenuation x
    // scatterAlbedo, the rest absorbs.
    vec3 scatterAlbedo;             // the single-scatter albedo per channel
    float scatterAnisotropy;        // Henyey-Greenstein g
};

// Texture coordinates of one triangle in BVH order: uvK = (TEXCOORD_a.xy,
// TEXCOORD_b.xy) of vertex K, {a, b} the material's two sets ({0, 1} unless
// it reads a higher one; scene.h, MaterialDesc::uvSets), 0 where the
// primitive lacks a set. Uploaded only when a scene uses textures.
struct TriTexcoords {
    vec4 uv0;
    vec4 uv1;
    vec4 uv2;
};

// Tangents of one triangle in BVH order: xyz world-space unit tangent of
// vertex K, w = +-1 handedness (bitangent = w * cross(normal, tangent), glTF's
// TANGENT convention). Uploaded only when a scene uses normal maps.
struct TriTangents {
    vec4 t0;
    vec4 t1;
    vec4 t2;
};

// COLOR_0 of one triangle in BVH order: cK = linear RGBA of vertex K (alpha
// 1 for a VEC3 accessor, (1, 1, 1, 1) where the primitive has no COLOR_0),
// multiplying baseColor (glTF 2.0 3.7.2.1). Uploaded only with
// kFeatureVertexColor.
struct TriColors {
    vec4 c0;
    vec4 c1;
    vec4 c2;
};

// TextureRef.flags: bits 0-1 wrapS, bits 2-3 wrapT (kWrap*), then kTex* bits.
STRATA_CONST(uint, kWrapRepeat, 0u);
STRATA_CONST(uint, kWrapClamp, 1u);
STRATA_CONST(uint, kWrapMirror, 2u);
STRATA_CONST(uint, kTexNearest, 16u);    // magFilter NEAREST (else bilinear)
STRATA_CONST(uint, kTexCoord1, 32u);     // reads the second set (uv.zw) of TriTexcoords (else uv.xy)
STRATA_CONST(uint, kTex16Bit, 64u);      // 2 texel-buffer words per texel (else 1)
STRATA_CONST(uint, kTexSrgb, 128u);      // rgb is sRGB-encoded (baseColor, emissive)
// flags >> kTexLevelsShift: the mip levels stored (kFeatureTextureLod): each
// after the one before, sides halved rounding up (ceil) down to 1x1; 0 or 1:
// the image alone.
STRATA_CONST(uint, kTexLevelsShift, 16u);
// Texture LOD's level bias for sample index s (lib/material.glsl
// lodScale2ForSample): max(kLodBiasMin, kLodBiasFirst - kLodBiasPerDoubling x
// log2(s + 1)) levels added to the footprint's. lodScale2ForSample takes
// its exp2(2 x bias) as an inverse square root: a quarter level a doubling.
STRATA_CONST(float, kLodBiasFirst, 0.25f);
STRATA_CONST(float, kLodBiasPerDoubling, 0.25f);
STRATA_CONST(float, kLodBiasMin, -2.5f);
#ifdef __cplusplus
static_assert(kLodBiasPerDoubling == 0.25f, "lib/material.glsl lodScale2ForSample: (s + 1)^(-1/2)");
#endif

// One texture reference of a material slot: the image's place in the packed
// texel buffer (BINDING_TEXELS, R32UI words, rows top to bottom; an 8-bit
// texel is one word R | G << 8 | B << 16 | A << 24, a 16-bit texel two words
// R | G << 16, B | A << 16), its sampler and the KHR_texture_transform as a
// 2x3 matrix: uv' = (dot(row0.xy, uv) + row0.z, dot(row1.xy, uv) + row1.z).
struct TextureRef {
    uint offset;        // first word of the image
    uint width;         // texels
    uint height;
    uint flags;         // wrap modes and kTex* bits
    vec4 row0;          // w: log2 of the texels a uv unit spans (pack/textures.cpp setTexelDensity)
    vec4 row1;          // w unused
};

// Light kinds (Emitter.kind). Triangles come from emissive materials;
// the others from KHR_lights_punctual and --env.
STRATA_CONST(uint, kLightTriangle, 0u);
STRATA_CONST(uint, kLightPoint, 1u);
STRATA_CONST(uint, kLightSpot, 2u);
STRATA_CONST(uint, kLightDirectional, 3u);
STRATA_CONST(uint, kLightEnvironment, 4u);

// A light, selected through a Walker alias table built on the host: pick
// slot i = floor(u * count), keep it if the second uniform is below
// `aliasProb`, else take `alias`. `pmf` is the probability of choosing this
// emitter (its share of the estimated power, pack/gpu_scene.cpp).
// Fields by kind (unused ones are 0):
//   kLightTriangle: v0, e1 = v1 - v0, e2 = v2 - v0, triangle, area;
//                   radiance = emitted radiance (W sr^-1 m^-2); flags.
//                   With kEmitterInstanced in flags (a triangle of a mesh
//                   that moves: kFeatureInstancedEmitters), v0.x's bits are
//                   the first texel of its placement's Instance record, e1,
//                   e2 and area 0: its vertices are TriVerts[triangle] (object
//                   space), placed by that record at the path's time.
//   kLightPoint:    v0 = position; radiance = radiant intensity (W/sr).
//   kLightSpot:     v0 = position, e1 = unit axis (where the light travels),
//                   e2.x = scale, e2.y = offset of the cone falloff
//                   clamp(cos * scale + offset, 0, 1)^2; radiance as point.
//   kLightDirectional: e1 = unit direction the light travels;
//                   radiance = irradiance (W/m^2) on a surface facing it.
//   kLightEnvironment: nothing here; FrameUniforms.env* describe it.
struct Emitter {
    vec3 v0;
    uint triangle;    // index into TriVerts/TriShading (BVH order)
    vec3 e1;
    float area;
    vec3 e2;
    float pmf;
    vec3 radiance;
    uint flags;       // kMaterialDoubleSided: emits from both sides; kEmitterInstanced
    float aliasProb;
    uint alias;
    uint kind;        // kLight*
    uint trail;       // with the light tree (kFeatureLightTree), a bounded
                      // light's path from the root: bit d = 1 takes the second
                      // child at depth d (LightNode)
};

STRATA_CONST(uint, kEmitterInstanced, 0x80000000u);  // Emitter.flags: stored by its instance (above)

// A node of the light tree (pack/light_tree.h; Conty Estevez & Kulla 2018):
// the bounds, total estimated power and orientation cone of the bounded
// lights (triangles, point and spot lights) below it. Node 0 is the root;
// an interior node's first child follows it, its second is in `link`. A
// leaf holds one light, `link` then holds its emitter index. The bounds are
// the sphere around the lights' box (all the importance reads of it). The
// cone: every light's normal (or a spot's axis) is within theta_o of
// `axis`, and emits within theta_e beyond it (pi/2 for a surface).
struct LightNode {
    vec3 centre;      // of the lights' bounding box
    float radius;     // its half diagonal (rounded up)
    vec3 axis;        // unit
    float power;      // sum of the lights' estimated powers (packScene's weights)
    float cosTheta_o;
    float sinTheta_o;
    float cosTheta_e;
    uint link;        // kLightNodeIndex bits: the second child, or a leaf's emitter;
                      // kLightNodeLeaf, kLightNodeTwoSided (some light below emits
                      // from both sides)
};
STRATA_CONST(uint, kLightNodeLeaf, 0x80000000u);
STRATA_CONST(uint, kLightNodeTwoSided, 0x40000000u);
STRATA_CONST(uint, kLightNodeIndex, 0x3fffffffu);

// Accumulation layout: per pixel, two vec4 — sum of sample rgb and the number
// of finite samples (in .w), then the sum of squared rgb (.w unused).
STRATA_CONST(uint, kAccumVec4PerPixel, 2u);

// With AOVs (--aov, the aov axis) the accumulation buffer goes on, after the two vec4
// of every pixel, with kAovVec4PerPixel vec4 per pixel, summed over the same
// samples (lib/film.glsl, accumulateAov): the even-indexed samples' rgb and
// their count; albedo rgb and depth; the camera-space normal and the
// emitter mark; albedo squared and depth squared; the normal squared (.w unused).
STRATA_CONST(uint, kAovVec4PerPixel, 5u);

// Entries of the pixel filter's inverse-CDF table (u = i / (n - 1)).
STRATA_CONST(uint, kFilterTableEntries, 16385u);

// Camera and per-render constants (uniform buffer, std140-compatible: only
// vec4-sized members).
struct FrameUniforms {
    vec4 camOrigin;     // xyz: eye position
    vec4 camForward;    // xyz: unit view direction
    vec4 camRight;      // xyz: right * tan(yfov/2) * aspect
    vec4 camUp;         // xyz: up * tan(yfov/2)
    uvec4 image;        // width, height, maxDepth, seed
    uvec4 counts;       // emitterCount, triangleCount, nodeCount, spp (of the whole render)
    vec4 scene;         // x: total emitted power (for stats); y: with the light tree, the
                        // probability of choosing a bounded light (the tree) over the
                        // directional and environment lights; z: the camera ray cone's
                        // width in pixels, the pixel filter's diameter (texture LOD); w unused
    // Environment light (scene.h states the equirectangular convention).
    vec4 envScale;      // xyz: radiance (constant) or the map's multiplier; w unused
    vec4 envRotation;   // x, y: cos, sin of the rotation about +Y; zw unused
    uvec4 envInfo;      // x: the environment's emitter index (kNoLight: none);
                        // y, z: map width, height (0 without a map); w unused
    // The camera effects (STRATA_MOTION, the motion axis; lib/motion.glsl).
    // lens: x: lens radius (0: a pinhole), y: focus distance along the view
    // direction (world units), z: aperture blades (0: a disk), w unused.
    vec4 lens;
    // shutter: x, y: open and close times (seconds on the animation's
    // timeline), z: the camera's motion keys in cameraKeys (0: it does not
    // move), w unused.
    vec4 shutter;
    // Two texels per key: (time, position xyz), (orientation: unit quaternion
    // xyzw taking camera space to world space).
    vec4 cameraKeys[2 * kMaxCameraKeys];
};

// Per-dispatch constants (push constants).
struct DispatchParams {
    uint tileX;         // first pixel of this dispatch's tile
    uint tileY;
    uint tileW;         // tile size in pixels (<= image size)
    uint tileH;
    uint sampleIndex;   // index of the sample being taken (0-based)
    uint blockStride;   // SPEC_WORK_QUEUE: workgroup w shades the tile's 8x8 block
                        // (w * blockStride) mod blocks (coprime to blocks)
    uint sampleCount;   // pathtrace.comp: samples sampleIndex.. of this many (0 counts as 1)
    uint pad2;
};

// Trace kernel (tests and `strata bench`): one ray in, one closest hit out.
struct TraceRay {
    vec3 origin;
    float tmin;
    vec3 dir;
    float tmax;
};

struct TraceHit {
    float t;            // hit distance, or -1 on a miss
    uint triangle;      // BVH-order triangle index, kNoHit on a miss
    float u;            // barycentrics of v1 and v2
    float v;
};

STRATA_CONST(uint, kNoHit, 0xffffffffu);

// Trace kernel modes (SPEC_TRACE_MODE, one pipeline each). kTraceAny:
// hit.t = 1 if occluded, else -1. kTraceSpawn: rays come in pairs; ray 2i
// is traced to its closest hit, then a ray leaves that hit along the
// direction of ray 2i+1 from the origin the path tracer would use
// (spawnOrigin), and hit 2i+1 is its closest hit.
STRATA_CONST(uint, kTraceClosest, 0u);
STRATA_CONST(uint, kTraceAny, 1u);
STRATA_CONST(uint, kTraceSpawn, 2u);

// The trace kernel's work queue (SPEC_WORK_QUEUE, trace.comp): the most
// vectors of rays (one per lane each) a subgroup takes at a time, the part of
// lavapipe's loop budget (kLoopLimit loop iterations an invocation) after
// which it takes no more.
STRATA_CONST(uint, kQueueMaxVectors, 32u);
STRATA_CONST(uint, kQueueTickBudget, 32768u);
STRATA_CONST(uint, kLoopLimit, 65535u);
// The first pass launches a subgroup for every kQueueRaysPerSubgroup rays;
// its last subgroup writes the second pass's group count for what is left.
STRATA_CONST(uint, kQueueRaysPerSubgroup, 512u);
// Per dispatch in BINDING_WORK, kQueueWords words: the ray counter, the
// first pass's finished subgroups, and the second pass's
// VkDispatchIndirectCommand (x, y, z).
STRATA_CONST(uint, kQueueWords, 8u);

// One path's state between the wavefront stages (BINDING_WAVE_STATE).
struct PathState {
    vec4 betaPdf;       // path throughput; w: the last BSDF sample's pdf
    vec4 lDelta;        // radiance so far; w: 1 if the last sample was a delta lobe (or the camera)
    uvec4 misc;         // x: pixel index (y * width + x), y: bounces so far, z: 1 while alive,
                        // w: the path's wavelength's float bits (the dispersion axis; 0: RGB)
};

// Wavefront stage push constants.
struct WaveParams {
    uint count;         // entries of this stage's list (paths, rays)
    uint sampleIndex;   // index of the sample being taken
    uint tileX;         // the tile (camera stage)
    uint tileY;
    uint tileW;
    uint pad0;
    uint pad1;
    uint pad2;
};

// Wavefront integrator stages (wavefront.comp, SPEC_WAVE_STAGE: one pipeline each).
STRATA_CONST(uint, kStageCamera, 0u);
STRATA_CONST(uint, kStageShade, 1u);
STRATA_CONST(uint, kStageResolve, 2u);
STRATA_CONST(uint, kStageAccumulate, 3u);

// Trace kernel push constants.
struct TraceParams {
    uint count;         // rays in this dispatch
    uint first;         // index of this dispatch's first ray
    uint slot;          // this dispatch's words in BINDING_WORK (SPEC_WORK_QUEUE; slot * kQueueWords)
    uint pass;          // SPEC_WORK_QUEUE: 0 the first pass, 1 the second (the mode is SPEC_TRACE_MODE)
};

// Statistics written by the shader with atomics. Ray counts are 64-bit
// counters kept as two words (low word added atomically, a carry into the
// high word when it wraps), summed per subgroup before the atomics, and only
// counted when SPEC_COUNT_RAYS is 1.
struct RenderCounters {
    uint nonFinite;     // samples dropped because a channel was NaN/Inf
    uint pad0;
    uint closestLo;     // closest-hit rays traced (= path segments), low word
    uint closestHi;     //   high word
    uint shadowLo;      // any-hit (shadow) rays traced, low word
    uint shadowHi;      //   high word
    uint pad1;
    uint pad2;
};

#ifdef __cplusplus
static_assert(sizeof(BvhNode) == 32);
static_assert(sizeof(TriVerts) == 48);
static_assert(sizeof(TriShading) == 48);
static_assert(sizeof(Material) == 256);
static_assert(sizeof(Emitter) == 80);
static_assert(sizeof(LightNode) == 48);
static_assert(sizeof(TriTexcoords) == 48);
static_assert(sizeof(TriTangents) == 48);
static_assert(sizeof(TriColors) == 48);
static_assert(sizeof(TextureRef) == 48);
static_assert(sizeof(FrameUniforms) == 192 + 32 * kMaxCameraKeys);
static_assert(sizeof(DispatchParams) == 32);
static_assert(sizeof(RenderCounters) == 32);
static_assert(sizeof(TraceRay) == 32);
static_assert(sizeof(TraceHit) == 16);
static_assert(sizeof(Instance) == 112);
static_assert(sizeof(MotionKey) == 16 * kMotionKeyTexels);
static_assert(sizeof(TraceParams) == 16);
static_assert(sizeof(PathState) == 48);
static_assert(sizeof(WaveParams) == 32);
}  // namespace strata::gpu
#endif

// The texel-view layouts of these structs (the shaders' decoders).
#include "texel_layout.h"

#endif
