// What the two path tracers (pathtrace.comp and wavefront.comp) share at the
// film: the Frame uniform, the accumulation buffer (kAccumVec4PerPixel vec4
// per pixel, shared/types.h) and the RenderCounters, a pixel's sampler and
// camera ray, and the adding of a sample to its pixel's sums.
#ifndef STRATA_LIB_FILM_GLSL
#define STRATA_LIB_FILM_GLSL

#include "shared/types.h"
#include "shared/bindings.h"
#include "lib/sampler.glsl"
#include "lib/filter.glsl"

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_ACCUM) buffer AccumBuffer { vec4 accum[]; };
layout(std430, set = 0, binding = BINDING_COUNTERS) buffer CounterBuffer { RenderCounters counters; };

// Adaptive sampling (SPEC_ADAPTIVE): per 8x8 block of the image, 1 while it
// is sampled, 0 once converged (render/adaptive.h). Without the constant
// every pixel is sampled and the buffer is never read.
layout(constant_id = SPEC_ADAPTIVE) const uint kAdaptive = 0u;
layout(std430, set = 0, binding = BINDING_ACTIVE_BLOCKS) readonly buffer ActiveBlocks { uint activeBlocks[]; };
bool pixelSampled(uvec2 pixel) {
    return kAdaptive == 0u || activeBlocks[(pixel.y / 8u) * ((frame.image.x + 7u) / 8u) + pixel.x / 8u] != 0u;
}

// The sampler of sample `sampleIndex` of `pixel`.
Sampler pixelSampler(uvec2 pixel, uint sampleIndex) {
    return samplerInit(pixel, frame.image.x, sampleIndex, frame.counts.w, frame.image.w);
}

// Unit direction of the camera ray through image position `pixel` (in
// pixels from the top-left corner).
vec3 cameraRay(vec2 pixel) {
    vec2 ndc = vec2(2.0 * pixel.x / float(frame.image.x) - 1.0,
                    1.0 - 2.0 * pixel.y / float(frame.image.y));
    return normalize(frame.camForward.xyz + ndc.x * frame.camRight.xyz + ndc.y * frame.camUp.xyz);
}

#ifdef STRATA_MOTION
#include "lib/camera.glsl"
#endif

// Sample `sampleIndex` of `pixel`: its sampler, and its camera ray through a
// point drawn by filter importance sampling (weight 1) from the sampler's
// first pair: from frame.camOrigin (a pinhole), or with STRATA_MOTION at the
// sample.s time and through a point of the lens (lib/camera.glsl).
void cameraSample(uvec2 pixel, uint sampleIndex, out Sampler smp, out vec3 origin, out vec3 dir) {
    smp = pixelSampler(pixel, sampleIndex);
    vec2 offset = sampleFilter(sample2D(smp));
#ifdef STRATA_MOTION
    motionCameraRay(vec2(pixel) + 0.5 + offset, smp, origin, dir);
#else
    dir = cameraRay(vec2(pixel) + 0.5 + offset);
    origin = frame.camOrigin.xyz;
#endif
}

// Radiance L of one sample added to the sums of pixel `pixelIndex` (y * width
// + x); a sample with a NaN or infinite channel is counted and dropped.
void accumulateSample(uint pixelIndex, vec3 L) {
    if (any(isnan(L)) || any(isinf(L))) {
        atomicAdd(counters.nonFinite, 1u);
    } else {
        uint base = pixelIndex * kAccumVec4PerPixel;
        accum[base] += vec4(L, 1.0);
        accum[base + 1u] += vec4(L * L, 0.0);
    }
}

#ifdef STRATA_AOV
// The AOVs of one path (STRATA_AOV: the aov axis), recorded at its first non-delta vertex:
// the camera ray and the mirror and smooth-glass vertices it meets first are
// followed, their sampled weights multiplied into `tint`.
struct AovPath {
    vec3 tint;
    bool done;       // the first non-delta vertex, an emitter or an escape was recorded
    vec3 albedo;     // tint times the material's albedo (clamped to [0,1] when summed)
    float depth;     // the camera ray's hit distance; 0 when it escaped
    vec3 normal;     // unit shading normal, world space (camera space when summed: x right, y up,
                     // z towards the camera); 0 on escape
    float emitter;   // 1: an emitter, an unlit surface or the background was seen there
};
AovPath gAov;

void aovStart() { gAov = AovPath(vec3(1.0), false, vec3(0.0), 0.0, vec3(0.0), 0.0); }

// Records the first non-delta vertex: its albedo, its world-space shading
// normal (made camera-space by accumulateAov), whether it emits.
#define AOV_RECORD(albedo_, n_, emitter_) \
    gAov.albedo = gAov.tint * (albedo_);  \
    gAov.normal = (n_);                   \
    gAov.emitter = (emitter_);            \
    gAov.done = true

// The AOV sums of sample `sampleIndex` (radiance L) of pixel `pixelIndex`,
// after the image's own sums (kAovVec4PerPixel, shared/types.h): the
// samples accumulateSample keeps, the even-indexed ones also in half A.
void accumulateAov(uint pixelIndex, uint sampleIndex, vec3 L) {
    if (any(isnan(L)) || any(isinf(L))) return;
    vec3 albedo = clamp(gAov.albedo, 0.0, 1.0);
    vec3 right = normalize(frame.camRight.xyz), up = normalize(frame.camUp.xyz);
    vec3 n = vec3(dot(gAov.normal, right), dot(gAov.normal, up), -dot(gAov.normal, frame.camForward.xyz));
    uint base = frame.image.x * frame.image.y * kAccumVec4PerPixel + pixelIndex * kAovVec4PerPixel;
    if ((sampleIndex & 1u) == 0u) accum[base] += vec4(L, 1.0);
    accum[base + 1u] += vec4(albedo, gAov.depth);
    accum[base + 2u] += vec4(n, gAov.emitter);
    accum[base + 3u] += vec4(albedo * albedo, gAov.depth * gAov.depth);
    accum[base + 4u] += vec4(n * n, 0.0);
}

#endif  // STRATA_AOV

#endif
