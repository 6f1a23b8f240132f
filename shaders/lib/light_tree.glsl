// The light tree (STRATA_LIGHT_TREE, the lighttree axis): a binary tree
// over the bounded lights (emissive triangles, point and spot lights) built
// on the host (pack/light_tree.h), after Conty Estevez & Kulla 2018 and
// pbrt-v4's BVH light sampler. A shading point descends it once, choosing
// each child in proportion to a bound of what the child's lights can give
// it (lightNodeImportance); the probability of any light is the product of
// the choices on its path, which its Emitter's `trail` spells out.
// Needs lib/emitters.glsl (for kTexelAll through lib/reads.glsl).
#ifndef STRATA_LIB_LIGHT_TREE_GLSL
#define STRATA_LIB_LIGHT_TREE_GLSL

#include "lib/reads.glsl"

layout(std430, set = 0, binding = BINDING_LIGHT_TREE) readonly buffer LightTreeBuffer { LightNode lightNodes[]; };
layout(set = 0, binding = BINDING_LIGHT_TREE_TEXEL) uniform usamplerBuffer lightNodesTexel;

LightNode lightNodeAt(uint i) {
    if (kTexelAll) {
        uvec4 t[kLightNodeTexels] = texels3(lightNodesTexel, i);
        return LightNode(TEXEL_VEC3(t, kLightNodeWordCentre), TEXEL_FLOAT(t, kLightNodeWordRadius),
                         TEXEL_VEC3(t, kLightNodeWordAxis), TEXEL_FLOAT(t, kLightNodeWordPower),
                         TEXEL_FLOAT(t, kLightNodeWordCosThetaO), TEXEL_FLOAT(t, kLightNodeWordSinThetaO),
                         TEXEL_FLOAT(t, kLightNodeWordCosThetaE), TEXEL_UINT(t, kLightNodeWordLink));
    }
    return lightNodes[i];
}

bool lightNodeIsLeaf(LightNode nd) { return (nd.link & kLightNodeLeaf) != 0u; }
uint lightNodeIndex(LightNode nd) { return nd.link & kLightNodeIndex; }

// cos(a - b) for angles a, b in [0, pi] given by their cosines and sines,
// with a - b clamped at 0 (cos 1): the smallest angle a can shrink to.
float cosMinusClamped(float cosA, float sinA, float cosB, float sinB) {
    return cosA >= cosB ? 1.0 : cosA * cosB + sinA * sinB;
}
float sinMinusClamped(float cosA, float sinA, float cosB, float sinB) {
    return cosA >= cosB ? 0.0 : sinA * cosB - cosA * sinB;
}

// An upper bound, up to a constant, of what the node's lights can send to
// point p with unit normal n (n = 0: no receiver cosine): power / d^2 times
// the smallest angle between the cone and the direction to p, and the
// smallest angle between n and the directions to the box. 0 only where no
// light below can reach p: its direction from every light leaves the cone's
// emission range, or lies in p's tangent plane.
float lightNodeImportance(LightNode nd, vec3 p, vec3 n) {
    vec3 toP = p - nd.centre;
    float d2 = dot(toP, toP);
    float invD = inversesqrt(d2);
    // Inside the bounding sphere every direction is possible (theta_b = pi).
    float sinB = nd.radius * invD;
    bool outside = sinB < 1.0;
    float cosB = outside ? sqrt(1.0 - sinB * sinB) : -1.0;
    sinB = outside ? sinB : 0.0;
    vec3 wi = d2 > 0.0 ? toP * invD : nd.axis;
    float cosW = dot(nd.axis, wi);
    if ((nd.link & kLightNodeTwoSided) != 0u) cosW = abs(cosW);
    float sinW = sqrt(max(0.0, 1.0 - cosW * cosW));
    float sinO = nd.sinTheta_o;
    // theta' = max(0, theta_w - theta_o - theta_b)
    float cosX = cosMinusClamped(cosW, sinW, nd.cosTheta_o, sinO);
    float sinX = sinMinusClamped(cosW, sinW, nd.cosTheta_o, sinO);
    float cosP = cosMinusClamped(cosX, sinX, cosB, sinB);
    if (cosP <= nd.cosTheta_e) return 0.0;
    // The distance is clamped to the box's half diagonal: near or inside it
    // 1/d^2 says nothing of the lights.
    float importance = nd.power * cosP / max(max(d2, nd.radius * nd.radius), 1e-20);
    if (n != vec3(0.0)) {
        float cosI = abs(dot(wi, n));
        float sinI = sqrt(max(0.0, 1.0 - cosI * cosI));
        importance *= cosMinusClamped(cosI, sinI, cosB, sinB);
    }
    return max(importance, 0.0);
}

// The probability of the first child of a node whose children have
// importances ia and ib (ia + ib > 0).
float lightFirstChildProb(float ia, float ib) { return ia / (ia + ib); }

// One light for p and n: its emitter index and probability `pmf` (of the
// tree alone), kNoLight with pmf 0 where no light can reach p. `u` is
// rescaled at each choice. A tree of one light always gives it (pmf 1).
// `leafImportance`: the chosen leaf's lightNodeImportance (resampling's
// target, lib/lights.glsl).
uint sampleLightTree(vec3 p, vec3 n, float u, out float pmf, out float leafImportance) {
    pmf = 1.0;
    uint i = 0u;
    LightNode nd = lightNodeAt(0u);
    leafImportance = lightNodeIsLeaf(nd) ? lightNodeImportance(nd, p, n) : 0.0;
    while (!lightNodeIsLeaf(nd)) {
        LightNode a = lightNodeAt(i + 1u), b = lightNodeAt(lightNodeIndex(nd));
        float ia = lightNodeImportance(a, p, n), ib = lightNodeImportance(b, p, n);
        if (!(ia + ib > 0.0)) {
            pmf = 0.0;
            return kNoLight;
        }
        float pa = lightFirstChildProb(ia, ib);
        if (u < pa) {
            u = min(u / pa, 0.99999994);
            pmf *= pa;
            i = i + 1u;
            nd = a;
            leafImportance = ia;
        } else {
            u = min((u - pa) / (1.0 - pa), 0.99999994);
            pmf *= 1.0 - pa;
            i = lightNodeIndex(nd);
            nd = b;
            leafImportance = ib;
        }
    }
    return lightNodeIndex(nd);
}

// The probability that sampleLightTree(p, n, ...) gives the light whose
// Emitter has this trail.
float lightTreePmf(vec3 p, vec3 n, uint trail) {
    float pmf = 1.0;
    uint i = 0u;
    LightNode nd = lightNodeAt(0u);
    while (!lightNodeIsLeaf(nd)) {
        LightNode a = lightNodeAt(i + 1u), b = lightNodeAt(lightNodeIndex(nd));
        float ia = lightNodeImportance(a, p, n), ib = lightNodeImportance(b, p, n);
        if (!(ia + ib > 0.0)) return 0.0;
        float pa = lightFirstChildProb(ia, ib);
        if ((trail & 1u) == 0u) {
            pmf *= pa;
            i = i + 1u;
            nd = a;
        } else {
            pmf *= 1.0 - pa;
            i = lightNodeIndex(nd);
            nd = b;
        }
        trail >>= 1u;
    }
    return pmf;
}

#endif
