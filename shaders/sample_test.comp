#version 460
// Draws samples from the GLSL sampling routines exactly as the path tracer
// calls them, for chi-square tests on the host (tests/test_sampling_glsl.cpp).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "shared/types.h"
#include "shared/bindings.h"

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
        LightSample ls = sampleEmitter(params.emitterCount, sample2D(smp));
        // Identify the emitter by its pmf-independent payload: radiance.x holds its index.
        out4.x = ls.radiance.x;
    }
    samples[i] = out4;
}
