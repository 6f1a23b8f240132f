// Filter importance sampling of the pixel filter: the host tabulates the
// inverse CDF of the separable 1D profile (render/filter.h); x and y offsets
// come from one table lookup each, interpolated linearly.
#ifndef STRATA_LIB_FILTER_GLSL
#define STRATA_LIB_FILTER_GLSL

#include "shared/types.h"
#include "shared/bindings.h"

layout(std430, set = 0, binding = BINDING_FILTER) readonly buffer FilterBuffer { float filterInvCdf[]; };

float filterOffset1D(float u) {
    float x = u * float(kFilterTableEntries - 1u);
    uint i = min(uint(x), kFilterTableEntries - 2u);
    return mix(filterInvCdf[i], filterInvCdf[i + 1u], x - float(i));
}

// Offset from the pixel centre, in pixels, with density f(x) f(y).
vec2 sampleFilter(vec2 u) { return vec2(filterOffset1D(u.x), filterOffset1D(u.y)); }

#endif
