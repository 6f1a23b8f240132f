#version 460
// Progressive path tracer: one path per pixel of the dispatch's tile, one
// sample per dispatch, added into the accumulation buffer (sum, count, sum of
// squares). The glTF BSDF (lib/bsdf.glsl; plain Lambert when no material has
// a specular or transmission lobe); next-event estimation on emissive
// triangles combined with BSDF-sampled emission by the power heuristic
// (Veach 1997; delta lobes take no MIS); Russian roulette after depth 3.
// maxDepth counts scattering events (pbrt's convention): 0 shows emitters
// seen directly, 1 is direct lighting.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/sampler.glsl"

layout(constant_id = SPEC_HAS_EMITTERS) const uint kHasEmitters = 1u;

layout(std140, set = 0, binding = BINDING_FRAME) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = BINDING_EMITTERS) readonly buffer EmitterBuffer { Emitter emitters[]; };
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

vec3 cameraRay(vec2 pixel) {
    vec2 ndc = vec2(2.0 * pixel.x / float(frame.image.x) - 1.0,
                    1.0 - 2.0 * pixel.y / float(frame.image.y));
    return normalize(frame.camForward.xyz + ndc.x * frame.camRight.xyz + ndc.y * frame.camUp.xyz);
}

// Lambert only: no material of the scene has a specular or transmission lobe.
const bool kLambertOnly = (kFeatures & (kFeatureSpecular | kFeatureTransmission)) == 0u;

vec3 tracePath(inout Sampler smp, vec3 origin, vec3 dir) {
    const uint maxDepth = frame.image.z;
    const uint emitterCount = frame.counts.x;
    vec3 L = vec3(0.0);
    vec3 beta = vec3(1.0);
    float prevBsdfPdf = 0.0;
    bool prevDelta = true;  // the camera ray: emission seen directly counts fully

    for (uint depth = 0u;; ++depth) {
        TraceHit hit;
        if (!bvhTraceClosest(origin, dir, 0.0, kRayMax, hit)) break;

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
                if (!prevDelta) {
                    Emitter em = emitters[sh.light];
                    float lightPdf = emitterPdfSolidAngle(em.pmf, em.area, hit.t, abs(dot(dir, ng)));
                    w = powerHeuristic(prevBsdfPdf, lightPdf);
                }
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

        // Next-event estimation: one shadow ray to a point on an emitter.
        if (kHasEmitters != 0u) {
            LightSample ls = sampleEmitter(emitterCount, sample2D(smp));
            vec3 toLight = ls.position - p;
            float dist = length(toLight);
            vec3 wi = toLight / dist;
            float cosSigned = -dot(wi, ls.normal);
            vec3 lightSide = cosSigned > 0.0 ? ls.normal : -ls.normal;  // faces p
            bool emits = cosSigned > 0.0 || (ls.flags & kMaterialDoubleSided) != 0u;
            float cosLight = abs(cosSigned);
            vec3 wiL = vec3(dot(wi, t), dot(wi, b), dot(wi, ns));
            float geoSide = dot(n, wi);
            // The shading and geometric normals must agree on the side wi leaves to.
            if (emits && dist > 0.0 && geoSide != 0.0 && (geoSide > 0.0) == (wiL.z > 0.0)) {
                float lightPdf = emitterPdfSolidAngle(ls.pmf, ls.area, dist, cosLight);
                float bsdfPdf;
                vec3 f = evalBsdf(bsdf, woL, wiL, bsdfPdf);
                if (lightPdf > 0.0 && any(greaterThan(f, vec3(0.0)))) {
                    vec3 from = spawnOrigin(tv, hit.u, hit.v, geoSide > 0.0 ? n : -n);
                    vec3 target = spawnOriginOnEmitter(ls.position, ls.v0, ls.e1, ls.e2, lightSide);
                    vec3 seg = target - from;
                    float segLen = length(seg);
                    if (segLen > 0.0 && !bvhTraceAny(from, seg / segLen, 0.0, segLen)) {
                        float w = powerHeuristic(lightPdf, bsdfPdf);
                        vec3 Le = (kFeatures & kFeatureTextures) != 0u
                                      ? emissionAt(shading[ls.triangle].material, ls.triangle, ls.bary)
                                      : ls.radiance;
                        L += beta * f * Le * (w / lightPdf);
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
