#version 460
// NFOR's filtering step (Bitterli et al. 2016, "Nonlinearly Weighted
// First-Order Regression for Denoising Monte Carlo Renderings"): for each
// pixel p, a weighted least-squares fit over a (2R+1)^2 window of the
// albedo-demodulated colour on the features x = [1, normal - normal(p),
// relative depth difference, screen offset / R], evaluated at p (the
// intercept). Weights are NL-means weights (Rousselle et al. 2012) from the
// other half: half A is filtered with weights from half B's guide and
// half B with half A's, at two bandwidths: four candidates out.
// The guides are the halves box-filtered over 3x3 (host/denoise), their
// alpha the variance of that box mean; a neighbour's distance is the mean
// of the guides' distance and the two pixels' own.
#extension GL_GOOGLE_include_directive : require
#include "denoise_common.glsl"

layout(set = 0, binding = DN_IN0) uniform samplerBuffer guideA;  // rgb guide of half A, a: its variance
layout(set = 0, binding = DN_IN1) uniform samplerBuffer guideB;
layout(set = 0, binding = DN_IN2) uniform samplerBuffer colorA;  // rgb half A, a: the pixel's weight as a neighbour
layout(set = 0, binding = DN_IN3) uniform samplerBuffer colorB;  // rgb half B
layout(set = 0, binding = DN_IN4) uniform samplerBuffer features;  // normal xyz, depth / the image's largest depth
layout(std430, set = 0, binding = DN_OUT0) writeonly buffer OutA1 { vec4 outA1[]; };
layout(std430, set = 0, binding = DN_OUT1) writeonly buffer OutB1 { vec4 outB1[]; };
layout(std430, set = 0, binding = DN_OUT2) writeonly buffer OutA2 { vec4 outA2[]; };
layout(std430, set = 0, binding = DN_OUT3) writeonly buffer OutB2 { vec4 outB2[]; };

// The normal equations of one candidate's fit, in two blocks of the terms:
// a = (1, normal difference xyz), b = (relative depth difference, screen
// offset xy). aa, ab, bb: the weighted Gram matrix's blocks; ra, rb: the
// weighted sums of x y^T (column i: term i's sum over the colour).
struct Normal {
    mat4 aa;
    mat3x4 ab;
    mat3 bb;
    mat4x3 ra;
    mat3 rb;
};

Normal emptyNormal() { return Normal(mat4(0.0), mat3x4(0.0), mat3(0.0), mat4x3(0.0), mat3(0.0)); }

void accumulate(inout Normal n, float w, vec4 xa, vec3 xb, vec3 y) {
    const vec4 wa = w * xa;
    const vec3 wb = w * xb;
    n.aa += outerProduct(wa, xa);
    n.ab += outerProduct(wa, xb);
    n.bb += outerProduct(wb, xb);
    n.ra += outerProduct(y, wa);
    n.rb += outerProduct(y, wb);
}

// NL-means distance of two guide texels at k = 1 (clamped at 0); the
// weight at bandwidth k is exp(-d / k^2).
float nlmDistance(vec4 gp, vec4 gq) {
    const vec3 diff = gp.rgb - gq.rgb;
    const float vp = gp.a, vq = gq.a;
    const float floorVar = 1e-4 * dot(gp.rgb, gp.rgb) * (1.0 / 3.0) + 1e-10;
    const float num = dot(diff, diff) * (1.0 / 3.0) - (vp + min(vp, vq));
    return max(num / (floorVar + vp + vq), 0.0);
}

// The intercept of the ridge-regularised fit, by the Schur complement of
// the a block: beta_b = S^-1 (r_b - ab^T aa^-1 r_a), S = bb - ab^T aa^-1 ab,
// beta_a = aa^-1 (r_a - ab beta_b). Falls back to the weighted mean where
// the solve is not finite; never negative.
vec3 solveIntercept(Normal n, float ridge) {
    const float sumW = n.aa[0][0];
    const float lambda = ridge * sumW;
    mat4 a = n.aa;
    a[0][0] += 1e-6 * sumW;
    a[1][1] += lambda;
    a[2][2] += lambda;
    a[3][3] += lambda;
    mat3 c = n.bb;
    c[0][0] += lambda;
    c[1][1] += lambda;
    c[2][2] += lambda;
    const mat4 aInv = inverse(a);
    const mat3x4 ra = transpose(n.ra);  // rows: a terms, columns: colour channels
    const mat3 rb = transpose(n.rb);
    const mat4x3 abT = transpose(n.ab);
    const mat3 s = c - abT * aInv * n.ab;
    const mat3 betaB = inverse(s) * (rb - abT * (aInv * ra));
    const mat3x4 betaA = aInv * (ra - n.ab * betaB);
    const vec3 b = vec3(betaA[0][0], betaA[1][0], betaA[2][0]);
    const vec3 mean = n.ra[0] / max(sumW, 1e-20);
    const bool ok = !any(isnan(b)) && !any(isinf(b));
    return max(ok ? b : mean, vec3(0.0));
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= int(P.width) || p.y >= int(P.height)) return;
    const int ip = dnTexel(p);
    const vec4 gAp = texelFetch(guideA, ip), gBp = texelFetch(guideB, ip);
    const vec4 fp = texelFetch(features, ip);
    const vec4 cAp = texelFetch(colorA, ip), cBp = texelFetch(colorB, ip);
    const int radius = int(P.radius);
    const float invR = 1.0 / float(max(radius, 1));
    const float depthScale = 1.0 / max(fp.w, 1e-4);

    // Half A at k1 (weights from B), half B at k1 (weights from A), the same at k2.
    Normal a1 = emptyNormal(), b1 = emptyNormal(), a2 = emptyNormal(), b2 = emptyNormal();
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            bool inImage;
            const int iq = dnTexel(p + ivec2(dx, dy), inImage);
            const vec4 cAq = texelFetch(colorA, iq), cBq = texelFetch(colorB, iq);
            const vec4 fq = texelFetch(features, iq);
            const vec4 gAq = texelFetch(guideA, iq), gBq = texelFetch(guideB, iq);
            // The guides' distance and the pixels' own (each half's variance
            // is 9 times its guide's): the mean of the two.
            const float dA = 0.5 * (nlmDistance(gAp, gAq) + nlmDistance(vec4(cAp.rgb, 9.0 * gAp.a), vec4(cAq.rgb, 9.0 * gAq.a)));
            const float dB = 0.5 * (nlmDistance(gBp, gBq) + nlmDistance(vec4(cBp.rgb, 9.0 * gBp.a), vec4(cBq.rgb, 9.0 * gBq.a)));
            const float valid = inImage ? cAq.a : 0.0;
            const vec4 xa = vec4(1.0, fq.xyz - fp.xyz);
            const vec3 xb = vec3((fq.w - fp.w) * depthScale, float(dx) * invR, float(dy) * invR);
            accumulate(a1, valid * exp(-dB * P.invK1), xa, xb, cAq.rgb);
            accumulate(b1, valid * exp(-dA * P.invK1), xa, xb, cBq.rgb);
            accumulate(a2, valid * exp(-dB * P.invK2), xa, xb, cAq.rgb);
            accumulate(b2, valid * exp(-dA * P.invK2), xa, xb, cBq.rgb);
        }
    }
    outA1[ip] = vec4(solveIntercept(a1, P.ridge), 0.0);
    outB1[ip] = vec4(solveIntercept(b1, P.ridge), 0.0);
    outA2[ip] = vec4(solveIntercept(a2, P.ridge), 0.0);
    outB2[ip] = vec4(solveIntercept(b2, P.ridge), 0.0);
}
