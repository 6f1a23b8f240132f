// The samplers: every random number of a path comes from here, as a pure
// function of (pixel, sample index, dimension, seed). SPEC_SAMPLER picks one
// at pipeline creation (kSampler* in shared/types.h).
//
// Dimensions are drawn in 2D pairs (the pixel position is pair 0; each path
// vertex starts at a fixed pair, samplerSetDim) so the dimensions of a path
// line up across samples whatever branch a path takes; 1D draws take a pair
// of their own. Every pair other than the pixel's is decorrelated from the
// others by a per-pair scramble of the sample order ("padding", as pbrt-v4's
// samplers do), so the good 2D distribution of each pair holds without
// correlations between pairs.
#ifndef STRATA_LIB_SAMPLER_GLSL
#define STRATA_LIB_SAMPLER_GLSL

#include "shared/types.h"
#include "shared/bindings.h"
#include "lib/rng.glsl"

layout(constant_id = SPEC_SAMPLER) const uint kSampler = 0u;

struct Sampler {
    uvec2 pixel;
    uint pixelIndex;   // y * width + x
    uint sampleIndex;  // 0 .. spp-1
    uint spp;          // samples per pixel of the whole render
    uint grid;         // sqrt(spp) for the grid samplers
    uint seed;
    uint dim;          // next dimension (even: pairs start on even dimensions)
};

Sampler samplerInit(uvec2 pixel, uint width, uint sampleIndex, uint spp, uint seed) {
    uint grid = uint(sqrt(float(spp)) + 0.5);
    return Sampler(pixel, pixel.y * width + pixel.x, sampleIndex, spp, grid, seed, 0u);
}

void samplerSetDim(inout Sampler s, uint dim) { s.dim = dim; }

// ---- Owen scrambling in base 2 (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4)): a Laine-Karras style hash flips each bit
// depending only on the bits below it; applied to the bit-reversed value it
// flips each binary digit depending on the digits before it, which is a
// nested uniform (Owen) scramble.
uint laineKarrasPermutation(uint x, uint seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

uint nestedUniformScramble(uint x, uint seed) {
    return bitfieldReverse(laineKarrasPermutation(bitfieldReverse(x), seed));
}

// First two Sobol dimensions as 32-bit fixed-point fractions: dimension 0 is
// the van der Corput sequence (bit reversal); dimension 1 uses the direction
// numbers of the primitive polynomial x + 1, v_k = v_(k-1) xor (v_(k-1) >> 1),
// so v_(i+1) has bit 31 - j set exactly when C(i, j) is odd, that is when
// the bits of j are a subset of those of i (Lucas). Bit 31 - j of the result
// is then the xor of the index bits i that contain j: a superset sum over
// the 5-bit positions, five shift-mask-xor steps instead of a loop over the
// index bits (lavapipe runs a loop until its slowest lane, 32 trips for a
// scrambled index).
uvec2 sobol2D(uint index) {
    uint x = bitfieldReverse(index);
    uint z = index;
    z ^= (z >> 1u) & 0x55555555u;
    z ^= (z >> 2u) & 0x33333333u;
    z ^= (z >> 4u) & 0x0f0f0f0fu;
    z ^= (z >> 8u) & 0x00ff00ffu;
    z ^= (z >> 16u) & 0x0000ffffu;
    return uvec2(x, bitfieldReverse(z));
}

// Owen-scrambled 2D Sobol point number `index`, with the sample order
// shuffled by an Owen scramble of the index (Burley 2020, sec. 4): any
// prefix of 2^m points of a pair is still a (0, m, 2)-net.
vec2 owenSobol2D(uint index, uint seed) {
    uint shuffled = nestedUniformScramble(index, hash4(seed, 0x9e3779b9u, 1u, 2u));
    uvec2 p = sobol2D(shuffled);
    return vec2(uintToUnit(nestedUniformScramble(p.x, hash4(seed, 0x85ebca6bu, 3u, 4u))),
                uintToUnit(nestedUniformScramble(p.y, hash4(seed, 0xc2b2ae35u, 5u, 6u))));
}

// A pseudo-random permutation of [0, n). On [0, 2^bits) with 2^bits >= n,
// the Laine-Karras hash masked to `bits` is a bijection (each output bit
// depends only on the bits below it); alternating it with a bit reversal
// inside the domain mixes in both directions. Cycle-walking (applying the
// bijection again until the value lands below n) turns it into a permutation
// of [0, n) (Black & Rogaway 2002; Kensler 2013 uses it for sample shuffles).
uint permuteIndex(uint i, uint n, uint seed) {
    if (n <= 1u) return 0u;
    uint bits = uint(findMSB(n - 1u)) + 1u;
    uint mask = bits >= 32u ? 0xffffffffu : (1u << bits) - 1u;
    do {
        i = laineKarrasPermutation(i, seed) & mask;
        i = bitfieldReverse(i) >> (32u - bits);
        i = laineKarrasPermutation(i, seed ^ 0x5bd1e995u) & mask;
        i = bitfieldReverse(i) >> (32u - bits);
        i = laineKarrasPermutation(i, seed ^ 0x1b873593u) & mask;
    } while (i >= n);
    return i;
}

// Grid coordinates of sample k on the n x n grid, k = row * n + column.
// kSamplerRotated: the grid rotated by atan(1/n) (7.125 degrees for n = 8),
// the lattice spanned by (1/n, 1/n^2) and (-1/n^2, 1/n) modulo 1: sample
// (i, j) sits in column i n - j and row i + j n of the n^2 x n^2 subgrid, so
// each of the n^2 samples has a row and a column of its own.
vec2 gridPoint(uint k, uint n, vec2 jitter) {
    uint i = k % n, j = k / n;
    if (kSampler == kSamplerRotated) {
        uint n2 = n * n;
        uint col = (i * n + n2 - j) % n2;
        uint row = (i + j * n) % n2;
        return (vec2(col, row) + 0.5) / float(n2);
    }
    return (vec2(i, j) + jitter) / float(n);
}

// Z-order blue-noise sample index (Ahmed & Wonka 2020, "Screen-Space
// Blue-Noise Diffusion of Monte Carlo Sampling Error via Hierarchical
// Ordering of Pixels"; as pbrt-v4's ZSobolSampler): the pixel's Morton code
// followed by the sample index, with each base-4 digit permuted by a hash of
// the digits above it, so neighbouring pixels take complementary parts of
// one Sobol sequence. Needs spp a power of two and Morton code + log2(spp)
// within 32 bits (checked on the host).
uint mortonCode(uvec2 p) {
    uint x = p.x, y = p.y;
    x = (x | (x << 8u)) & 0x00ff00ffu;
    x = (x | (x << 4u)) & 0x0f0f0f0fu;
    x = (x | (x << 2u)) & 0x33333333u;
    x = (x | (x << 1u)) & 0x55555555u;
    y = (y | (y << 8u)) & 0x00ff00ffu;
    y = (y | (y << 4u)) & 0x0f0f0f0fu;
    y = (y | (y << 2u)) & 0x33333333u;
    y = (y | (y << 1u)) & 0x55555555u;
    return x | (y << 1u);
}

uint zOrderIndex(Sampler s, uint pair) {
    uint log2spp = uint(findMSB(s.spp));
    uint z = (mortonCode(s.pixel) << log2spp) | s.sampleIndex;
    uint bits = 2u * 16u + log2spp;  // enough base-4 digits for 65536^2 pixels
    uint digits = (bits + 1u) / 2u;
    bool odd = (log2spp & 1u) != 0u;
    uint index = 0u;
    for (int d = int(digits) - 1; d >= (odd ? 1 : 0); --d) {
        uint shift = 2u * uint(d) - (odd ? 1u : 0u);
        if (shift >= 32u) continue;
        uint digit = (z >> shift) & 3u;
        uint higher = shift + 2u >= 32u ? 0u : z >> (shift + 2u);
        // One of the 24 permutations of {0,1,2,3}, chosen by a hash of the
        // digits above and decoded Fisher-Yates style (swap slot k with slot
        // k + r_k, r_k < 4 - k).
        uint p = hash4(higher, pair, s.seed, 0x27d4eb2du) % 24u;
        uint perm[4] = uint[4](0u, 1u, 2u, 3u);
        uint r0 = p / 6u, r1 = (p % 6u) / 2u, r2 = p % 2u;
        uint t = perm[0]; perm[0] = perm[r0]; perm[r0] = t;
        t = perm[1]; perm[1] = perm[1u + r1]; perm[1u + r1] = t;
        t = perm[2]; perm[2] = perm[2u + r2]; perm[2u + r2] = t;
        index |= perm[digit] << shift;
    }
    if (odd) index |= (z & 1u) ^ (hash4(z >> 1u, pair, s.seed, 0x165667b1u) & 1u);
    return index;
}

vec2 samplerNext2D(inout Sampler s) {
    uint pair = s.dim >> 1u;
    s.dim += 2u;
    uint pairSeed = hash4(s.pixelIndex, pair, s.seed, 0x68e31da4u);
    if (kSampler == kSamplerIndependent) {
        uvec4 h = pcg4d(uvec4(s.pixelIndex, s.sampleIndex, pair, s.seed));
        return vec2(uintToUnit(h.x), uintToUnit(h.y));
    }
    if (kSampler == kSamplerSobol) return owenSobol2D(s.sampleIndex, pairSeed);
    if (kSampler == kSamplerBlueNoise) return owenSobol2D(zOrderIndex(s, pair), hash4(pair, s.seed, 7u, 8u));
    // Grid samplers: the pixel pair takes sample k at grid cell k (for
    // regular and rotated the same pattern in every pixel, whatever the seed:
    // the lecture's patterns). Other pairs take a per-pixel, per-pair
    // permutation of the cells; regular and rotated grids there are moved by
    // a random toroidal shift (Cranley & Patterson 1976), which keeps the
    // grid's structure and makes their estimates unbiased and seed-dependent.
    uint k = pair == 0u ? s.sampleIndex : permuteIndex(s.sampleIndex, s.grid * s.grid, pairSeed);
    vec2 jitter = vec2(0.5);
    if (kSampler == kSamplerStratified) {
        uvec4 h = pcg4d(uvec4(s.pixelIndex, s.sampleIndex, pair, s.seed ^ 0xa511e9b3u));
        jitter = vec2(uintToUnit(h.x), uintToUnit(h.y));
    }
    vec2 p = gridPoint(k, s.grid, jitter);
    if (pair != 0u && kSampler != kSamplerStratified) {
        uvec4 h = pcg4d(uvec4(s.pixelIndex, pair, s.seed, 0xcc9e2d51u));
        p = fract(p + vec2(uintToUnit(h.x), uintToUnit(h.y)));
    }
    return p;
}

vec2 sample2D(inout Sampler s) {
    s.dim = (s.dim + 1u) & ~1u;  // pairs start on even dimensions
    return samplerNext2D(s);
}

float sample1D(inout Sampler s) { return sample2D(s).x; }

#endif
