// Time for motion blur (STRATA_MOTION, the motion axis): the time of
// the path being traced, quaternions, and the pose of a moving instance at
// that time from its MotionKeys (shared/types.h). Included by lib/scene.glsl.
#ifndef STRATA_LIB_MOTION_GLSL
#define STRATA_LIB_MOTION_GLSL

// The time of the path being traced (seconds on the animation's timeline):
// every ray of a path sees the scene at its camera sample's time
// (lib/camera.glsl, motionCameraRay).
float gRayTime = 0.0;

// Unit quaternions (xyzw): v rotated by q.
vec3 quatRotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// Spherical linear interpolation on the shorter arc; nearly equal
// quaternions are lerped and normalised (sin(theta) would lose all precision).
vec4 quatSlerp(vec4 a, vec4 b, float w) {
    float c = dot(a, b);
    if (c < 0.0) {
        b = -b;
        c = -c;
    }
    if (c > 0.9995) return normalize(mix(a, b, w));
    float theta = acos(c), s = sin(theta);
    return (sin((1.0 - w) * theta) / s) * a + (sin(w * theta) / s) * b;
}

#ifdef STRATA_INSTANCING
// The pose of a moving instance at gRayTime, as the six rows instanceRow
// gives (worldToObject's three, then objectToWorld's), cached for the record
// last asked for (gRayTime is fixed for the path).
uint gPoseRecord = kNoInstance;
vec4 gPoseRows[6];

vec4 motionKeyTexel(uint key, uint k) { return uintBitsToFloat(instanceWord(key + k)); }

void motionPose(uint first, uint count) {
    // The last key at or before the time (the first when the time precedes it).
    uint a = first;
    for (uint k = 1u; k < count; ++k) {
        uint key = first + k * kMotionKeyTexels;
        if (motionKeyTexel(key, 0u).x <= gRayTime) a = key;
    }
    uint last = first + (count - 1u) * kMotionKeyTexels;
    uint b = min(a + kMotionKeyTexels, last);
    vec4 ta = motionKeyTexel(a, 0u), tb = motionKeyTexel(b, 0u);
    float w = tb.x > ta.x ? clamp((gRayTime - ta.x) / (tb.x - ta.x), 0.0, 1.0) : 0.0;
    vec3 t = mix(ta.yzw, tb.yzw, w);
    vec4 q = quatSlerp(motionKeyTexel(a, 1u), motionKeyTexel(b, 1u), w);
    vec3 s = mix(motionKeyTexel(a, 2u).xyz, motionKeyTexel(b, 2u).xyz, w);
    vec3 c0 = quatRotate(q, vec3(1.0, 0.0, 0.0)), c1 = quatRotate(q, vec3(0.0, 1.0, 0.0)),
         c2 = quatRotate(q, vec3(0.0, 0.0, 1.0));
    // objectToWorld = T R S; worldToObject = S^-1 R^T (p - T).
    vec3 r0 = c0 / s.x, r1 = c1 / s.y, r2 = c2 / s.z;
    gPoseRows[0] = vec4(r0, -dot(r0, t));
    gPoseRows[1] = vec4(r1, -dot(r1, t));
    gPoseRows[2] = vec4(r2, -dot(r2, t));
    gPoseRows[3] = vec4(c0.x * s.x, c1.x * s.y, c2.x * s.z, t.x);
    gPoseRows[4] = vec4(c0.y * s.x, c1.y * s.y, c2.y * s.z, t.y);
    gPoseRows[5] = vec4(c0.z * s.x, c1.z * s.y, c2.z * s.z, t.z);
}

// Row `row` of the record starting at texel `first`: its stored row, or for
// a moving instance (motionCount > 0) the row of its pose at gRayTime.
vec4 instanceRow(uint first, uint row) {
    uvec4 m = instanceWord(first + kInstanceWordMotionFirst / kTexelWords);
    uint count = m[kInstanceWordMotionCount % kTexelWords];
    if (count == 0u) return uintBitsToFloat(instanceWord(first + row));
    if (gPoseRecord != first) {
        motionPose(m[kInstanceWordMotionFirst % kTexelWords], count);
        gPoseRecord = first;
    }
    return gPoseRows[row];
}
#endif

#endif
