// What the denoise kernels share: the push constants, the pixel of an
// invocation, and the clamped texel index of a neighbour.
#ifndef STRATA_DENOISE_COMMON_GLSL
#define STRATA_DENOISE_COMMON_GLSL
#include "shared/denoise.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(push_constant) uniform Push { DenoiseParams P; };

// The texel of pixel q clamped into the image; inImage says whether q was inside.
int dnTexel(ivec2 q, out bool inImage) {
    const int w = int(P.width), h = int(P.height);
    inImage = q.x >= 0 && q.y >= 0 && q.x < w && q.y < h;
    return clamp(q.y, 0, h - 1) * w + clamp(q.x, 0, w - 1);
}

int dnTexel(ivec2 q) {
    bool unused;
    return dnTexel(q, unused);
}

float dnLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
#endif
