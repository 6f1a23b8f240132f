// The Fresnel terms of lib/bsdf.glsl's lobes: the exact dielectric
// Fresnel and Schlick's for metals; with the layers (STRATA_LAYERS) the
// specular colour's RGB Fresnel and the thin film's (STRATA_IRIDESCENCE,
// lib/thin_film.glsl); and what a microfacet reflects of the metal and the
// dielectric together (reflectance, dielectricMax, specularSplit). Included
// by lib/bsdf.glsl after its Bsdf struct.
#ifndef STRATA_LIB_FRESNEL_GLSL
#define STRATA_LIB_FRESNEL_GLSL

// Exact Fresnel reflectance of a dielectric interface for unpolarised light
// arriving at cosine cosI >= 0 from the side with relative index etap
// (transmitted side over incident side); 1 under total internal reflection.
float fresnelDielectric(float cosI, float etap) {
    cosI = clamp(cosI, 0.0, 1.0);
    float sin2T = (1.0 - cosI * cosI) / (etap * etap);
    if (sin2T >= 1.0) return 1.0;
    float cosT = sqrt(1.0 - sin2T);
    float rs = (cosI - etap * cosT) / (cosI + etap * cosT);
    float rp = (etap * cosI - cosT) / (etap * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

vec3 fresnelSchlick(vec3 f0, float cosI) {
    float m = clamp(1.0 - cosI, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

#ifdef STRATA_LAYERS

// The dielectric's Fresnel reflectance Fd at wo.h = c, RGB (the header's
// formula with a specular colour).
vec3 dielectricFresnel(Bsdf b, float c) {
    float w = clamp((fresnelDielectric(c, b.etap) - b.f0) / (1.0 - b.f0), 0.0, 1.0);
    return b.specular * mix(b.f0Tint, vec3(1.0), w);
}

#ifdef STRATA_IRIDESCENCE
#include "lib/thin_film.glsl"
#endif

// The dielectric's and the metal's Fresnel with the layers that change
// them: the specular colour, and the film mixed in by its factor (on the
// outside of a dielectric only: a ray leaving a volume sees the bare
// interface; the dielectric's film sits on F0 = the tinted F0, the metal's
// on its base colour).
vec3 dielectricRGB(Bsdf b, float c) {
#ifdef STRATA_IRIDESCENCE
    vec3 f = hasFeature(kFeatureSpecularColor) ? dielectricFresnel(b, c)
                                               : vec3(b.specular * fresnelDielectric(c, b.etap));
    if (hasFeature(kFeatureIridescence) && b.film > 0.0 && b.etap >= 1.0)
        f = mix(f, b.specular * thinFilmFresnel(b.filmIor, c, b.filmThickness, b.f0Tint), b.film);
    return f;
#else
    return dielectricFresnel(b, c);
#endif
}

vec3 metalFresnel(Bsdf b, float c) {
#ifdef STRATA_IRIDESCENCE
    vec3 f = fresnelSchlick(b.baseColor, c);
    if (hasFeature(kFeatureIridescence) && b.film > 0.0)
        f = mix(f, thinFilmFresnel(b.filmIor, c, b.filmThickness, b.baseColor), b.film);
    return f;
#else
    return fresnelSchlick(b.baseColor, c);
#endif
}
#endif

// max(Fd) at wo.h = c: what the dielectric's reflection takes from the
// lobes beneath (Fd itself without a specular colour or film).
float dielectricMax(Bsdf b, float c) {
#ifdef STRATA_LAYERS
    if (hasFeature(kFeatureSpecularColor | kFeatureIridescence)) return max3(dielectricRGB(b, c));
#endif
    return b.specular * fresnelDielectric(c, b.etap);
}

// Reflectance of the mirror lobe, metal and dielectric together, at wo.h = c.
vec3 reflectance(Bsdf b, float c) {
#ifdef STRATA_LAYERS
    if (hasFeature(kFeatureSpecularColor | kFeatureIridescence))
        return b.metallic * metalFresnel(b, c) + (1.0 - b.metallic) * dielectricRGB(b, c);
#endif
    return b.metallic * fresnelSchlick(b.baseColor, c) +
           vec3((1.0 - b.metallic) * b.specular * fresnelDielectric(c, b.etap));
}

// Probability of reflecting (rather than refracting) off a microfacet with
// wo.h = c: the two lobes' albedo estimates, Fresnel exact.
float specularSplit(Bsdf b, float c) {
    float fd = dielectricMax(b, c);
    float wr = b.metallic * max(luminance(fresnelSchlick(b.baseColor, c)), 1.0e-3) +
               (1.0 - b.metallic) * fd;
    float wt = (1.0 - b.metallic) * b.transmission * (1.0 - fd) * luminance(b.baseColor);
    return wr + wt > 0.0 ? wr / (wr + wt) : 1.0;
}

#endif
