// Counter-based random numbers: every draw is a pure function of
// (pixel, sample index, dimension, seed), so any sample of any pixel can be
// recomputed alone and a render is bit-reproducible.
// Hash: pcg4d of Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"
// (JCGT 9(3)), a PCG-family permutation of 4 x 32 bits.
#ifndef STRATA_LIB_RNG_GLSL
#define STRATA_LIB_RNG_GLSL

uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

// The top 24 bits as a float in [0, 1): exactly representable, never 1.
float uintToUnit(uint x) { return float(x >> 8u) * (1.0 / 16777216.0); }

struct Sampler {
    uint pixel;
    uint sampleIndex;
    uint seed;
    uint dim;          // next dimension to draw
};

Sampler samplerInit(uint pixel, uint sampleIndex, uint seed) {
    return Sampler(pixel, sampleIndex, seed, 0u);
}

// Jumps to dimension `dim`; each path vertex starts at a fixed dimension so the
// dimensions of a path line up across samples whatever branch a path takes.
void samplerSetDim(inout Sampler s, uint dim) { s.dim = dim; }

float sample1D(inout Sampler s) {
    uvec4 h = pcg4d(uvec4(s.pixel, s.sampleIndex, s.dim, s.seed));
    s.dim += 1u;
    return uintToUnit(h.x);
}

vec2 sample2D(inout Sampler s) {
    uvec4 h = pcg4d(uvec4(s.pixel, s.sampleIndex, s.dim, s.seed));
    s.dim += 2u;
    return vec2(uintToUnit(h.x), uintToUnit(h.y));
}

#endif
