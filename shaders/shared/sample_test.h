// The sampling test kernel's interface (shaders/sample_test.comp; the C++
// side in measure/sample_dump.h): the routines it draws samples of and its
// push constants, shared byte-for-byte as types.h's structs are.
#ifndef STRATA_SHARED_SAMPLE_TEST_H
#define STRATA_SHARED_SAMPLE_TEST_H

#include "types.h"

#ifdef __cplusplus
namespace strata::gpu {
#endif

// Sampling test kernel (sample_test.comp): draws `count` samples of one GLSL
// sampling routine, each from its own counter-based random numbers.
STRATA_CONST(uint, kSampleCosineHemisphere, 0u);  // out: direction xyz
STRATA_CONST(uint, kSampleTriangle, 1u);          // out: barycentrics (b1, b2)
STRATA_CONST(uint, kSampleEmitterChoice, 2u);     // out: x = chosen emitter index
STRATA_CONST(uint, kSampleFilter, 4u);            // out: filter offset (x, y) in pixels
STRATA_CONST(uint, kSamplePixel, 3u);             // out: the pixel pair and the first light
                                                  // pair of sample i % spp of pixel i / spp of
                                                  // the block of blockWidth columns from
                                                  // (pixelX, pixelY), row by row
// BSDF routines (lib/bsdf.glsl) for the material in `bsdf0/bsdf1` seen from
// wo = (sin t, 0, cos t) in the shading frame, t the incidence angle:
STRATA_CONST(uint, kSampleBsdf, 5u);              // out: wi xyz, w = 1 if the sample is valid
STRATA_CONST(uint, kSampleBsdfWeight, 6u);        // out: weight.r, eval.r / evalPdf, sample pdf,
                                                  // eval pdf (x < 0 marks an invalid sample;
                                                  // y = z = w = -1 a delta sample)
STRATA_CONST(uint, kBsdfPdfCells, 7u);            // out: x = integral of the pdf over cell i of
                                                  // a pixelX (theta in [0,pi]) x pixelY (phi)
                                                  // grid, row-major in theta
STRATA_CONST(uint, kSampleLight, 8u);             // out: sampleLight(0, u): wi xyz, pdf w
STRATA_CONST(uint, kSampleLightTree, 10u);        // light tree at point bsdf0.xyz, normal bsdf1.xyz:
                                                  // out: x = chosen emitter (-1: none), y = its
                                                  // pmf as sampled, z = lightTreePmf of it
STRATA_CONST(uint, kLightTreePmf, 11u);           // out: x = lightTreePmf of emitter i at the
                                                  // point and normal of kSampleLightTree
STRATA_CONST(uint, kSampleEnvironmentPdf, 9u);    // out: direction xyz at the centre of cell
                                                  // (i % width, i / width) of a width x
                                                  // (count / width) grid in (phi / 2pi,
                                                  // (z + 1) / 2), polar axis +Z; w: its
                                                  // lightPdfEnvironment
// Media (lib/medium.glsl):
STRATA_CONST(uint, kSamplePhase, 12u);            // Henyey-Greenstein g = bsdf4.z about the travel
                                                  // direction +Z: out: wi xyz, w = its pdf
STRATA_CONST(uint, kSampleFreeFlight, 13u);       // free flight in attenuation bsdf3.xyz up to
                                                  // bsdf4.w, channels chosen by shares bsdf1.xyz:
                                                  // out: x = distance (bsdf4.w: none before it),
                                                  // yzw = the path weight's rgb (the scattering
                                                  // albedo bsdf2.xyz folded in)
// Wavelengths (lib/spectrum.glsl; the dispersion axis, kFeatureDispersion):
STRATA_CONST(uint, kSampleWavelength, 14u);       // out: x = lambda (nm), yzw = the throughput's
                                                  // weight wavelengthRgb / pdf
STRATA_CONST(uint, kWavelengthFunctions, 15u);    // at lambda = bsdf4.x + i * bsdf4.y: out: x =
                                                  // visibleWavelengthPdf, yzw = wavelengthRgb

struct SampleTestParams {
    uint count;
    uint routine;       // kSample*
    uint seed;
    uint emitterCount;  // for kSampleEmitterChoice
    uint pixelX;        // for kSamplePixel: the block's first pixel, image width, spp
    uint pixelY;        // and the block's width in pixels (0 counts as 1)
    uint width;
    uint spp;
    uint blockWidth;
    float diffTrans;       // BSDF routines: diffuse transmission factor
    float diffTransColor;  // and its colour (grey)
    uint pad0;
    vec4 bsdf0;         // BSDF routines: cos(incidence), roughness, metallic, transmission
    vec4 bsdf1;         // ior, specular, base colour (grey), 1 = entering (wo outside)
    vec4 bsdf2;         // clearcoat, clearcoat roughness, sheen colour (grey), sheen roughness
    vec4 bsdf3;         // specular colour rgb; w: the coat normal's tilt t from the shading
                        // normal, towards (0.6, 0.8, 0): (0.6 sin t, 0.8 sin t, cos t)
    vec4 bsdf4;         // anisotropy strength (along x), wo's azimuth from x (radians); media:
                        // phase g, free-flight segment length
};

#ifdef __cplusplus
static_assert(sizeof(SampleTestParams) == 128);  // lavapipe's maxPushConstantsSize
}  // namespace strata::gpu
#endif

#endif
