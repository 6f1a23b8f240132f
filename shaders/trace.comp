#version 460
// Trace-only kernel: one ray in, one closest (or any) hit out. Used by the
// tests to check the shader traversal against the CPU reference, and by
// `strata bench` to time traversal alone.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/sampling.glsl"

layout(std430, set = 0, binding = BINDING_RAYS) readonly buffer RayBuffer { TraceRay rays[]; };
layout(std430, set = 0, binding = BINDING_HITS) writeonly buffer HitBuffer { TraceHit hits[]; };
layout(push_constant) uniform Push { TraceParams params; };
// A constant, not a push constant: lavapipe runs both sides of every branch,
// uniform or not, so a mode chosen at run time cost the other modes'
// traversals on every ray (primary rays 1.8x slower on the Cornell box).
layout(constant_id = SPEC_TRACE_MODE) const uint kTraceMode = kTraceClosest;

void main() {
    if (gl_GlobalInvocationID.x >= params.count) return;
    uint i = params.first + gl_GlobalInvocationID.x;
    TraceRay r = rays[i];
    TraceHit h;
    if (kTraceMode == kTraceAny) {
        bool occluded = bvhTraceAny(r.origin, r.dir, r.tmin, r.tmax);
        h = TraceHit(occluded ? 1.0 : -1.0, occluded ? 0u : kNoHit, 0.0, 0.0);
    } else if (kTraceMode == kTraceSpawn) {
        if ((i & 1u) != 0u) return;  // the pair's first invocation writes both
        bvhTraceClosest(r.origin, r.dir, r.tmin, r.tmax, h);
        TraceHit h2 = TraceHit(-1.0, kNoHit, 0.0, 0.0);
        if (h.triangle != kNoHit) {
            TriVerts tv = bvhFetchTri(h.triangle);
            vec3 ng = cross(tv.v1.xyz - tv.v0.xyz, tv.v2.xyz - tv.v0.xyz);
            vec3 dir2 = rays[i + 1u].dir;
            vec3 side = normalize(dot(dir2, ng) > 0.0 ? ng : -ng);
            bvhTraceClosest(spawnOrigin(tv, h.u, h.v, side), dir2, 0.0, rays[i + 1u].tmax, h2);
        }
        hits[i + 1u] = h2;
    } else {
        bvhTraceClosest(r.origin, r.dir, r.tmin, r.tmax, h);
    }
    hits[i] = h;
}
