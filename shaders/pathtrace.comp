#version 460
// Progressive path tracer: one path per pixel of the dispatch's tile, one
// sample per dispatch, added into the accumulation buffer (sum, count, sum of
// squares). The glTF BSDF (lib/bsdf.glsl; plain Lambert when no material has
// a specular or transmission lobe); next-event estimation on all lights
// (emissive triangles, KHR_lights_punctual, the environment; lib/lights.glsl)
// combined with BSDF sampling by the power heuristic (Veach 1997; delta
// lights and delta lobes take no MIS; SPEC_MIS can keep one technique only);
// Russian roulette after depth 3. maxDepth counts scattering events (pbrt's
// convention): 0 shows emitters and the environment seen directly, 1 is
// direct lighting.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/sampler.glsl"

layout(constant_id = SPEC_HAS_EMITTERS) const uint kHasEmitters = 1u;  // any light at all
layout(constant_id = SPEC_MIS) const uint kMis = kMisPower;             // kMis* (types.h)
layout(constant_id = SPEC_COUNT_RAYS) const uint kCountRays = 1u;       // count rays in RenderCounters
layout(constant_id = SPEC_WORK_QUEUE) const uint kWorkQueue = 0u;       // 1: blocks in a permuted order

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_ACCUM) buffer AccumBuffer { vec4 accum[]; };
layout(std430, set = 0, binding = BINDING_COUNTERS) buffer CounterBuffer { RenderCounters counters; };
layout(push_constant) uniform Push { DispatchParams params; };

#include "lib/lights.glsl"
#include "lib/filter.glsl"
#include "lib/bsdf.glsl"

// Dimensions: 0-1 pixel position; then kDimsPerVertex per path vertex, in
// 2D pairs: light choice and point, BSDF lobe (1D in a pair), BSDF
// direction, roulette (1D in a pair).
const uint kDimsPerVertex = 8u;
const float kRayMax = 3.0e38;

// Rays this invocation traced (SPEC_COUNT_RAYS).
uint gClosestRays = 0u;
uint gShadowRays = 0u;

vec3 cameraRay(vec2 pixel) {
    vec2 ndc = vec2(2.0 * pixel.x / float(frame.image.x) - 1.0,
                    1.0 - 2.0 * pixel.y / float(frame.image.y));
    return normalize(frame.camForward.xyz + ndc.x * frame.camRight.xyz + ndc.y * frame.camUp.xyz);
}

// Lambert only: no material of the scene has a specular or transmission lobe.
const bool kLambertOnly = (kFeatures & (kFeatureSpecular | kFeatureTransmission)) == 0u;

// MIS weight of a light found by BSDF sampling with density bsdfPdf, which
// light sampling finds with density lightPdf.
float misWeightBsdf(bool prevDelta, float bsdfPdf, float lightPdf) {
    if (prevDelta || kMis == kMisBsdf) return 1.0;
    if (kMis == kMisLight) return 0.0;
    return powerHeuristic(bsdfPdf, lightPdf);
}

vec3 tracePath(inout Sampler smp, vec3 origin, vec3 dir) {
    const uint maxDepth = frame.image.z;
    const bool lightSampling = kHasEmitters != 0u && kMis != kMisBsdf;
    vec3 L = vec3(0.0);
    vec3 beta = vec3(1.0);
    float prevBsdfPdf = 0.0;
    bool prevDelta = true;  // the camera ray: emitters it finds get weight 1

    for (uint depth = 0u;; ++depth) {
        TraceHit hit;
        if (kCountRays != 0u) ++gClosestRays;
        if (!bvhTraceClosest(origin, dir, 0.0, kRayMax, hit)) {
            // Escaped: the environment, weighted against light sampling.
            if (kHasEmitters != 0u && hasFeature(kFeatureEnvironment)) {
                float w = misWeightBsdf(prevDelta, prevBsdfPdf, prevDelta ? 0.0 : lightPdfEnvironment(dir));
                L += beta * w * environmentRadiance(dir);
            }
            break;
        }

        TriVerts tv = bvhFetchTri(hit.triangle);
        vec3 e1 = tv.v1.xyz - tv.v0.xyz, e2 = tv.v2.xyz - tv.v0.xyz;
        vec3 ng = normalize(cross(e1, e2));
        bool front = dot(dir, ng) < 0.0;
        TriShading sh = sceneShading(hit.triangle);
        Material mat = sceneMaterial(sh.material);

        // Emission found by the previous vertex's BSDF sample (or directly).
        if (kHasEmitters != 0u && sh.light != kNoLight) {
            if (front || (mat.flags & kMaterialDoubleSided) != 0u) {
                float lightPdf = prevDelta ? 0.0 : lightPdfTriangle(sh.light, hit.t, abs(dot(dir, ng)));
                float w = misWeightBsdf(prevDelta, prevBsdfPdf, lightPdf);
                L += beta * w * emissionAt(sh.material, hit.triangle, vec2(hit.u, hit.v));
            }
        }
        if (depth >= maxDepth) break;

        vec3 n = front ? ng : -ng;  // geometric normal on the incoming side
        vec3 wo = -dir;
        vec3 ns = normalize((1.0 - hit.u - hit.v) * sh.n0 + hit.u * sh.n1 + hit.v * sh.n2);
        if (dot(ns, n) < 0.0) ns = -ns;
        SurfacePoint sp = surfacePoint(mat, hit.triangle, vec2(hit.u, hit.v), n, ns);
        ns = sp.ns;
        if (dot(ns, wo) <= 0.0) ns = n;  // the viewer is behind the shading normal
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

        // Next-event estimation: one light sample, one shadow ray.
        if (lightSampling) {
            LightSample ls = sampleLight(p, sample2D(smp));
            vec3 wiL = vec3(dot(ls.wi, t), dot(ls.wi, b), dot(ls.wi, ns));
            float geoSide = dot(n, ls.wi);
            // The shading and geometric normals must agree on the side wi leaves to.
            if (ls.pdf > 0.0 && any(greaterThan(ls.Li, vec3(0.0))) && geoSide != 0.0 &&
                (geoSide > 0.0) == (wiL.z > 0.0)) {
                float bsdfPdf;
                vec3 f = evalBsdf(bsdf, woL, wiL, bsdfPdf);
                if (any(greaterThan(f, vec3(0.0)))) {
                    vec3 from = spawnOrigin(tv, hit.u, hit.v, geoSide > 0.0 ? n : -n);
                    if (kCountRays != 0u) ++gShadowRays;
                    // One call site for both kinds of light (each call is
                    // inlined: a second copy of the traversal cost ~20% of
                    // pipeline creation on lavapipe).
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
                    bool visible = open && !bvhTraceAny(from, shadowDir, 0.0, shadowMax);
                    if (visible) {
                        float w = ls.isDelta || kMis == kMisLight ? 1.0 : powerHeuristic(ls.pdf, bsdfPdf);
                        L += beta * f * ls.Li * (w / ls.pdf);
                    }
                }
            }
        }

        // BSDF sampling: lobe choice, direction, then Russian roulette.
        samplerSetDim(smp, 2u + depth * kDimsPerVertex + 2u);
        float uLobe = sample1D(smp);
        BsdfSample bs = sampleBsdf(bsdf, woL, uLobe, sample2D(smp));
        if (!bs.valid) break;
        vec3 wi = bs.wi.x * t + bs.wi.y * b + bs.wi.z * ns;
        float geoSide = dot(n, wi);
        if (geoSide == 0.0 || (geoSide > 0.0) != (bs.wi.z > 0.0)) break;
        beta *= bs.weight;
        prevBsdfPdf = bs.pdf;
        prevDelta = bs.delta;

        // Russian roulette after depth 3, survival probability max(beta) (>= 0.05).
        float u = sample1D(smp);
        if (depth >= 3u) {
            float q = max(0.05, 1.0 - max(beta.r, max(beta.g, beta.b)));
            if (u < q) break;
            beta /= 1.0 - q;
        }
        origin = spawnOrigin(tv, hit.u, hit.v, geoSide > 0.0 ? n : -n);
        dir = wi;
    }
    return L;
}

// One path through pixel `local` of the dispatch's tile, added to its sums.
void shadePixel(uvec2 local) {
    if (local.x >= params.tileW || local.y >= params.tileH) return;
    uvec2 pixel = uvec2(params.tileX, params.tileY) + local;
    uint pixelIndex = pixel.y * frame.image.x + pixel.x;

    Sampler smp = samplerInit(pixel, frame.image.x, params.sampleIndex, frame.counts.w, frame.image.w);
    vec2 offset = sampleFilter(sample2D(smp));  // filter importance sampling, weight 1
    vec3 dir = cameraRay(vec2(pixel) + 0.5 + offset);
    vec3 L = tracePath(smp, frame.camOrigin.xyz, dir);

    if (any(isnan(L)) || any(isinf(L))) {
        atomicAdd(counters.nonFinite, 1u);
        return;
    }
    uint base = pixelIndex * kAccumVec4PerPixel;
    accum[base] += vec4(L, 1.0);
    accum[base + 1u] += vec4(L * L, 0.0);
}

void main() {
    uvec2 local = gl_GlobalInvocationID.xy;
    if (kWorkQueue != 0u) {
        // lavapipe gives each thread one contiguous share of the workgroups:
        // with blocks in row order, one thread took the tile's top rows and
        // the other its bottom ones, and one waited for the other. Workgroup
        // w shades block (w * blockStride) mod blocks instead (a permutation;
        // each share spreads over the whole tile). A path's loops cannot be
        // bounded, so the trace kernel's work queue, which runs many in one
        // invocation, is not an option here (lib/bvh.glsl, gBvhTicks).
        uint blocksX = (params.tileW + 7u) / 8u, blocks = blocksX * ((params.tileH + 7u) / 8u);
        uint w = (gl_WorkGroupID.y * blocksX + gl_WorkGroupID.x) * params.blockStride % blocks;
        local = uvec2(w % blocksX, w / blocksX) * 8u + gl_LocalInvocationID.xy;
    }
    shadePixel(local);
    if (kCountRays != 0u) {
        // One pair of atomics per subgroup; a carry into the high word when the low one wraps.
        uint closest = subgroupAdd(gClosestRays), shadow = subgroupAdd(gShadowRays);
        if (subgroupElect()) {
            uint old = atomicAdd(counters.closestLo, closest);
            if (old + closest < old) atomicAdd(counters.closestHi, 1u);
            old = atomicAdd(counters.shadowLo, shadow);
            if (old + shadow < old) atomicAdd(counters.shadowHi, 1u);
        }
    }
}
