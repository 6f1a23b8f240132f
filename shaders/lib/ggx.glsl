// The GGX (Trowbridge-Reitz) microfacet distribution the BSDF's lobes share
// (lib/bsdf.glsl): its density, height-correlated Smith masking-shadowing,
// visible-normal sampling and refraction through a microfacet. Directions
// in the shading frame (z the normal).
#ifndef STRATA_LIB_GGX_GLSL
#define STRATA_LIB_GGX_GLSL

#include "lib/sampling.glsl"

// GGX normal distribution, isotropic, written so alpha near 1e-3 keeps its
// precision: D = a^2 / (pi (h.x^2 + h.y^2 + a^2 h.z^2)^2) for unit h.
float ggxD(vec3 h, float a) {
    float a2 = a * a;
    float d = dot(h.xy, h.xy) + a2 * h.z * h.z;
    return d > 0.0 ? a2 / (kPi * d * d) : 0.0;
}

// Smith Lambda for GGX: (sqrt(1 + a^2 tan^2) - 1) / 2.
float ggxLambda(vec3 w, float a) {
    float z2 = w.z * w.z;
    if (z2 <= 0.0) return 1.0e30;
    float t2 = dot(w.xy, w.xy) / z2;
    return 0.5 * (sqrt(1.0 + a * a * t2) - 1.0);
}

float ggxG1(vec3 w, float a) { return 1.0 / (1.0 + ggxLambda(w, a)); }

// Height-correlated masking-shadowing (Heitz 2014).
float ggxG2(vec3 wo, vec3 wi, float a) { return 1.0 / (1.0 + ggxLambda(wo, a) + ggxLambda(wi, a)); }

// Density of the visible normal h seen from wo (wo.z > 0): G1(wo) max(0, wo.h) D(h) / wo.z.
float ggxVisiblePdf(vec3 wo, vec3 h, float a) {
    return ggxG1(wo, a) * max(0.0, dot(wo, h)) * ggxD(h, a) / wo.z;
}

// Visible-normal sample by spherical caps (Dupuy & Benyoub 2023): in the
// configuration stretched to alpha = 1, a uniform point on the cap of the
// unit sphere below wo, offset by wo, is distributed as the visible normals.
vec3 ggxSampleVisible(vec3 wo, float a, vec2 u) {
    vec3 ws = normalize(vec3(a * wo.xy, wo.z));
    float phi = 2.0 * kPi * u.x;
    float z = (1.0 - u.y) * (1.0 + ws.z) - ws.z;
    float sinTheta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    vec3 hs = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + ws;
    vec3 h = vec3(a * hs.xy, max(hs.z, 0.0));
    float len2 = dot(h, h);
    return len2 > 1.0e-30 ? h * inversesqrt(len2) : vec3(0.0, 0.0, 1.0);
}

// Refraction of wo through a surface with normal h (wo.h > 0) into relative
// index etap; false under total internal reflection.
bool refractDir(vec3 wo, vec3 h, float etap, out vec3 wi) {
    float cosI = dot(wo, h);
    float sin2T = max(0.0, 1.0 - cosI * cosI) / (etap * etap);
    if (sin2T >= 1.0) {
        wi = vec3(0.0);
        return false;
    }
    float cosT = sqrt(1.0 - sin2T);
    wi = -wo / etap + (cosI / etap - cosT) * h;
    return true;
}

#ifdef STRATA_ANISOTROPY
// KHR_materials_anisotropy's anisotropic GGX: alpha.x along the frame's x
// (the anisotropy direction), alpha.y along y (Heitz 2014). The isotropic
// functions above are these with alpha.x = alpha.y.
float ggxD(vec3 h, vec2 a) {
    float d = h.x * h.x / (a.x * a.x) + h.y * h.y / (a.y * a.y) + h.z * h.z;
    return d > 0.0 ? 1.0 / (kPi * a.x * a.y * d * d) : 0.0;
}

float ggxLambda(vec3 w, vec2 a) {
    float z2 = w.z * w.z;
    if (z2 <= 0.0) return 1.0e30;
    float t2 = (a.x * a.x * w.x * w.x + a.y * a.y * w.y * w.y) / z2;
    return 0.5 * (sqrt(1.0 + t2) - 1.0);
}

float ggxG1(vec3 w, vec2 a) { return 1.0 / (1.0 + ggxLambda(w, a)); }

float ggxG2(vec3 wo, vec3 wi, vec2 a) { return 1.0 / (1.0 + ggxLambda(wo, a) + ggxLambda(wi, a)); }

float ggxVisiblePdf(vec3 wo, vec3 h, vec2 a) {
    return ggxG1(wo, a) * max(0.0, dot(wo, h)) * ggxD(h, a) / wo.z;
}

// Spherical caps in the configuration stretched by alpha.x, alpha.y to 1.
vec3 ggxSampleVisible(vec3 wo, vec2 a, vec2 u) {
    vec3 ws = normalize(vec3(a * wo.xy, wo.z));
    float phi = 2.0 * kPi * u.x;
    float z = (1.0 - u.y) * (1.0 + ws.z) - ws.z;
    float sinTheta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    vec3 hs = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + ws;
    vec3 h = vec3(a * hs.xy, max(hs.z, 0.0));
    float len2 = dot(h, h);
    return len2 > 1.0e-30 ? h * inversesqrt(len2) : vec3(0.0, 0.0, 1.0);
}
#endif

#endif
