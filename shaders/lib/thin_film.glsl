// KHR_materials_iridescence's thin film (lib/bsdf.glsl includes it with
// STRATA_IRIDESCENCE, after fresnelSchlick, which it uses).
#ifndef STRATA_LIB_THIN_FILM_GLSL
#define STRATA_LIB_THIN_FILM_GLSL

#include "lib/sampling.glsl"

// KHR_materials_iridescence: the reflectance of a thin film of index
// filmIor and thickness d (nanometres) between air and a base whose
// normal-incidence reflectance is baseF0, at cosine cosI, as the extension
// specifies after Belcour & Barla 2017 ("A Practical Extension to
// Microfacet Theory for the Modeling of Varying Iridescence"): the Airy
// series of the film's multiple reflections to its second order, each
// order's interference term integrated against the CIE 1931 XYZ matching
// functions in closed form (filmSpectralTerm), then converted to linear
// Rec. 709. Each interface's reflectance is Schlick's of its F0; the base's
// index is the dielectric one its F0 implies, and a reflection off a
// denser side shifts the phase by pi.
vec3 filmSpectralTerm(float opd, vec3 phaseShift) {
    // Fourier transforms of Gaussian fits to the XYZ matching functions
    // (the paper's supplemental): amplitude, centre and variance per channel,
    // and a second Gaussian for X's blue lobe; opd in nanometres.
    float phase = 2.0 * kPi * opd * 1.0e-9;
    const vec3 amp = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
    const vec3 centre = vec3(1.6810e6, 1.7953e6, 2.2084e6);
    const vec3 var = vec3(4.3278e9, 9.3046e9, 6.6121e9);
    vec3 xyz = amp * sqrt(2.0 * kPi * var) * cos(centre * phase + phaseShift) * exp(-phase * phase * var);
    xyz.x += 9.7470e-14 * sqrt(2.0 * kPi * 4.5282e9) * cos(2.2399e6 * phase + phaseShift.x) *
             exp(-4.5282e9 * phase * phase);
    xyz /= 1.0685e-7;  // normalised so that the integral of Y is 1
    const mat3 xyzToRec709 = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259,
                                  -0.4985314, 0.0415560, 1.0572252);
    return xyzToRec709 * xyz;
}

vec3 thinFilmFresnel(float filmIor, float cosI, float d, vec3 baseF0) {
    // No film at thickness 0: its index fades to the outside's (the extension's smoothstep).
    float n2 = mix(1.0, filmIor, smoothstep(0.0, 0.03, d));
    cosI = clamp(cosI, 0.0, 1.0);
    float cosT = sqrt(max(1.0 - (1.0 - cosI * cosI) / (n2 * n2), 0.0));
    float f12 = (n2 - 1.0) * (n2 - 1.0) / ((n2 + 1.0) * (n2 + 1.0));
    float r12 = fresnelSchlick(vec3(f12), cosI).x;  // air | film, R12 = R21
    float t121 = 1.0 - r12;
    vec3 s = sqrt(clamp(baseF0, 0.0, 0.9999));
    vec3 n3 = (1.0 + s) / (1.0 - s);  // the base's index
    vec3 f23 = (n3 - n2) * (n3 - n2) / ((n3 + n2) * (n3 + n2));
    vec3 r23 = fresnelSchlick(f23, cosT);  // film | base
    float phi21 = n2 < 1.0 ? 0.0 : kPi;    // reflection inside the film off air
    vec3 phi23 = mix(vec3(0.0), vec3(kPi), lessThan(n3, vec3(n2)));
    vec3 phi = vec3(phi21) + phi23;
    float opd = 2.0 * n2 * d * cosT;       // optical path difference of one round trip
    vec3 r123 = clamp(r12 * r23, 1.0e-5, 0.9999);
    vec3 rs = t121 * t121 * r23 / (1.0 - r123);
    vec3 result = r12 + rs;                // the orders' mean (no interference)
    vec3 cm = rs - t121;
    for (int m = 1; m <= 2; ++m) {
        cm *= sqrt(r123);
        result += cm * 2.0 * filmSpectralTerm(float(m) * opd, float(m) * phi);
    }
    return max(result, vec3(0.0));
}

#endif
