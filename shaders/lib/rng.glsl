// Hashes for counter-based random numbers: every draw is a pure function of
// its inputs, so any sample of any pixel can be recomputed alone and a render
// is bit-reproducible.
#ifndef STRATA_LIB_RNG_GLSL
#define STRATA_LIB_RNG_GLSL

// pcg4d of Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"
// (JCGT 9(3)): a PCG-family permutation of 4 x 32 bits.
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

// One 32-bit hash of up to four words.
uint hash4(uint a, uint b, uint c, uint d) { return pcg4d(uvec4(a, b, c, d)).x; }

// Two words to one, cheaply: a xor b times the golden ratio's 32 bits,
// through an xorshift-multiply finaliser (three multiplies against
// pcg4d's twelve).
uint hashMix(uint a, uint b) {
    uint x = a ^ (b * 0x9e3779b9u);
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// The top 24 bits as a float in [0, 1): exactly representable, never 1.
float uintToUnit(uint x) { return float(x >> 8u) * (1.0 / 16777216.0); }

#endif
