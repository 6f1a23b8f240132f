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

#include "lib/rng.glsl"
#include "lib/lights.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    Sampler smp = samplerInit(i, 0u, params.seed);
    vec4 out4 = vec4(0.0);
    if (params.routine == kSampleCosineHemisphere) {
        out4.xyz = sampleCosineHemisphere(sample2D(smp));
    } else if (params.routine == kSampleTriangle) {
        out4.xy = sampleTriangle(sample2D(smp));
    } else if (params.routine == kSampleEmitterChoice) {
        LightSample ls = sampleEmitter(params.emitterCount, sample2D(smp), sample2D(smp));
        // Identify the emitter by its pmf-independent payload: radiance.x holds its index.
        out4.x = ls.radiance.x;
    }
    samples[i] = out4;
}
