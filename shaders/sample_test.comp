#version 460
// Draws samples from the GLSL sampling routines exactly as the path tracer
// calls them, for chi-square tests on the host (tests/test_sampling_glsl.cpp).
#extension GL_GOOGLE_include_directive : require
#define STRATA_LAYERS  // the BSDF's layers, under their feature bits (lib/features.glsl)

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "shared/types.h"
#include "shared/sample_test.h"
#include "shared/bindings.h"

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_SAMPLES) writeonly buffer SampleBuffer { vec4 samples[]; };
layout(push_constant) uniform Push { SampleTestParams params; };

#include "lib/sampler.glsl"
#include "lib/lights.glsl"
#include "lib/filter.glsl"
#include "lib/bsdf.glsl"
#include "lib/medium.glsl"
#ifdef STRATA_DISPERSION
#include "lib/spectrum.glsl"
#endif

Bsdf testBsdf(out vec3 wo) {
    float c = params.bsdf0.x;
    float s = sqrt(max(0.0, 1.0 - c * c));
    wo = params.bsdf4.y == 0.0 ? vec3(s, 0.0, c) : vec3(s * cos(params.bsdf4.y), s * sin(params.bsdf4.y), c);
    BsdfLayers layers = noLayers();
    layers.coat = params.bsdf2.x;
    layers.coatRoughness = params.bsdf2.y;
    float tilt = params.bsdf3.w;
    layers.coatNormal = vec3(0.6 * sin(tilt), 0.8 * sin(tilt), cos(tilt));
    layers.sheenColor = vec3(params.bsdf2.z);
    layers.sheenRoughness = params.bsdf2.w;
    layers.specularColor = params.bsdf3.xyz;
#ifdef STRATA_ANISOTROPY
    layers.anisotropy = params.bsdf4.x;
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
    layers.diffuseTransmission = params.diffTrans;
    layers.diffuseTransmissionColor = vec3(params.diffTransColor);
#endif
    return makeBsdf(vec3(params.bsdf1.z), params.bsdf0.z, params.bsdf0.y, params.bsdf0.w,
                    params.bsdf1.x, params.bsdf1.y, layers, params.bsdf1.w != 0.0, wo);
}

// 8-point Gauss-Legendre nodes and weights on [-1, 1] (positive half).
const float kGlNode[4] = float[4](0.18343464249564980, 0.52553240991632899,
                                  0.79666647741362674, 0.96028985649753623);
const float kGlWeight[4] = float[4](0.36268378337836198, 0.31370664587788729,
                                    0.22238103445337447, 0.10122853629037626);

// Integral of the BSDF sampling density over cell i of a theta x phi grid,
// by 8 x 8 Gauss-Legendre quadrature in (theta, phi) with the sin(theta)
// Jacobian.
float pdfCellIntegral(uint i) {
    vec3 wo;
    Bsdf b = testBsdf(wo);
    uint rt = params.pixelX, rp = params.pixelY;
    uint it = i / rp, ip = i % rp;
    float dt = kPi / float(rt), dp = 2.0 * kPi / float(rp);
    float t0 = float(it) * dt, p0 = float(ip) * dp;
    float sum = 0.0;
    for (int a = 0; a < 8; ++a) {
        float na = a < 4 ? -kGlNode[3 - a] : kGlNode[a - 4];
        float wa = a < 4 ? kGlWeight[3 - a] : kGlWeight[a - 4];
        float theta = t0 + dt * 0.5 * (1.0 + na);
        for (int c = 0; c < 8; ++c) {
            float nc = c < 4 ? -kGlNode[3 - c] : kGlNode[c - 4];
            float wc = c < 4 ? kGlWeight[3 - c] : kGlWeight[c - 4];
            float phi = p0 + dp * 0.5 * (1.0 + nc);
            vec3 wi = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            float pdf;
            evalBsdf(b, wo, wi, pdf);
            sum += wa * wc * pdf * sin(theta);
        }
    }
    return sum * 0.25 * dt * dp;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    vec4 out4 = vec4(0.0);
    if (params.routine == kSamplePixel) {
        uint columns = max(params.blockWidth, 1u);
        uint p = i / params.spp;
        uvec2 pixel = uvec2(params.pixelX + p % columns, params.pixelY + p / columns);
        Sampler ps = samplerInit(pixel, params.width, i % params.spp, params.spp, params.seed);
        out4.xy = sample2D(ps);
        samplerSetDim(ps, 2u);  // the first path vertex's light choice pair
        out4.zw = sample2D(ps);
        samples[i] = out4;
        return;
    }
    if (params.routine == kBsdfPdfCells) {
        samples[i] = vec4(pdfCellIntegral(i), 0.0, 0.0, 0.0);
        return;
    }
    // The warps below take independent numbers (SPEC_SAMPLER left at 0).
    Sampler smp = samplerInit(uvec2(i, 0u), 0u, 0u, 1u, params.seed);
    if (params.routine == kSampleCosineHemisphere) {
        out4.xyz = sampleCosineHemisphere(sample2D(smp));
    } else if (params.routine == kSampleTriangle) {
        out4.xy = sampleTriangle(sample2D(smp));
    } else if (params.routine == kSampleFilter) {
        out4.xy = sampleFilter(sample2D(smp));
    } else if (params.routine == kSampleEmitterChoice) {
        float rest;
        // Identify the emitter by its pmf-independent payload: radiance.x holds its index.
        out4.x = emitterAt(chooseLight(params.emitterCount, sample2D(smp).x, rest)).radiance.x;
    } else if (params.routine == kSampleLight) {
#ifdef STRATA_LIGHT_TREE
        vec2 u = sample2D(smp);
        LightSample ls = sampleLight(params.bsdf0.xyz, params.bsdf1.xyz, u, sample1D(smp));
#else
        LightSample ls = sampleLight(vec3(0.0), sample2D(smp));
#endif
        out4 = vec4(ls.wi, ls.pdf);
#ifdef STRATA_LIGHT_TREE
    } else if (params.routine == kSampleLightTree) {
        float pmf;
        float leafImportance;
        uint light = sampleLightTree(params.bsdf0.xyz, params.bsdf1.xyz, sample1D(smp), pmf, leafImportance);
        out4.x = light == kNoLight ? -1.0 : float(light);
        out4.y = pmf;
        out4.z = light == kNoLight ? 0.0 : lightTreePmf(params.bsdf0.xyz, params.bsdf1.xyz, emitterAt(light).trail);
    } else if (params.routine == kLightTreePmf) {
        out4.x = lightTreePmf(params.bsdf0.xyz, params.bsdf1.xyz, emitterAt(i).trail);
#endif
    } else if (params.routine == kSampleEnvironmentPdf) {
        uint rows = params.count / params.width;
        vec2 c = (vec2(i % params.width, i / params.width) + 0.5) / vec2(params.width, rows);
        float z = 2.0 * c.y - 1.0, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * c.x;
        vec3 d = vec3(r * cos(phi), r * sin(phi), z);
        out4 = vec4(d, lightPdfEnvironment(d));
    } else if (params.routine == kSamplePhase) {
        float pdf;
        out4.xyz = samplePhaseHG(vec3(0.0, 0.0, 1.0), params.bsdf4.z, sample2D(smp), pdf);
        out4.w = pdf;
    } else if (params.routine == kSampleFreeFlight) {
        float t;
        out4.yzw = mediumFreeFlight(params.bsdf3.xyz, params.bsdf2.xyz, params.bsdf1.xyz, params.bsdf4.w,
                                    sample1D(smp), t);
        out4.x = t;
#ifdef STRATA_DISPERSION
    } else if (params.routine == kSampleWavelength) {
        float lambda = sampleVisibleWavelength(sample1D(smp));
        out4 = vec4(lambda, wavelengthRgb(lambda) / visibleWavelengthPdf(lambda));
    } else if (params.routine == kWavelengthFunctions) {
        float lambda = params.bsdf4.x + float(i) * params.bsdf4.y;
        out4 = vec4(visibleWavelengthPdf(lambda), wavelengthRgb(lambda));
#endif
    } else if (params.routine == kSampleBsdf || params.routine == kSampleBsdfWeight) {
        vec3 wo;
        Bsdf b = testBsdf(wo);
        float uLobe = sample1D(smp);
        BsdfSample bs = sampleBsdf(b, wo, uLobe, sample2D(smp));
        if (params.routine == kSampleBsdf) {
            out4 = vec4(bs.wi, bs.valid ? 1.0 : 0.0);
        } else if (!bs.valid) {
            out4 = vec4(-1.0, 0.0, 0.0, 0.0);
        } else if (bs.delta) {
            out4 = vec4(bs.weight.r, -1.0, -1.0, -1.0);
        } else {
            float pdf;
            vec3 f = evalBsdf(b, wo, bs.wi, pdf);
            out4 = vec4(bs.weight.r, pdf > 0.0 ? f.r / pdf : 0.0, bs.pdf, pdf);
        }
    }
    samples[i] = out4;
}
