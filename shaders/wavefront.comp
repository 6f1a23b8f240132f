#version 460
// The wavefront integrator (`--integrator wavefront`; host/render/wavefront.cpp
// drives it): pathtrace.comp's estimator split into stages, so that every
// traversal runs in trace.comp over a list of live rays. One sample of a
// tile: kStageCamera makes each pixel's camera ray and path state; then, per
// bounce, trace.comp finds the closest hits, kStageShade adds the emission
// found, appends the next-event shadow ray (with its contribution, held
// apart) and the BSDF-sampled next ray to the lists of the next stages,
// trace.comp tests the shadow rays, and kStageResolve adds the contributions
// of the unoccluded ones; kStageAccumulate adds each path's radiance to the
// film's sums. The arithmetic, its order and the sampler dimensions are
// pathtrace.comp's, vertex by vertex, and each pixel's sums are added in
// sample order as there, so the images are the same bits.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/sampler.glsl"

layout(constant_id = SPEC_HAS_EMITTERS) const uint kHasEmitters = 1u;
layout(constant_id = SPEC_MIS) const uint kMis = kMisPower;
layout(constant_id = SPEC_TRACE_MODE) const uint kStage = 0u;  // kStage* (types.h)

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };

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

layout(std430, set = 0, binding = BINDING_ACCUM) buffer AccumBuffer { vec4 accum[]; };
layout(std430, set = 0, binding = BINDING_COUNTERS) buffer CounterBuffer { RenderCounters counters; };
layout(push_constant) uniform Push { WaveParams params; };

#include "lib/lights.glsl"
#include "lib/filter.glsl"
#include "lib/bsdf.glsl"

const uint kDimsPerVertex = 8u;
const float kRayMax = 3.0e38;
const bool kLambertOnly = (kFeatures & (kFeatureSpecular | kFeatureTransmission)) == 0u;

float misWeightBsdf(bool prevDelta, float bsdfPdf, float lightPdf) {
    if (prevDelta || kMis == kMisBsdf) return 1.0;
    if (kMis == kMisLight) return 0.0;
    return powerHeuristic(bsdfPdf, lightPdf);
}

vec3 cameraRay(vec2 pixel) {
    vec2 ndc = vec2(2.0 * pixel.x / float(frame.image.x) - 1.0,
                    1.0 - 2.0 * pixel.y / float(frame.image.y));
    return normalize(frame.camForward.xyz + ndc.x * frame.camRight.xyz + ndc.y * frame.camUp.xyz);
}

void cameraStage(uint k) {
    uvec2 pixel = uvec2(params.tileX + k % params.tileW, params.tileY + k / params.tileW);
    Sampler smp = samplerInit(pixel, frame.image.x, params.sampleIndex, frame.counts.w, frame.image.w);
    vec2 offset = sampleFilter(sample2D(smp));
    vec3 dir = cameraRay(vec2(pixel) + 0.5 + offset);
    uint pixelIndex = pixel.y * frame.image.x + pixel.x;
    state[k] = PathState(vec4(1.0, 1.0, 1.0, 0.0), vec4(0.0, 0.0, 0.0, 1.0), uvec4(pixelIndex, 0u, 1u, 0u));
    nextRays[k] = TraceRay(frame.camOrigin.xyz, 0.0, dir, kRayMax);
    nextLive[k] = k;
}

void shadeStage(uint k) {
    uint slot = live[k];
    PathState st = state[slot];
    TraceHit hit = hits[k];
    TraceRay ray = inRays[k];
    vec3 dir = ray.dir;
    vec3 beta = st.betaPdf.xyz;
    float prevBsdfPdf = st.betaPdf.w;
    vec3 L = st.lDelta.xyz;
    bool prevDelta = st.lDelta.w != 0.0;
    uint depth = st.misc.y;
    bool alive = false;
    bool hasShadow = false;
    TraceRay next, shadow;
    vec3 contrib = vec3(0.0);
    const uint maxDepth = frame.image.z;
    const bool lightSampling = kHasEmitters != 0u && kMis != kMisBsdf;

    if (hit.triangle == kNoHit) {
        if (kHasEmitters != 0u && hasFeature(kFeatureEnvironment)) {
            float w = misWeightBsdf(prevDelta, prevBsdfPdf, prevDelta ? 0.0 : lightPdfEnvironment(dir));
            L += beta * w * environmentRadiance(dir);
        }
    } else {
        TriVerts tv = bvhFetchTri(hit.triangle);
        vec3 e1 = tv.v1.xyz - tv.v0.xyz, e2 = tv.v2.xyz - tv.v0.xyz;
        vec3 ng = normalize(cross(e1, e2));
        bool front = dot(dir, ng) < 0.0;
        TriShading sh = sceneShading(hit.triangle);
        Material mat = sceneMaterial(sh.material);
        if (kHasEmitters != 0u && sh.light != kNoLight) {
            if (front || (mat.flags & kMaterialDoubleSided) != 0u) {
                float lightPdf = prevDelta ? 0.0 : lightPdfTriangle(sh.light, hit.t, abs(dot(dir, ng)));
                float w = misWeightBsdf(prevDelta, prevBsdfPdf, lightPdf);
                L += beta * w * emissionAt(sh.material, hit.triangle, vec2(hit.u, hit.v));
            }
        }
        if (depth < maxDepth) {
            uvec2 pixel = uvec2(st.misc.x % frame.image.x, st.misc.x / frame.image.x);
            Sampler smp = samplerInit(pixel, frame.image.x, params.sampleIndex, frame.counts.w, frame.image.w);
            vec3 n = front ? ng : -ng;
            vec3 wo = -dir;
            vec3 ns = normalize((1.0 - hit.u - hit.v) * sh.n0 + hit.u * sh.n1 + hit.v * sh.n2);
            if (dot(ns, n) < 0.0) ns = -ns;
            SurfacePoint sp = surfacePoint(mat, hit.triangle, vec2(hit.u, hit.v), n, ns);
            ns = sp.ns;
            if (dot(ns, wo) <= 0.0) ns = n;
            vec3 t, b;
            basis(ns, t, b);
            vec3 woL = vec3(dot(wo, t), dot(wo, b), dot(wo, ns));
            Bsdf bsdf;
            if (kLambertOnly) {
                bsdf = makeLambert(sp.baseColor);
            } else {
                bsdf = makeBsdf(sp.baseColor, sp.metallic, sp.roughness, sp.transmission, sp.ior,
                                sp.specular, front, woL.z);
            }
            vec3 p = tv.v0.xyz + hit.u * e1 + hit.v * e2;
            samplerSetDim(smp, 2u + depth * kDimsPerVertex);
            if (lightSampling) {
                LightSample ls = sampleLight(p, sample2D(smp));
                vec3 wiL = vec3(dot(ls.wi, t), dot(ls.wi, b), dot(ls.wi, ns));
                float geoSide = dot(n, ls.wi);
                if (ls.pdf > 0.0 && any(greaterThan(ls.Li, vec3(0.0))) && geoSide != 0.0 &&
                    (geoSide > 0.0) == (wiL.z > 0.0)) {
                    float bsdfPdf;
                    vec3 f = evalBsdf(bsdf, woL, wiL, bsdfPdf);
                    if (any(greaterThan(f, vec3(0.0)))) {
                        vec3 from = spawnOrigin(tv, hit.u, hit.v, geoSide > 0.0 ? n : -n);
                        vec3 shadowDir = ls.wi;
                        float shadowMax = kRayMax;
                        bool open = true;
                        if (ls.dist < kLightFar) {
                            vec3 seg = ls.target - from;
                            float segLen = length(seg);
                            open = segLen > 0.0;
                            shadowDir = open ? seg / segLen : ls.wi;
                            shadowMax = segLen;
                        }
                        if (open) {
                            float w = ls.isDelta || kMis == kMisLight ? 1.0 : powerHeuristic(ls.pdf, bsdfPdf);
                            shadow = TraceRay(from, 0.0, shadowDir, shadowMax);
                            contrib = beta * f * ls.Li * (w / ls.pdf);
                            hasShadow = true;
                        }
                    }
                }
            }
            samplerSetDim(smp, 2u + depth * kDimsPerVertex + 2u);
            float uLobe = sample1D(smp);
            BsdfSample bs = sampleBsdf(bsdf, woL, uLobe, sample2D(smp));
            if (bs.valid) {
                vec3 wi = bs.wi.x * t + bs.wi.y * b + bs.wi.z * ns;
                float geoSide = dot(n, wi);
                if (!(geoSide == 0.0 || (geoSide > 0.0) != (bs.wi.z > 0.0))) {
                    beta *= bs.weight;
                    prevBsdfPdf = bs.pdf;
                    prevDelta = bs.delta;
                    float u = sample1D(smp);
                    alive = true;
                    if (depth >= 3u) {
                        float q = max(0.05, 1.0 - max(beta.r, max(beta.g, beta.b)));
                        if (u < q) alive = false;
                        else beta /= 1.0 - q;
                    }
                    next = TraceRay(spawnOrigin(tv, hit.u, hit.v, geoSide > 0.0 ? n : -n), 0.0, wi, kRayMax);
                }
            }
        }
    }
    state[slot] = PathState(vec4(beta, prevBsdfPdf), vec4(L, prevDelta ? 1.0 : 0.0),
                            uvec4(st.misc.x, depth + 1u, alive ? 1u : 0u, 0u));
    uint ni = appendIndex(0u, alive);
    if (alive) {
        nextRays[ni] = next;
        nextLive[ni] = slot;
    }
    uint si = appendIndex(1u, hasShadow);
    if (hasShadow) {
        shadowRays[si] = shadow;
        shadowContrib[si] = vec4(contrib, 1.0);
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

// Path k's radiance into its pixel's sums, as pathtrace.comp's shadePixel.
void accumulateStage(uint k) {
    vec3 L = state[k].lDelta.xyz;
    if (any(isnan(L)) || any(isinf(L))) {
        atomicAdd(counters.nonFinite, 1u);
        return;
    }
    uint base = state[k].misc.x * kAccumVec4PerPixel;
    accum[base] += vec4(L, 1.0);
    accum[base + 1u] += vec4(L * L, 0.0);
}

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= params.count) return;
    if (kStage == kStageCamera) cameraStage(k);
    else if (kStage == kStageResolve) resolveStage(k);
    else if (kStage == kStageAccumulate) accumulateStage(k);
    else shadeStage(k);
}
