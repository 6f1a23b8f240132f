#version 460
// NFOR's selection (Bitterli et al. 2016, section 5.3): the mean squared
// error of each candidate's output, the average of its two filtered halves
// F_A and F_B, is estimated per pixel from the cross-half differences as
// ((F_A - B)^2 - Var(B) + (F_B - A)^2 - Var(A)) / 2 - (F_A - F_B)^2 / 4,
// averaged over a (2R+1)^2 box; the unfiltered mean is a third candidate
// whose error is its variance. The output blends the candidates with
// weights 1 / error^2. Colours are albedo-demodulated.
#extension GL_GOOGLE_include_directive : require
#include "denoise_common.glsl"

layout(set = 0, binding = DN_IN0) uniform samplerBuffer filteredA1;
layout(set = 0, binding = DN_IN1) uniform samplerBuffer filteredB1;
layout(set = 0, binding = DN_IN2) uniform samplerBuffer filteredA2;
layout(set = 0, binding = DN_IN3) uniform samplerBuffer filteredB2;
layout(set = 0, binding = DN_IN4) uniform samplerBuffer colorA;  // rgb half A, a: the pixel's weight as a neighbour
layout(set = 0, binding = DN_IN5) uniform samplerBuffer colorB;  // rgb half B, a: the variance of a half's mean
layout(std430, set = 0, binding = DN_OUT0) writeonly buffer Out { vec4 outColor[]; };

float sq3(vec3 v) { return dot(v, v) * (1.0 / 3.0); }

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= int(P.width) || p.y >= int(P.height)) return;
    const int ip = dnTexel(p);
    const int radius = int(P.radius);
    float e0 = 0.0, e1 = 0.0, e2 = 0.0, n = 0.0;
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            bool inImage;
            const int iq = dnTexel(p + ivec2(dx, dy), inImage);
            const vec4 a = texelFetch(colorA, iq), b = texelFetch(colorB, iq);
            const float w = inImage ? a.a : 0.0;
            const float v = b.a;
            const vec3 fA1 = texelFetch(filteredA1, iq).rgb, fB1 = texelFetch(filteredB1, iq).rgb;
            const vec3 fA2 = texelFetch(filteredA2, iq).rgb, fB2 = texelFetch(filteredB2, iq).rgb;
            e0 += w * v;
            e1 += w * (0.5 * (sq3(fA1 - b.rgb) + sq3(fB1 - a.rgb)) - v - 0.25 * sq3(fA1 - fB1));
            e2 += w * (0.5 * (sq3(fA2 - b.rgb) + sq3(fB2 - a.rgb)) - v - 0.25 * sq3(fA2 - fB2));
            n += w;
        }
    }
    const float inv = 1.0 / max(n, 1e-6);
    e0 *= 0.5 * inv;  // the variance of the mean of both halves
    const float floorErr = 1e-3 * e0 + 1e-20;
    e1 = max(e1 * inv, floorErr);
    e2 = max(e2 * inv, floorErr);
    e0 = max(e0, floorErr);
    const float w0 = 1.0 / (e0 * e0), w1 = 1.0 / (e1 * e1), w2 = 1.0 / (e2 * e2);
    const vec3 raw = 0.5 * (texelFetch(colorA, ip).rgb + texelFetch(colorB, ip).rgb);
    const vec3 c1 = 0.5 * (texelFetch(filteredA1, ip).rgb + texelFetch(filteredB1, ip).rgb);
    const vec3 c2 = 0.5 * (texelFetch(filteredA2, ip).rgb + texelFetch(filteredB2, ip).rgb);
    outColor[ip] = vec4((w0 * raw + w1 * c1 + w2 * c2) / (w0 + w1 + w2), 0.0);
}
