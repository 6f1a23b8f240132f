// Warps from [0,1)^2 to directions and points, frames, MIS weights.
#ifndef STRATA_LIB_SAMPLING_GLSL
#define STRATA_LIB_SAMPLING_GLSL

const float kPi = 3.14159265358979323846;
const float kInvPi = 0.31830988618379067154;

// Orthonormal basis around unit n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited", JCGT 6(1)).
void basis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted hemisphere around +z via the concentric disk map
// (Shirley & Chiu 1997); pdf = cos(theta) / pi.
vec3 sampleCosineHemisphere(vec2 u) {
    vec2 o = 2.0 * u - 1.0;
    vec2 d = vec2(0.0);
    if (o.x != 0.0 || o.y != 0.0) {
        float r, phi;
        if (abs(o.x) > abs(o.y)) {
            r = o.x;
            phi = (kPi / 4.0) * (o.y / o.x);
        } else {
            r = o.y;
            phi = (kPi / 2.0) - (kPi / 4.0) * (o.x / o.y);
        }
        d = r * vec2(cos(phi), sin(phi));
    }
    return vec3(d, sqrt(max(0.0, 1.0 - dot(d, d))));
}

vec3 toWorld(vec3 local, vec3 n) {
    vec3 t, b;
    basis(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

// Uniform point on a triangle as barycentrics (b1, b2) of v1 and v2
// (the square-root map, Turk 1990).
vec2 sampleTriangle(vec2 u) {
    float su = sqrt(u.x);
    return vec2(su * (1.0 - u.y), su * u.y);
}

// Veach's power heuristic (beta = 2) for the technique with pdf `a` against `b`.
float powerHeuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// Moves a ray origin off a surface along the geometric normal `n` (pointing to
// the side the ray leaves into), in integer ulps so the offset scales with
// |p| (Wächter & Binder 2019, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems ch. 6).
vec3 offsetRayOrigin(vec3 p, vec3 n) {
    const float kOrigin = 1.0 / 32.0;
    const float kFloatScale = 1.0 / 65536.0;
    const float kIntScale = 256.0;
    ivec3 ofs = ivec3(kIntScale * n);
    vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -ofs.x : ofs.x)),
                   intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -ofs.y : ofs.y)),
                   intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -ofs.z : ofs.z)));
    return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : pi.x,
                abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : pi.y,
                abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : pi.z);
}

// Origin for a ray leaving the hit (barycentrics u, v of v1, v2) of triangle
// tv into the side of unit geometric normal `side`: the hit point from
// barycentrics (more accurate than o + t d), moved off the surface.
vec3 spawnOrigin(TriVerts tv, float u, float v, vec3 side) {
    vec3 p = tv.v0.xyz + u * (tv.v1.xyz - tv.v0.xyz) + v * (tv.v2.xyz - tv.v0.xyz);
    return offsetRayOrigin(p, side);
}

#endif
