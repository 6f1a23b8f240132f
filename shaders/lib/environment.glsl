// Environment light: constant radiance, or an equirectangular map sampled in
// proportion to luminance x sin(theta) by a piecewise-constant 2D
// distribution (marginal over rows, conditional per row; the model is
// pbrt-v4's PiecewiseConstant2D). Mapping (host/scene/scene.h): in the map's
// frame, +Y up, the image centre is -Z and u grows towards +X:
//   u = 1/2 + atan(d.x, -d.z) / (2 pi),  v = acos(d.y) / pi  (row 0 = +Y);
// a world direction d is in the map's frame after R_y(-rotation).
// Texels are looked up nearest (constant over each texel, as the
// distribution is), so sampling density and radiance agree texel by texel.
// Needs `frame` (FrameUniforms) declared by the includer; tables are laid out
// by host/pack/env_tables.h.
#ifndef STRATA_LIB_ENVIRONMENT_GLSL
#define STRATA_LIB_ENVIRONMENT_GLSL

#include "lib/features.glsl"
#include "lib/sampling.glsl"
#include "lib/reads.glsl"

layout(set = 0, binding = BINDING_ENV_TEXELS) uniform samplerBuffer envTexels;
layout(std430, set = 0, binding = BINDING_ENV_CDF) readonly buffer EnvTableBuffer { float envTables[]; };
layout(set = 0, binding = BINDING_ENV_CDF_TEXEL) uniform usamplerBuffer envTablesTexel;

// envTables[i], through its RGBA32UI texel view with kTexelAll (the binary
// searches below make a divergent read a step, a loop over the lanes each
// on lavapipe when it is a storage load).
float envTable(uint i) {
    if (!kTexelAll) return envTables[i];
    uvec4 t = texelFetch(envTablesTexel, int(i / kTexelWords));
    uint k = i % kTexelWords;
    return uintBitsToFloat(k == 0u ? t.x : k == 1u ? t.y : k == 2u ? t.z : t.w);
}

// World direction -> the map's frame (R_y(-rotation)) and back (R_y(rotation)).
vec3 envToMap(vec3 d) {
    float c = frame.envRotation.x, s = frame.envRotation.y;
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

vec3 envFromMap(vec3 m) {
    float c = frame.envRotation.x, s = frame.envRotation.y;
    return vec3(c * m.x + s * m.z, m.y, -s * m.x + c * m.z);
}

// Texel (x, y) of the map's frame direction m.
uvec2 envTexelOf(vec3 m) {
    uvec2 size = frame.envInfo.yz;
    float u = (m.x == 0.0 && m.z == 0.0) ? 0.5 : 0.5 + atan(m.x, -m.z) * (0.5 * kInvPi);
    float v = acos(clamp(m.y, -1.0, 1.0)) * kInvPi;
    return min(uvec2(vec2(u, v) * vec2(size)), size - 1u);
}

vec3 environmentRadiance(vec3 dir) {
    vec3 L = frame.envScale.xyz;
    if (hasFeature(kFeatureEnvMap)) {
        uvec2 t = envTexelOf(envToMap(dir));
        L *= texelFetch(envTexels, int(t.y * frame.envInfo.y + t.x)).rgb;
    }
    return L;
}

// Largest i < n with envTables[base + i] <= u, for the n + 1 CDF entries at
// base (0 ... 1) and 0 <= u < 1: the interval has positive width.
uint envFindInterval(uint base, uint n, float u) {
    uint lo = 0u, hi = n;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (envTable(base + mid) <= u) lo = mid;
        else hi = mid;
    }
    return lo;
}

// Density (solid angle) of texel t of the map's (u, v) density at polar sin
// `sinTheta`: p(u, v) / (2 pi^2 sin theta), since dw = 2 pi^2 sin theta du dv.
float envTexelPdf(uvec2 t, float sinTheta) {
    uint w = frame.envInfo.y, h = frame.envInfo.z;
    float puv = envTable(t.y) * envTable(2u * h + 1u + t.y * w + t.x);
    return sinTheta > 0.0 ? puv / (2.0 * kPi * kPi * sinTheta) : 0.0;
}

// Solid-angle density of sampleEnvironment producing `dir` (choice excluded).
float environmentPdf(vec3 dir) {
    if (!hasFeature(kFeatureEnvMap)) return 0.25 * kInvPi;
    vec3 m = envToMap(dir);
    return envTexelPdf(envTexelOf(m), length(m.xz));
}

// A direction with density `pdf` (solid angle): uniform on the sphere for a
// constant environment, else row by the marginal CDF, column by the row's
// conditional CDF, uniform inside the texel in (u, v).
vec3 sampleEnvironment(vec2 u, out float pdf) {
    if (!hasFeature(kFeatureEnvMap)) {
        float z = 1.0 - 2.0 * u.x, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y;
        pdf = 0.25 * kInvPi;
        return vec3(r * cos(phi), r * sin(phi), z);
    }
    uint w = frame.envInfo.y, h = frame.envInfo.z;
    uint rowCdf = h;
    uint y = envFindInterval(rowCdf, h, u.y);
    float r0 = envTable(rowCdf + y), r1 = envTable(rowCdf + y + 1u);
    uint colCdf = 2u * h + 1u + h * w + y * (w + 1u);
    uint x = envFindInterval(colCdf, w, u.x);
    float c0 = envTable(colCdf + x), c1 = envTable(colCdf + x + 1u);
    float v = (float(y) + clamp((u.y - r0) / (r1 - r0), 0.0, 1.0)) / float(h);
    float uu = (float(x) + clamp((u.x - c0) / (c1 - c0), 0.0, 1.0)) / float(w);
    float theta = kPi * v, phi = 2.0 * kPi * (uu - 0.5);
    float sinTheta = sin(theta);
    pdf = envTexelPdf(uvec2(x, y), sinTheta);
    return envFromMap(vec3(sinTheta * sin(phi), cos(theta), -sinTheta * cos(phi)));
}

#endif
