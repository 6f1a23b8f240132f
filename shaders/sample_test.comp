#version 460
// Draws samples from the GLSL sampling routines exactly as the path tracer
// calls them, for chi-square tests on the host (tests/test_sampling_glsl.cpp).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "shared/types.h"
#include "shared/bindings.h"

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_EMITTERS) readonly buffer EmitterBuffer { Emitter emitters[]; };
layout(std430, set = 0, binding = BINDING_SAMPLES) writeonly buffer SampleBuffer { vec4 samples[]; };
layout(push_constant) uniform Push { SampleTestParams params; };

#include "lib/sampler.glsl"
#include "lib/lights.glsl"
#include "lib/filter.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    vec4 out4 = vec4(0.0);
    if (params.routine == kSamplePixel) {
        Sampler ps = samplerInit(uvec2(params.pixelX, params.pixelY), params.width, i, params.spp, params.seed);
        out4.xy = sample2D(ps);
        samplerSetDim(ps, 2u);  // the first path vertex's light choice pair
        out4.zw = sample2D(ps);
        samples[i] = out4;
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
        out4.x = emitters[chooseLight(params.emitterCount, sample2D(smp).x, rest)].radiance.x;
    } else if (params.routine == kSampleLight) {
        LightSample ls = sampleLight(vec3(0.0), sample2D(smp));
        out4 = vec4(ls.wi, ls.pdf);
    } else if (params.routine == kSampleEnvironmentPdf) {
        uint rows = params.count / params.width;
        vec2 c = (vec2(i % params.width, i / params.width) + 0.5) / vec2(params.width, rows);
        float z = 2.0 * c.y - 1.0, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * c.x;
        vec3 d = vec3(r * cos(phi), r * sin(phi), z);
        out4 = vec4(d, lightPdfEnvironment(d));
    }
    samples[i] = out4;
}
