// KHR_materials_sheen's lobe: the "Charlie" distribution of Estevez & Kulla
// 2017 with alpha = sheenRoughness^2 (roughness below kSheenRoughnessMin is
// taken as that), the visibility fit the extension gives (its l and
// lambda_sheen), the sampling of its normals, and the lobe's directional
// albedo E(mu, roughness) from the table tools/sheen-albedo computes at
// build time (sheen_albedo.h in the build folder: its nodes; the values
// are the first words of the texel words, lib/texel_words.glsl).
#ifndef STRATA_LIB_SHEEN_GLSL
#define STRATA_LIB_SHEEN_GLSL

#include "sheen_albedo.h"
#include "lib/sampling.glsl"
#include "lib/texel_words.glsl"

// ln(1 - x) for x in [0, 1], keeping its precision for small x.
float logOneMinus(float x) { return x < 1.0e-3 ? -x * (1.0 + x * (0.5 + x / 3.0)) : log(1.0 - x); }

// 1 - e^x for x <= 0, keeping its precision near 0.
float oneMinusExp(float x) { return x > -1.0e-3 ? -x * (1.0 + x * (0.5 + x / 6.0)) : 1.0 - exp(x); }

// D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi) at cos(theta_h) = cosH.
float charlieD(float cosH, float alpha) {
    float lnSin2 = logOneMinus(min(cosH * cosH, 1.0));
    return (2.0 + 1.0 / alpha) * exp(0.5 / alpha * lnSin2) * (0.5 * kInvPi);
}

float charlieFitL(float x, float alpha) {
    float t = (1.0 - alpha) * (1.0 - alpha);
    float a = mix(21.5473, 25.3245, t);
    float b = mix(3.82987, 3.32435, t);
    float c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t);
    float e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

// The visibility term is 1 / ((1 + Lambda(wo.z) + Lambda(wi.z)) 4 wo.z wi.z).
float charlieLambda(float cosTheta, float alpha) {
    return cosTheta < 0.5 ? exp(charlieFitL(cosTheta, alpha))
                          : exp(2.0 * charlieFitL(0.5, alpha) - charlieFitL(1.0 - cosTheta, alpha));
}

// A normal h with density D(h) h.z (solid angle): the distribution of
// sin(theta)^2 = s is s^(1 + 1/(2 alpha)) ds, so s = u^(2 alpha / (1 + 2 alpha)).
vec3 charlieSample(float alpha, vec2 u) {
    float lnSin2 = 2.0 * alpha / (1.0 + 2.0 * alpha) * log(u.y);
    float sinT = sqrt(exp(lnSin2)), cosT = sqrt(oneMinusExp(lnSin2));
    float phi = 2.0 * kPi * u.x;
    return vec3(sinT * cos(phi), sinT * sin(phi), cosT);
}

// Entry k of the table (row-major, a row per roughness node).
float sheenTable(int k) { return uintBitsToFloat(texelFetch(texelWords, k).r); }

// The table's E(mu, roughness), bilinear in (mu^(1/3), sqrt(roughness)),
// the coordinates of its nodes.
float sheenAlbedo(float mu, float roughness) {
    float x = pow(clamp(mu, 0.0, 1.0), 1.0 / 3.0) * float(kSheenAlbedoMuCount - 1);
    float s0 = sqrt(kSheenRoughnessMin);
    float y = clamp((sqrt(max(roughness, kSheenRoughnessMin)) - s0) / (1.0 - s0), 0.0, 1.0) *
              float(kSheenAlbedoRoughnessCount - 1);
    int i = min(int(x), kSheenAlbedoMuCount - 2), j = min(int(y), kSheenAlbedoRoughnessCount - 2);
    float fx = x - float(i), fy = y - float(j);
    int k = j * kSheenAlbedoMuCount + i;
    float lo = mix(sheenTable(k), sheenTable(k + 1), fx);
    float hi = mix(sheenTable(k + kSheenAlbedoMuCount), sheenTable(k + kSheenAlbedoMuCount + 1), fx);
    return mix(lo, hi, fy);
}

#endif
