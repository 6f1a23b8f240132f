#version 460
// The wavefront integrator (`--integrator wavefront`; host/integrate/wavefront.cpp
// drives it): pathtrace.comp's estimator split into stages, so that every
// traversal runs in trace.comp over a list of live rays. One sample of a
// tile: kStageCamera makes each pixel's camera ray and path state; then, per
// bounce, trace.comp finds the closest hits, kStageShade adds the emission
// found, appends the next-event shadow ray (with its contribution, held
// apart) and the BSDF-sampled next ray to the lists of the next stages,
// trace.comp tests the shadow rays, and kStageResolve adds the contributions
// of the unoccluded ones; kStageAccumulate adds each path's radiance to the
// film's sums. A vertex is shaded by lib/path.glsl's pathShadeHit, as in
// pathtrace.comp, the shadow ray's contribution is added after the
// emission found there, as there, and each pixel's sums are added in
// sample order, so the images are the same bits.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/film.glsl"

layout(constant_id = SPEC_HAS_EMITTERS) const uint kHasEmitters = 1u;
layout(constant_id = SPEC_MIS) const uint kMis = kMisPower;
layout(constant_id = SPEC_WAVE_STAGE) const uint kStage = kStageCamera;  // kStage* (types.h)
// Adaptive sampling: lib/film.glsl's pixelSampled, for a pixel's index.
bool pixelActive(uint pixelIndex) {
    return pixelSampled(uvec2(pixelIndex % frame.image.x, pixelIndex / frame.image.x));
}

layout(std430, set = 0, binding = BINDING_WAVE_STATE) buffer StateBuffer { PathState state[]; };
layout(std430, set = 0, binding = BINDING_WAVE_LIVE) readonly buffer LiveBuffer { uint live[]; };
layout(std430, set = 0, binding = BINDING_WAVE_HITS) readonly buffer HitBuffer { TraceHit hits[]; };
layout(std430, set = 0, binding = BINDING_WAVE_NEXT_RAYS) writeonly buffer NextBuffer { TraceRay nextRays[]; };
layout(std430, set = 0, binding = BINDING_WAVE_SHADOW_RAYS) writeonly buffer ShadowBuffer { TraceRay shadowRays[]; };
layout(std430, set = 0, binding = BINDING_WAVE_CONTRIB) buffer ContribBuffer { vec4 shadowContrib[]; };
layout(std430, set = 0, binding = BINDING_WAVE_RAYS) readonly buffer InBuffer { TraceRay inRays[]; };
layout(std430, set = 0, binding = BINDING_WAVE_NEXT_LIVE) writeonly buffer NextLiveBuffer { uint nextLive[]; };
layout(std430, set = 0, binding = BINDING_WAVE_SHADOW_SLOTS) buffer ShadowSlotBuffer { uint shadowSlot[]; };
layout(std430, set = 0, binding = BINDING_WAVE_COUNTS) buffer CountBuffer { uint counts[]; };  // next rays, shadow rays
layout(std430, set = 0, binding = BINDING_WAVE_SHADOW_HITS) readonly buffer ShadowHitBuffer { TraceHit shadowHits[]; };
#ifdef STRATA_INSTANCING
layout(std430, set = 0, binding = BINDING_HIT_INSTANCES) readonly buffer HitInstanceBuffer { uint hitInstances[]; };
#endif
#ifdef STRATA_LIGHT_TREE
// Each path's PathVertex prevP and prevN (the light tree's probability of
// an emitter a BSDF ray finds) between bounces, two entries a path.
layout(std430, set = 0, binding = BINDING_WAVE_TREE_VERTEX) buffer TreeVertexBuffer { vec4 treeVertex[]; };
#endif
#ifdef STRATA_TEXTURE_LOD
// Each path's ray cone (lib/path.glsl gConeWidth, gConeSpread) between bounces.
layout(std430, set = 0, binding = BINDING_WAVE_CONES) buffer ConeBuffer { vec2 cones[]; };
#endif

// This lane's place in a list that the subgroup's wanting lanes append to
// together: one atomic per subgroup.
uint appendIndex(uint word, bool want) {
    uvec4 ballot = subgroupBallot(want);
    uint total = subgroupBallotBitCount(ballot);
    uint base = 0u;
    if (subgroupElect() && total > 0u) base = atomicAdd(counts[word], total);
    base = subgroupBroadcastFirst(base);
    return base + subgroupBallotExclusiveBitCount(ballot);
}

layout(push_constant) uniform Push { WaveParams params; };

#include "lib/lights.glsl"
#include "lib/bsdf.glsl"
#include "lib/path.glsl"

void cameraStage(uint k) {
    uvec2 pixel = uvec2(params.tileX + k % params.tileW, params.tileY + k / params.tileW);
    Sampler smp;
    vec3 dir;
    vec3 origin;
    cameraSample(pixel, params.sampleIndex, smp, origin, dir);
    uint pixelIndex = pixel.y * frame.image.x + pixel.x;
    state[k] = PathState(vec4(1.0, 1.0, 1.0, 0.0), vec4(0.0, 0.0, 0.0, 1.0), uvec4(pixelIndex, 0u, 1u, 0u));
#ifdef STRATA_TEXTURE_LOD
    cones[k] = vec2(0.0, cameraConeSpread());
#endif
#ifdef STRATA_LIGHT_TREE
    treeVertex[2u * k] = vec4(0.0);
    treeVertex[2u * k + 1u] = vec4(0.0);
#endif
    if (kAdaptive == 0u) {
        nextRays[k] = TraceRay(origin, 0.0, dir, kRayMax);
        nextLive[k] = k;
        return;
    }
    // Adaptive: only the paths of blocks still sampled go on (the host reads
    // their count); the others are never traced or accumulated.
    bool sampled = pixelActive(pixelIndex);
    uint i = appendIndex(0u, sampled);
    if (sampled) {
        nextRays[i] = TraceRay(origin, 0.0, dir, kRayMax);
        nextLive[i] = k;
    }
}

void shadeStage(uint k) {
    uint slot = live[k];
    PathState st = state[slot];
    vec3 dir = inRays[k].dir;
    PathVertex v = pathStart();
    v.beta = st.betaPdf.xyz;
    v.L = st.lDelta.xyz;
    v.prevBsdfPdf = st.betaPdf.w;
    v.prevDelta = st.lDelta.w != 0.0;
#ifdef STRATA_LIGHT_TREE
    v.prevP = treeVertex[2u * slot].xyz;
    v.prevN = treeVertex[2u * slot + 1u].xyz;
#endif
#ifdef STRATA_DISPERSION
    gWavelength = uintBitsToFloat(st.misc.w);  // 0 until the path reaches a dispersive surface
#endif
    uint depth = st.misc.y;
    uvec2 pixel = uvec2(st.misc.x % frame.image.x, st.misc.x / frame.image.x);
    Sampler smp = pixelSampler(pixel, params.sampleIndex);
    PathNext o;
    o.shadowOpen = false;
    o.alive = false;
    TraceHit hit = hits[k];
#ifdef STRATA_TEXTURE_LOD
    gConeWidth = cones[slot].x;
    gConeSpread = cones[slot].y;
#endif
#ifdef STRATA_INSTANCING
    gHitInstance = hitInstances[k];  // the trace kernel's, for pathShadeHit
#endif
    if (hit.triangle == kNoHit) pathEscaped(v, dir);
    else o = pathShadeHit(v, smp, dir, hit, depth);
    state[slot] = PathState(vec4(v.beta, v.prevBsdfPdf), vec4(v.L, v.prevDelta ? 1.0 : 0.0),
                            uvec4(st.misc.x, depth + 1u, o.alive ? 1u : 0u, 0u));
#ifdef STRATA_DISPERSION
    state[slot].misc.w = floatBitsToUint(gWavelength);
#endif
#ifdef STRATA_TEXTURE_LOD
    cones[slot] = vec2(gConeWidth, gConeSpread);
#endif
#ifdef STRATA_LIGHT_TREE
    treeVertex[2u * slot] = vec4(v.prevP, 0.0);
    treeVertex[2u * slot + 1u] = vec4(v.prevN, 0.0);
#endif
    uint ni = appendIndex(0u, o.alive);
    if (o.alive) {
        nextRays[ni] = o.next;
        nextLive[ni] = slot;
    }
    uint si = appendIndex(1u, o.shadowOpen);
    if (o.shadowOpen) {
        shadowRays[si] = o.shadow;
        shadowContrib[si] = vec4(o.contrib, 1.0);
        shadowSlot[si] = slot;
    }
}

// The unoccluded shadow rays' contributions, each to its path's L (a path
// has at most one shadow ray a bounce).
void resolveStage(uint j) {
    if (shadowHits[j].triangle != kNoHit) return;
    uint slot = shadowSlot[j];
    state[slot].lDelta.xyz += shadowContrib[j].xyz;
}

// Path k's radiance into its pixel's sums.
void accumulateStage(uint k) {
    uint pixelIndex = state[k].misc.x;
    if (pixelActive(pixelIndex)) accumulateSample(pixelIndex, state[k].lDelta.xyz);
}

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= params.count) return;
    if (kStage == kStageCamera) cameraStage(k);
    else if (kStage == kStageResolve) resolveStage(k);
    else if (kStage == kStageAccumulate) accumulateStage(k);
    else shadeStage(k);
}
