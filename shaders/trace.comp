#version 460
// Trace-only kernel: one ray in, one closest (or any) hit out. Used by the
// tests to check the shader traversal against the CPU reference, and by
// `strata bench` to time traversal alone.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "lib/scene.glsl"

layout(std430, set = 0, binding = BINDING_RAYS) readonly buffer RayBuffer { TraceRay rays[]; };
layout(std430, set = 0, binding = BINDING_HITS) writeonly buffer HitBuffer { TraceHit hits[]; };
layout(push_constant) uniform Push { TraceParams params; };

void main() {
    if (gl_GlobalInvocationID.x >= params.count) return;
    uint i = params.first + gl_GlobalInvocationID.x;
    TraceRay r = rays[i];
    TraceHit h;
    if (params.anyHit != 0u) {
        bool occluded = bvhTraceAny(r.origin, r.dir, r.tmin, r.tmax);
        h = TraceHit(occluded ? 1.0 : -1.0, occluded ? 0u : kNoHit, 0.0, 0.0);
    } else {
        bvhTraceClosest(r.origin, r.dir, r.tmin, r.tmax, h);
    }
    hits[i] = h;
}
