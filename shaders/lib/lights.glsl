// Emissive-triangle lights: choice in proportion to emitted power through
// the host-built alias table (Walker 1977 / Vose 1991), then a uniform point
// on the chosen triangle. Needs `emitters[]` declared by the includer.
#ifndef STRATA_LIB_LIGHTS_GLSL
#define STRATA_LIB_LIGHTS_GLSL

#include "lib/sampling.glsl"

struct LightSample {
    vec3 position;
    vec3 v0, e1, e2;   // the emitter triangle (for the shadow ray's end point)
    vec3 normal;       // unit geometric normal of the emitter (front side)
    vec3 radiance;     // the material's emission factor (times its texture: emissionAt)
    uint triangle;     // the emitter's triangle (BVH order)
    vec2 bary;         // barycentrics of the point (of vertices 1 and 2)
    float pmf;         // probability of having chosen this emitter
    float area;
    uint flags;
};

// One 2D sample picks the emitter and the point on it: u.x chooses the alias
// slot, its leftover fraction decides slot-or-alias and is then rescaled to
// [0,1) again as the point's first coordinate (u.y the second). The light
// sample is one 2D pair, so a stratified pair stratifies the points over all
// emitters together. The rescaled coordinate keeps 24 - log2(emitters) bits.
LightSample sampleEmitter(uint emitterCount, vec2 u) {
    float scaled = u.x * float(emitterCount);
    uint slot = min(uint(scaled), emitterCount - 1u);
    float f = clamp(scaled - float(slot), 0.0, 1.0);
    Emitter e = emitters[slot];
    if (f < e.aliasProb) {
        f = f / e.aliasProb;
    } else {
        f = (f - e.aliasProb) / (1.0 - e.aliasProb);
        e = emitters[e.alias];
    }
    vec2 b = sampleTriangle(vec2(min(f, 0.99999994), u.y));
    LightSample ls;
    ls.position = e.v0 + b.x * e.e1 + b.y * e.e2;
    ls.v0 = e.v0;
    ls.e1 = e.e1;
    ls.e2 = e.e2;
    ls.normal = normalize(cross(e.e1, e.e2));
    ls.radiance = e.radiance;
    ls.triangle = e.triangle;
    ls.bary = b;
    ls.pmf = e.pmf;
    ls.area = e.area;
    ls.flags = e.flags;
    return ls;
}

// Solid-angle density of reaching a point on an emitter (area `area`, chosen
// with `pmf`) at distance `dist` whose normal makes |cosine| `cosLight` with
// the direction to it.
float emitterPdfSolidAngle(float pmf, float area, float dist, float cosLight) {
    return cosLight > 0.0 ? pmf * dist * dist / (cosLight * area) : 0.0;
}

#endif
