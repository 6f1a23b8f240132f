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

// Uniform point on a triangle as barycentrics (b1, b2) of v1 and v2
// (the square-root map, Turk 1990).
vec2 sampleTriangle(vec2 u) {
    float su = sqrt(u.x);
    return vec2(su * (1.0 - u.y), su * u.y);
}

// Veach's power heuristic (beta = 2) for the technique with pdf `a` against `b`.
// Solid angle of the triangle v0 v1 v2 seen from p (Van Oosterom & Strackee
// 1983): 2 atan(|a . (b x c)|, 1 + a.b + b.c + c.a) of the unit directions.
float triangleSolidAngle(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
    vec3 a = normalize(v0 - p), b = normalize(v1 - p), c = normalize(v2 - p);
    return abs(2.0 * atan(abs(dot(a, cross(b, c))), 1.0 + dot(a, b) + dot(b, c) + dot(c, a)));
}

// A direction uniform over the spherical triangle of unit vectors A, B, C
// of solid angle `area` (triangleSolidAngle's: the pdf's own, so the sub-
// areas add up to it) (Arvo 1995, "Stratified sampling of spherical
// triangles"): u.x chooses the sub-triangle A B C' of area u.x times the
// whole, u.y a point on the arc from B to C'. The angle at A comes from
// atan(sin, cos) of the edges' plane normals. vec3(0) where the triangle
// is degenerate.
vec3 sampleSphericalTriangle(vec3 A, vec3 B, vec3 C, float area, vec2 u) {
    vec3 nAB = cross(A, B), nCA = cross(C, A);
    if (dot(nAB, nAB) == 0.0 || dot(nCA, nCA) == 0.0) return vec3(0.0);
    nAB = normalize(nAB);
    nCA = normalize(nCA);
    // The angle at A, between the planes of its two edges.
    float cosAlpha = -dot(nAB, nCA), sinAlpha = length(cross(nAB, nCA));
    float alpha = atan(sinAlpha, cosAlpha);
    float sub = u.x * area;
    float s = sin(sub - alpha), t = cos(sub - alpha);
    float pu = t - cosAlpha, pv = s + sinAlpha * dot(A, B);
    float den = (pv * s + pu * t) * sinAlpha;
    float q = den != 0.0 ? clamp(((pv * t - pu * s) * cosAlpha - pv) / den, -1.0, 1.0) : 1.0;
    vec3 cPerp = C - dot(C, A) * A;
    vec3 cHat = q * A + sqrt(max(0.0, 1.0 - q * q)) * (dot(cPerp, cPerp) > 0.0 ? normalize(cPerp) : vec3(0.0));
    float z = clamp(1.0 - u.y * (1.0 - dot(cHat, B)), -1.0, 1.0);
    vec3 pPerp = cHat - dot(cHat, B) * B;
    return z * B + sqrt(max(0.0, 1.0 - z * z)) * (dot(pPerp, pPerp) > 0.0 ? normalize(pPerp) : vec3(0.0));
}

float powerHeuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// Ray origins that do not re-hit their own surface at any scale. `p` carries
// an absolute error of at most `err` per component; moving it by the error
// projected on the unit normal `n` (pointing to the side the ray leaves into)
// and rounding each component one float further away puts it strictly on
// that side (Pharr, Jakob & Humphreys, "Physically Based Rendering", 4th ed.,
// sec. 6.8.6). The offset scales with the coordinates' magnitude, so a scene
// moved far from the origin or scaled down keeps its look; a fixed count of
// ulps (Wächter & Binder 2019) shifted a 2-unit box moved to 1e4 by 0.25
// units and failed the invariance test.
const float kGamma7 = 7.0 * 5.9604645e-8 / (1.0 - 7.0 * 5.9604645e-8);  // gamma(7), u = 2^-24
const float kUlp = 1.1920929e-7;                                         // 2^-23

float nextFloatAway(float x, float direction) {
    if (direction == 0.0) return x;
    if (x == 0.0) return direction > 0.0 ? 1.0e-45 : -1.0e-45;
    int bits = floatBitsToInt(x);
    bool up = direction > 0.0;
    bits += (x > 0.0) == up ? 1 : -1;
    return intBitsToFloat(bits);
}

vec3 offsetRayOrigin(vec3 p, vec3 err, vec3 n) {
    float d = dot(abs(n), err);
    vec3 o = p + d * n;
    return vec3(nextFloatAway(o.x, n.x), nextFloatAway(o.y, n.y), nextFloatAway(o.z, n.z));
}

// Origin for a ray leaving the hit (barycentrics u, v of v1, v2) of triangle
// tv into the side of unit geometric normal `side`. The point is the
// barycentric sum; its error is bounded by gamma(7) times the sum of the
// terms' magnitudes, plus one ulp of the largest vertex for the rounding of
// b0 = 1 - u - v.
vec3 spawnOrigin(TriVerts tv, float u, float v, vec3 side) {
    float b0 = 1.0 - u - v;
    precise vec3 p = b0 * tv.v0.xyz + u * tv.v1.xyz + v * tv.v2.xyz;
    vec3 err = kGamma7 * (abs(b0 * tv.v0.xyz) + abs(u * tv.v1.xyz) + abs(v * tv.v2.xyz)) +
               kUlp * max(abs(tv.v0.xyz), max(abs(tv.v1.xyz), abs(tv.v2.xyz)));
    return offsetRayOrigin(p, err, side);
}

#ifdef STRATA_INSTANCING
// The same, the point's error widened by `extraErr` (an instance's
// transforms: shadeSpawnError). offsetRayOrigin moves p by the error
// along `side`, so the two offsets add.
vec3 spawnOrigin(TriVerts tv, float u, float v, vec3 side, vec3 extraErr) {
    vec3 p = spawnOrigin(tv, u, v, side);
    return offsetRayOrigin(p, extraErr, side);
}
#endif

// The same for a point v0 + b1 e1 + b2 e2 sampled on an emitter stored as a
// vertex and two edges (the edges were rounded on the host: counted once more).
vec3 spawnOriginOnEmitter(vec3 p, vec3 v0, vec3 e1, vec3 e2, vec3 side) {
    vec3 err = kGamma7 * (abs(v0) + abs(e1) + abs(e2));
    return offsetRayOrigin(p, err, side);
}

#endif
