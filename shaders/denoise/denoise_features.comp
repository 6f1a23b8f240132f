#version 460
// The feature prefilter: NL-means over a (2R+1)^2 window of the normal and
// depth, per-pixel distances normalised by each feature's variance
// (Rousselle et al. 2012), weight exp(-d / k^2) with 1 / k^2 = P.sigma.
#extension GL_GOOGLE_include_directive : require
#include "denoise_common.glsl"

layout(set = 0, binding = DN_IN0) uniform samplerBuffer features;  // normal xyz, depth / the image's largest depth
layout(set = 0, binding = DN_IN1) uniform samplerBuffer featureVar; // their variances (normal per axis, depth)
layout(std430, set = 0, binding = DN_OUT0) writeonly buffer Out { vec4 featuresOut[]; };

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= int(P.width) || p.y >= int(P.height)) return;
    const int ip = dnTexel(p);
    const vec4 fp = texelFetch(features, ip), vp = texelFetch(featureVar, ip);
    const int radius = int(P.radius);
    vec4 sum = vec4(0.0);
    float sumW = 0.0;
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            bool inImage;
            const int iq = dnTexel(p + ivec2(dx, dy), inImage);
            const vec4 fq = texelFetch(features, iq), vq = texelFetch(featureVar, iq);
            const vec4 diff = fp - fq;
            const vec4 num = diff * diff - (vp + min(vp, vq));
            const vec4 d = num / (vp + vq + 1e-6);
            const float dist = max(0.25 * (d.x + d.y + d.z + d.w), 0.0);
            const float w = inImage ? exp(-dist * P.sigma) : 0.0;
            sum += w * fq;
            sumW += w;
        }
    }
    featuresOut[ip] = sum / sumW;
}
