#version 460
// Progressive path tracer: one path per pixel of the dispatch's tile, one
// sample per dispatch, added into the accumulation buffer (sum, count, sum of
// squares). Lambertian BSDF with cosine sampling; next-event estimation on
// all lights (emissive triangles, KHR_lights_punctual, the environment;
// lib/lights.glsl) combined with BSDF-sampled emission by the power
// heuristic (Veach 1997) except for delta lights; Russian roulette after
// depth 3. maxDepth counts scattering events (pbrt's convention): 0 shows
// emitters and the environment seen directly, 1 is direct lighting.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/sampler.glsl"

layout(constant_id = SPEC_HAS_EMITTERS) const uint kHasEmitters = 1u;  // any light at all

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_SHADING) readonly buffer ShadingBuffer { TriShading shading[]; };
layout(std430, set = 0, binding = BINDING_MATERIALS) readonly buffer MaterialBuffer { Material materials[]; };
layout(std430, set = 0, binding = BINDING_EMITTERS) readonly buffer EmitterBuffer { Emitter emitters[]; };
layout(std430, set = 0, binding = BINDING_ACCUM) buffer AccumBuffer { vec4 accum[]; };
layout(std430, set = 0, binding = BINDING_COUNTERS) buffer CounterBuffer { RenderCounters counters; };
layout(push_constant) uniform Push { DispatchParams params; };

#include "lib/lights.glsl"
#include "lib/filter.glsl"

// Dimensions: 0-1 pixel position; then kDimsPerVertex per path vertex, in
// 2D pairs: light choice, light point, BSDF direction, roulette (1D in a pair).
const uint kDimsPerVertex = 8u;
const float kRayMax = 3.0e38;

vec3 cameraRay(vec2 pixel) {
    vec2 ndc = vec2(2.0 * pixel.x / float(frame.image.x) - 1.0,
                    1.0 - 2.0 * pixel.y / float(frame.image.y));
    return normalize(frame.camForward.xyz + ndc.x * frame.camRight.xyz + ndc.y * frame.camUp.xyz);
}

// The BSDF, called at exactly two places in tracePath: bsdfEval (f cos and
// pdf for a light direction) and bsdfSample. Lambertian today: f = albedo / pi.
// `ns` is the shading normal, `n` the geometric normal, both on the side of
// the incoming ray; directions below either give nothing.
struct BsdfSample {
    vec3 wi;
    vec3 weight;    // f cos / pdf
    float pdf;      // solid angle
    bool isDelta;   // specular event: the next emitter hit gets MIS weight 1
};

vec3 bsdfEval(vec3 albedo, vec3 ns, vec3 n, vec3 wi, out float pdf) {
    float cosSurface = dot(ns, wi);
    pdf = 0.0;
    if (cosSurface <= 0.0 || dot(n, wi) <= 0.0) return vec3(0.0);
    pdf = cosSurface * kInvPi;
    return albedo * kInvPi * cosSurface;
}

bool bsdfSample(vec3 albedo, vec3 ns, vec3 n, vec2 u, out BsdfSample bs) {
    bs.wi = toWorld(sampleCosineHemisphere(u), ns);
    float cosSurface = dot(ns, bs.wi);
    bs.pdf = cosSurface * kInvPi;
    bs.weight = albedo;  // cosine-weighted: f cos / pdf = albedo
    bs.isDelta = false;
    return cosSurface > 0.0 && dot(n, bs.wi) > 0.0;
}

vec3 tracePath(inout Sampler smp, vec3 origin, vec3 dir) {
    const uint maxDepth = frame.image.z;
    vec3 L = vec3(0.0);
    vec3 beta = vec3(1.0);
    float prevBsdfPdf = 0.0;
    bool prevDelta = true;  // the camera ray: emitters it finds get weight 1

    for (uint depth = 0u;; ++depth) {
        TraceHit hit;
        if (!bvhTraceClosest(origin, dir, 0.0, kRayMax, hit)) {
            // Escaped: the environment, weighted against light sampling.
            if (kHasEmitters != 0u && hasFeature(kFeatureEnvironment)) {
                float w = prevDelta ? 1.0 : powerHeuristic(prevBsdfPdf, lightPdfEnvironment(dir));
                L += beta * w * environmentRadiance(dir);
            }
            break;
        }

        TriVerts tv = bvhFetchTri(hit.triangle);
        vec3 e1 = tv.v1.xyz - tv.v0.xyz, e2 = tv.v2.xyz - tv.v0.xyz;
        vec3 ng = normalize(cross(e1, e2));
        bool front = dot(dir, ng) < 0.0;
        TriShading sh = shading[hit.triangle];
        Material mat = materials[sh.material];

        // Emission found by the previous vertex's BSDF sample (or directly).
        if (kHasEmitters != 0u && sh.light != kNoLight) {
            if (front || (mat.flags & kMaterialDoubleSided) != 0u) {
                float w = 1.0;
                if (!prevDelta)
                    w = powerHeuristic(prevBsdfPdf, lightPdfTriangle(sh.light, hit.t, abs(dot(dir, ng))));
                L += beta * w * mat.emission;
            }
        }
        if (depth >= maxDepth) break;

        vec3 n = front ? ng : -ng;  // geometric normal on the incoming side
        vec3 ns = normalize((1.0 - hit.u - hit.v) * sh.n0 + hit.u * sh.n1 + hit.v * sh.n2);
        if (dot(ns, n) < 0.0) ns = -ns;
        vec3 albedo = mat.baseColor.rgb;
        vec3 p = tv.v0.xyz + hit.u * e1 + hit.v * e2;
        vec3 origin2 = spawnOrigin(tv, hit.u, hit.v, n);
        samplerSetDim(smp, 2u + depth * kDimsPerVertex);

        // Next-event estimation: one light sample, one shadow ray.
        if (kHasEmitters != 0u) {
            LightSample ls = sampleLight(p, sample2D(smp));
            if (ls.pdf > 0.0 && any(greaterThan(ls.Li, vec3(0.0)))) {
                float bsdfPdf;
                vec3 fcos = bsdfEval(albedo, ns, n, ls.wi, bsdfPdf);
                if (any(greaterThan(fcos, vec3(0.0)))) {
                    bool visible;
                    if (ls.dist < kLightFar) {
                        vec3 seg = ls.target - origin2;
                        float segLen = length(seg);
                        visible = segLen > 0.0 && !bvhTraceAny(origin2, seg / segLen, 0.0, segLen);
                    } else {
                        visible = !bvhTraceAny(origin2, ls.wi, 0.0, kRayMax);
                    }
                    if (visible) {
                        float w = ls.isDelta ? 1.0 : powerHeuristic(ls.pdf, bsdfPdf);
                        L += beta * fcos * ls.Li * (w / ls.pdf);
                    }
                }
            }
        }

        // BSDF sampling.
        samplerSetDim(smp, 2u + depth * kDimsPerVertex + 4u);
        BsdfSample bs;
        if (!bsdfSample(albedo, ns, n, sample2D(smp), bs)) break;
        beta *= bs.weight;
        prevBsdfPdf = bs.pdf;
        prevDelta = bs.isDelta;

        // Russian roulette after depth 3, survival probability max(beta) (>= 0.05).
        float u = sample1D(smp);
        if (depth >= 3u) {
            float q = max(0.05, 1.0 - max(beta.r, max(beta.g, beta.b)));
            if (u < q) break;
            beta /= 1.0 - q;
        }
        origin = origin2;
        dir = bs.wi;
    }
    return L;
}

void main() {
    uvec2 local = gl_GlobalInvocationID.xy;
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
