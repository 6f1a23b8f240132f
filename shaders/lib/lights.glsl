// Lights: one choice over all emitters (emissive triangles, KHR_lights_punctual
// lights and the environment) in proportion to estimated power through the
// host-built alias table (Walker 1977 / Vose 1991; weights in
// pack/gpu_scene.cpp), then a point or direction on the chosen one. With the
// light tree (STRATA_LIGHT_TREE) a bounded light is chosen by the tree at the
// shading point instead (lib/light_tree.glsl).
// Code for punctual lights and the environment is compiled out through the
// kFeature* bits when the scene has none. Needs `frame` (FrameUniforms)
// declared by the includer; reads emitters through lib/emitters.glsl.
#ifndef STRATA_LIB_LIGHTS_GLSL
#define STRATA_LIB_LIGHTS_GLSL

#include "lib/sampling.glsl"
#include "lib/features.glsl"
#include "lib/environment.glsl"
#include "lib/emitters.glsl"
#ifdef STRATA_LIGHT_TREE
#include "lib/light_tree.glsl"
#endif

const float kLightFar = 3.0e38;  // distance of directional and environment lights

struct LightSample {
    vec3 wi;        // unit direction from p towards the light
    float dist;     // distance from p to the sampled point; kLightFar at infinity
    vec3 Li;        // radiance arriving at p along -wi; for delta lights the
                    // intensity x cone falloff / d^2, or the directional irradiance;
                    // 0 when the light does not face p
    float pdf;      // solid-angle density of wi including the choice pmf; the pmf
                    // alone for delta lights; 0: no sample
    vec3 target;    // shadow ray end (dist < kLightFar): the triangle point moved off
                    // the emitter towards p (spawnOriginOnEmitter), or the light position
    bool isDelta;   // point, spot, directional: BSDF sampling cannot find them, no MIS
    float scale;    // with resampled light candidates, the factor on f Li / pdf (1 without)
};

// Light tree descents a light sample resamples (SPEC_LIGHT_CANDIDATES,
// --light-candidates; 1: the tree's choice as it is).
layout(constant_id = SPEC_LIGHT_CANDIDATES) const uint kLightCandidates = 1u;

// u.x picks the alias slot; its leftover fraction decides slot-or-alias and
// is then rescaled to [0,1) again (`rest`) for use as the sample's first
// coordinate. The light sample is one 2D pair, so a stratified pair
// stratifies the samples over all emitters together. The rescaled coordinate
// keeps 24 - log2(emitters) bits.
uint chooseLight(uint emitterCount, float ux, out float rest) {
    float scaled = ux * float(emitterCount);
    uint slot = min(uint(scaled), emitterCount - 1u);
    float f = clamp(scaled - float(slot), 0.0, 1.0);
    Emitter e = emitterAt(slot);
    float aliasProb = e.aliasProb;
    if (f < aliasProb) {
        rest = f / aliasProb;
        return slot;
    }
    rest = (f - aliasProb) / (1.0 - aliasProb);
    return e.alias;
}

// Solid-angle density of reaching a point on an emitter (area `area`, chosen
// with `pmf`) at distance `dist` whose normal makes |cosine| `cosLight` with
// the direction to it.
float emitterPdfSolidAngle(float pmf, float area, float dist, float cosLight) {
    return cosLight > 0.0 ? pmf * dist * dist / (cosLight * area) : 0.0;
}

// Emitter triangles subtending a solid angle in this range are sampled
// uniformly over it (sampleSphericalTriangle); smaller ones, where its
// angles lose precision, and larger ones, by area (pbrt-v4's range).
const float kSphericalMinSolidAngle = 3e-4;
const float kSphericalMaxSolidAngle = 6.22;
bool sampleBySolidAngle(float omega) { return omega >= kSphericalMinSolidAngle && omega <= kSphericalMaxSolidAngle; }

// The solid-angle density of choosing emitter e (with probability `pmf`)
// and a point on it at distance `dist` whose normal makes |cosine|
// `cosLight` with the direction to it, the triangle subtending `omega`.
float trianglePdfOmega(Emitter e, float pmf, float omega, float dist, float cosLight) {
    if (sampleBySolidAngle(omega)) return cosLight > 0.0 ? pmf / omega : 0.0;
    return emitterPdfSolidAngle(pmf, e.area, dist, cosLight);
}

// ... seen from point `from`.
float trianglePdf(Emitter e, float pmf, vec3 from, float dist, float cosLight) {
    return trianglePdfOmega(e, pmf, triangleSolidAngle(from, e.v0, e.v0 + e.e1, e.v0 + e.e2), dist, cosLight);
}

// An emitter of a moving mesh (kEmitterInstanced; the movinglights axis,
// STRATA_MOVING_LIGHTS, with instancing) is placed in world space
// at the path's time: its triangle from TriVerts by its record's rows, as
// the hit's shading places it (lib/scene.glsl shadeTri). Returns that
// record; kNoInstance (e unchanged) for any other emitter.
#ifdef STRATA_MOVING_LIGHTS
uint placeEmitter(inout Emitter e) {
    if ((e.flags & kEmitterInstanced) == 0u) return kNoInstance;
    uint record = floatBitsToUint(e.v0.x);
    TriVerts tv = bvhFetchTri(e.triangle);
    vec4 r0 = instanceRow(record, 3u), r1 = instanceRow(record, 4u), r2 = instanceRow(record, 5u);
    e.v0 = rowsPoint(r0, r1, r2, tv.v0.xyz);
    e.e1 = rowsPoint(r0, r1, r2, tv.v1.xyz) - e.v0;
    e.e2 = rowsPoint(r0, r1, r2, tv.v2.xyz) - e.v0;
    e.area = 0.5 * length(cross(e.e1, e.e2));
    return record;
}
#else
uint placeEmitter(inout Emitter e) { return kNoInstance; }
#endif

// For MIS when a BSDF-sampled ray from `from` hits emitter triangle `light`
// at distance `dist` with |cosine| `cosLight` to its normal; with the light
// tree, `n` is the normal the tree was asked with (sampleLight's p and n).
#ifdef STRATA_LIGHT_TREE
float lightPdfTriangle(uint light, float dist, float cosLight, vec3 from, vec3 n) {
    Emitter e = emitterAt(light);
    placeEmitter(e);
    return trianglePdf(e, frame.scene.y * lightTreePmf(from, n, e.trail), from, dist, cosLight);
}
#else
float lightPdfTriangle(uint light, float dist, float cosLight, vec3 from) {
    Emitter e = emitterAt(light);
    placeEmitter(e);
    return trianglePdf(e, e.pmf, from, dist, cosLight);
}
#endif

// For MIS when a BSDF-sampled ray escapes along `dir`.
float lightPdfEnvironment(vec3 dir) {
    return emitterAt(frame.envInfo.x).pmf * environmentPdf(dir);
}

LightSample noLight(vec3 p) {
    return LightSample(vec3(0.0, 0.0, 1.0), kLightFar, vec3(0.0), 0.0, p, false, 1.0);
}

// A point on the triangle, the triangle chosen with probability `pmf`: by
// a direction uniform over its solid angle from p where that is in range
// (sampleBySolidAngle), else uniform over its area (the square-root map).
// One-sided emitters give nothing behind them.
LightSample sampleTriangleLight(Emitter e, float pmf, vec3 p, vec2 u) {
    uint instance = placeEmitter(e);
    vec3 normal = normalize(cross(e.e1, e.e2));
    LightSample ls = noLight(p);
    vec3 v1 = e.v0 + e.e1, v2 = e.v0 + e.e2;
    float omega = triangleSolidAngle(p, e.v0, v1, v2);
    vec2 b;
    vec3 pos;
    float dist;
    if (sampleBySolidAngle(omega)) {
        vec3 wi = sampleSphericalTriangle(normalize(e.v0 - p), normalize(v1 - p), normalize(v2 - p), omega, u);
        float along = dot(wi, normal);
        dist = along != 0.0 ? dot(e.v0 - p, normal) / along : 0.0;
        if (!(dist > 0.0)) return ls;
        pos = p + dist * wi;
        // The point's barycentrics (for an emissive texture and the coat).
        vec3 d = pos - e.v0;
        float d00 = dot(e.e1, e.e1), d01 = dot(e.e1, e.e2), d11 = dot(e.e2, e.e2);
        float d20 = dot(d, e.e1), d21 = dot(d, e.e2), den = d00 * d11 - d01 * d01;
        b = clamp(vec2(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / den, 0.0, 1.0);
        ls.wi = wi;
    } else {
        b = sampleTriangle(u);
        pos = e.v0 + b.x * e.e1 + b.y * e.e2;
        vec3 toLight = pos - p;
        dist = length(toLight);
        if (!(dist > 0.0)) return ls;
        ls.wi = toLight / dist;
    }
    ls.dist = dist;
    float cosSigned = -dot(ls.wi, normal);
    bool emits = cosSigned > 0.0 || (e.flags & kMaterialDoubleSided) != 0u;
    if (!emits) return ls;
    ls.pdf = trianglePdfOmega(e, pmf, omega, dist, abs(cosSigned));
    if (ls.pdf > 0.0) {
        ls.Li = e.radiance;
#ifdef STRATA_LIB_MATERIAL_GLSL
        // An emissive texture varies over the triangle, and a clear coat
        // darkens the emission by its Fresnel towards p (lib/material.glsl;
        // kernels without materials, such as sample_test.comp, skip this).
        if (hasFeature(kFeatureTextures)) ls.Li = emissionAt(sceneShading(e.triangle).material, e.triangle, b);
        ls.Li = coatedEmission(sceneShading(e.triangle).material, e.triangle, b, ls.Li, -ls.wi, instance);
#endif
        ls.target = spawnOriginOnEmitter(pos, e.v0, e.e1, e.e2, cosSigned > 0.0 ? normal : -normal);
    }
    return ls;
}

// Point and spot lights: radiant intensity I falls off as 1/d^2; a spot is
// scaled by KHR_lights_punctual's smooth falloff clamp(cos * scale + offset,
// 0, 1)^2. Directional: irradiance E from -e1. The light is chosen with
// probability `pmf`.
LightSample samplePunctualLight(Emitter e, float pmf, vec3 p) {
    LightSample ls = noLight(p);
    ls.isDelta = true;
    ls.pdf = pmf;
    if (e.kind == kLightDirectional) {
        ls.wi = -e.e1;
        ls.Li = e.radiance;
        return ls;
    }
    vec3 toLight = e.v0 - p;
    float d2 = dot(toLight, toLight);
    if (!(d2 > 0.0)) return noLight(p);
    ls.dist = sqrt(d2);
    ls.wi = toLight / ls.dist;
    ls.target = e.v0;
    float falloff = 1.0;
    if (e.kind == kLightSpot) {
        float t = clamp(dot(-ls.wi, e.e1) * e.e2.x + e.e2.y, 0.0, 1.0);
        falloff = t * t;
    }
    ls.Li = e.radiance * (falloff / d2);
    return ls;
}

// The environment, chosen with probability e.pmf, sampled by its map.
LightSample sampleEnvironmentLight(Emitter e, vec3 p, vec2 u2) {
    LightSample ls = noLight(p);
    float pdf;
    ls.wi = sampleEnvironment(u2, pdf);
    ls.pdf = e.pmf * pdf;
    if (ls.pdf > 0.0) ls.Li = environmentRadiance(ls.wi);
    return ls;
}

#ifdef STRATA_LIGHT_TREE
// One light sample for shading point p with normal n (that of the BSDF's
// frame) from one 2D pair u and one more number uTree. The alias table
// chooses as without the tree (u.x); where it chooses a bounded light, that
// choice is dropped and the tree chooses one (uTree): so the directional and
// environment lights keep their probabilities, and the tree is taken with
// probability frame.scene.y (1 where there are none: no alias step).
LightSample sampleLight(vec3 p, vec3 n, vec2 u, float uTree) {
    vec2 u2 = u;
    if (frame.scene.y < 1.0) {
        float rest;
        Emitter e = emitterAt(chooseLight(frame.counts.x, u.x, rest));
        u2 = vec2(min(rest, 0.99999994), u.y);
        if (hasFeature(kFeatureEnvironment) && e.kind == kLightEnvironment) return sampleEnvironmentLight(e, p, u2);
        if (hasFeature(kFeaturePunctual) && e.kind == kLightDirectional) return samplePunctualLight(e, e.pmf, p);
    }
    float pmf, g;
    uint light = sampleLightTree(p, n, uTree, pmf, g);
    float scale = 1.0;
    if (kLightCandidates > 1u) {
        // Resampled importance sampling (Talbot et al. 2005): candidates
        // from kLightCandidates descents at numbers uTree + m / count (each
        // uniform, the set stratified), one kept with probability in
        // proportion to w = its leaf's importance g over its probability,
        // and weighted by the mean w over its own: f Li / pdf x pmf mean(w)
        // / g. The target is g times the point's density on the light, so a
        // candidate needs no point; it covers every light that can reach p
        // (g is a bound), which keeps the estimate unbiased, and MIS keeps
        // the tree's pdf on both sides (weights that sum to one).
        float wSum = light != kNoLight && g > 0.0 && pmf > 0.0 ? g / pmf : 0.0;
        if (wSum == 0.0) light = kNoLight;
        uvec4 h = pcg4d(uvec4(floatBitsToUint(uTree), floatBitsToUint(u.x), floatBitsToUint(u.y), floatBitsToUint(p.x)));
        for (uint m = 1u; m < kLightCandidates; ++m) {
            float pm, gm;
            uint lm = sampleLightTree(p, n, min(fract(uTree + float(m) / float(kLightCandidates)), 0.99999994), pm, gm);
            float w = lm != kNoLight && gm > 0.0 && pm > 0.0 ? gm / pm : 0.0;
            wSum += w;
            if (w > 0.0 && uintToUnit(pcg4d(h + uvec4(m)).x) * wSum < w) {
                light = lm;
                pmf = pm;
                g = gm;
            }
        }
        if (light != kNoLight) scale = pmf * (wSum / float(kLightCandidates)) / g;
    }
    if (light == kNoLight) return noLight(p);
    Emitter e = emitterAt(light);
    pmf *= frame.scene.y;
    LightSample ls;
    if (hasFeature(kFeaturePunctual) && e.kind != kLightTriangle) ls = samplePunctualLight(e, pmf, p);
    else ls = sampleTriangleLight(e, pmf, p, u2);
    ls.scale = scale;
    return ls;
}
#else
// One light sample for shading point p from one 2D pair u.
LightSample sampleLight(vec3 p, vec2 u) {
    float rest;
    Emitter e = emitterAt(chooseLight(frame.counts.x, u.x, rest));
    vec2 u2 = vec2(min(rest, 0.99999994), u.y);
    if (hasFeature(kFeatureEnvironment) && e.kind == kLightEnvironment) return sampleEnvironmentLight(e, p, u2);
    if (hasFeature(kFeaturePunctual) && e.kind != kLightTriangle) return samplePunctualLight(e, e.pmf, p);
    return sampleTriangleLight(e, e.pmf, p, u2);
}
#endif

#endif
