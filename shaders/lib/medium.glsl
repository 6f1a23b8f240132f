// Homogeneous media inside closed meshes (KHR_materials_volume_scatter over
// KHR_materials_volume): the attenuation sigma_t per channel, of which
// sigma_s = sigma_t x scatterAlbedo scatters with the Henyey-Greenstein
// phase function and the rest absorbs. A ray is inside a medium when it
// reaches a back face of its mesh (volumes closed and not nested, as for
// absorption). Needs lib/sampling.glsl (kPi, basis).
#ifndef STRATA_LIB_MEDIUM_GLSL
#define STRATA_LIB_MEDIUM_GLSL

// Henyey-Greenstein with the extension's sign: wo towards the viewer, wi
// towards the light; g > 0 scatters forwards (wi near -wo).
float phaseHG(float cosOI, float g) {
    float d = 1.0 + g * g + 2.0 * g * cosOI;
    return (1.0 - g * g) / (4.0 * kPi * d * sqrt(max(d, 1.0e-12)));
}

// A direction about the travel direction `dir` (= -wo) drawn from the phase
// function: its cosine with `dir` by inversion of HG's CDF, then a uniform
// azimuth. pdf is the phase function's value, so a sample weighs 1.
vec3 samplePhaseHG(vec3 dir, float g, vec2 u, out float pdf) {
    float cosT;
    if (abs(g) < 1.0e-3) {
        cosT = 1.0 - 2.0 * u.x;
    } else {
        float s = (1.0 - g * g) / (1.0 + g - 2.0 * g * u.x);
        cosT = (1.0 + g * g - s * s) / (2.0 * g);
    }
    cosT = clamp(cosT, -1.0, 1.0);
    float sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    float phi = 2.0 * kPi * u.y;
    vec3 t, b;
    basis(dir, t, b);
    pdf = phaseHG(-cosT, g);
    return normalize(sinT * cos(phi) * t + sinT * sin(phi) * b + cosT * dir);
}

// A free flight through a chromatic medium along a segment of length tMax:
// one channel chosen by u in proportion to `share` (the path's throughput:
// channels that carry more weigh more, as Cycles does), its exponential
// distance by the rest of u. The density is the channels' mixture, each
// weighted by its probability (single-sample MIS over the channels, the
// balance heuristic), so each channel's estimate stays unbiased. Returns the
// weight the path's throughput takes: sigma_s Tr(t) / pdf(t) for a
// scattering at t < tMax, Tr(tMax) / P(no event before tMax) when it
// reaches the end (t = tMax).
vec3 mediumFreeFlight(vec3 sigmaT, vec3 albedo, vec3 share, float tMax, float u, out float t) {
    vec3 prob = max(share, vec3(0.0));
    float total = prob.r + prob.g + prob.b;
    prob = total > 0.0 ? prob / total : vec3(1.0 / 3.0);
    // The channel whose interval of [0, 1) holds u, and u rescaled within it.
    float v, sigma;
    if (u < prob.r) {
        v = u / prob.r, sigma = sigmaT.r;
    } else if (u < prob.r + prob.g || prob.b <= 0.0) {
        v = (u - prob.r) / max(prob.g, 1.0e-30), sigma = sigmaT.g;
    } else {
        v = (u - prob.r - prob.g) / prob.b, sigma = sigmaT.b;
    }
    t = sigma > 0.0 ? -log(1.0 - clamp(v, 0.0, 0.99999994)) / sigma : tMax;
    if (t < tMax) {
        vec3 tr = exp(-sigmaT * t);
        // (sigma_t Tr) weighted by the probabilities first: no overflow at sigma_t = float max.
        float pdf = dot(prob * sigmaT, tr);
        return pdf > 0.0 ? albedo * sigmaT * tr / pdf : vec3(0.0);
    }
    t = tMax;
    vec3 tr = exp(-sigmaT * tMax);
    float p = dot(prob, tr);
    return p > 0.0 ? tr / p : vec3(0.0);
}

#endif
