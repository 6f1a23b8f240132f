#version 460
// One iteration of the edge-avoiding a-trous wavelet filter (Dammertz et
// al. 2010) with SVGF's edge-stopping functions (Schied et al. 2017): a
// 5x5 B3-spline kernel with taps P.step pixels apart, weighted by
// normal (max(0, n.n')^128), depth (relative to the depth gradient) and
// luminance (sigma_l sqrt of the 3x3 Gaussian-blurred variance). The
// colour is albedo-demodulated; its variance is filtered with the squared
// weights.
#extension GL_GOOGLE_include_directive : require
#include "denoise_common.glsl"

layout(set = 0, binding = DN_IN0) uniform samplerBuffer colorIn;  // rgb, a: variance of the luminance
layout(set = 0, binding = DN_IN1) uniform samplerBuffer features; // normal xyz, depth / the image's largest depth
layout(set = 0, binding = DN_IN2) uniform samplerBuffer neighbour; // r: 1 where the pixel may be a neighbour, else 0
layout(std430, set = 0, binding = DN_OUT0) writeonly buffer Out { vec4 colorOut[]; };

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= int(P.width) || p.y >= int(P.height)) return;
    const int ip = dnTexel(p);
    const vec4 cp = texelFetch(colorIn, ip);
    const vec4 fp = texelFetch(features, ip);
    // The 3x3 Gaussian of the variance.
    float blurredVar = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            blurredVar += texelFetch(colorIn, dnTexel(p + ivec2(dx, dy))).a * float((2 - abs(dx)) * (2 - abs(dy)));
    blurredVar *= 1.0 / 16.0;
    // Depth gradient per pixel by central differences.
    const float gx = 0.5 * abs(texelFetch(features, dnTexel(p + ivec2(1, 0))).w - texelFetch(features, dnTexel(p - ivec2(1, 0))).w);
    const float gy = 0.5 * abs(texelFetch(features, dnTexel(p + ivec2(0, 1))).w - texelFetch(features, dnTexel(p - ivec2(0, 1))).w);
    const float lp = dnLuminance(cp.rgb);
    const float lumScale = 1.0 / (P.sigma * sqrt(max(blurredVar, 0.0)) + 1e-6);
    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    const int step = int(P.step);
    vec3 sum = vec3(0.0);
    float sumVar = 0.0, sumW = 0.0;
    for (int j = -2; j <= 2; ++j) {
        for (int i = -2; i <= 2; ++i) {
            const ivec2 off = ivec2(i, j) * step;
            bool inImage;
            const int iq = dnTexel(p + off, inImage);
            const vec4 cq = texelFetch(colorIn, iq);
            const vec4 fq = texelFetch(features, iq);
            const float wn = pow(max(dot(fp.xyz, fq.xyz), 0.0), 128.0);
            const float expected = gx * abs(float(off.x)) + gy * abs(float(off.y));
            const float wz = exp(-abs(fp.w - fq.w) / (expected + 1e-3 * fp.w + 1e-6));
            const float wl = exp(-abs(lp - dnLuminance(cq.rgb)) * lumScale);
            const float h = kernel[abs(i)] * kernel[abs(j)];
            const bool centre = i == 0 && j == 0;
            const float valid = texelFetch(neighbour, iq).r;
            const float w = inImage ? (centre ? h : h * wn * wz * wl * valid) : 0.0;
            sum += w * cq.rgb;
            sumVar += w * w * cq.a;
            sumW += w;
        }
    }
    colorOut[ip] = vec4(sum / sumW, sumVar / (sumW * sumW));
}
