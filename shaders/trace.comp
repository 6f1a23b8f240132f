#version 460
// Trace-only kernel: one ray in, one closest (or any) hit out. Used by the
// tests to check the shader traversal against the CPU reference, and by
// `strata bench` to time traversal alone. One ray per invocation, or on CPU
// devices a work queue (SPEC_WORK_QUEUE, main below).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/sampling.glsl"

layout(std430, set = 0, binding = BINDING_RAYS) readonly buffer RayBuffer { TraceRay rays[]; };
layout(std430, set = 0, binding = BINDING_HITS) writeonly buffer HitBuffer { TraceHit hits[]; };
#ifdef STRATA_INSTANCING
layout(std430, set = 0, binding = BINDING_HIT_INSTANCES) writeonly buffer HitInstanceBuffer { uint hitInstances[]; };
#endif
layout(push_constant) uniform Push { TraceParams params; };
// A constant, not a push constant: lavapipe runs both sides of every branch,
// uniform or not, so with a mode chosen at run time every ray would pay for
// the other modes' traversals too.
layout(constant_id = SPEC_TRACE_MODE) const uint kTraceMode = kTraceClosest;
layout(constant_id = SPEC_WORK_QUEUE) const uint kWorkQueue = 0u;
layout(std430, set = 0, binding = BINDING_WORK) coherent buffer WorkBuffer { uint work[]; };

void traceOne(uint i) {
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
#ifdef STRATA_INSTANCING
            gInstance = gHitInstance;
#endif
            TriVerts tv = shadeTri(h.triangle);  // world space (an instance's triangle too)
            vec3 ng = cross(tv.v1.xyz - tv.v0.xyz, tv.v2.xyz - tv.v0.xyz);
            vec3 dir2 = rays[i + 1u].dir;
            vec3 side = normalize(dot(dir2, ng) > 0.0 ? ng : -ng);
#ifdef STRATA_INSTANCING
            vec3 from = spawnOrigin(tv, h.u, h.v, side, shadeSpawnError(bvhFetchTri(h.triangle)));
#else
            vec3 from = spawnOrigin(tv, h.u, h.v, side);
#endif
            bvhTraceClosest(from, dir2, 0.0, rays[i + 1u].tmax, h2);
        }
        hits[i + 1u] = h2;
    } else {
        bvhTraceClosest(r.origin, r.dir, r.tmin, r.tmax, h);
#ifdef STRATA_INSTANCING
        hitInstances[i] = gHitInstance;
#endif
    }
    hits[i] = h;
}

void main() {
    if (kWorkQueue == 0u) {
        if (gl_GlobalInvocationID.x < params.count) traceOne(params.first + gl_GlobalInvocationID.x);
        return;
    }
    // Work queue (CPU devices). lavapipe hands each thread one contiguous
    // share of a dispatch's workgroups, so a thread whose rows cost more, or
    // whose core other processes slow down, holds the dispatch up. Here a
    // subgroup takes the next rays from this dispatch's counter, again and
    // again, so the threads share the work as they go and walk the image
    // side by side. lavapipe ends every loop of an invocation once 65535
    // iterations are spent in all (lib/bvh_common.glsl, gBvhTicks), so a subgroup
    // first takes one ray per lane (with all of that budget, as without the
    // queue), then more only while it has spent less than kQueueTickBudget,
    // and only as many vectors of rays (one per lane each) as fit 4 times
    // over in what is left at the rate of its costliest vector so far. The
    // first pass launches one subgroup per kQueueRaysPerSubgroup rays; the
    // subgroup that finishes it last sets the second pass (an indirect
    // dispatch) to a subgroup per vector of rays still left, usually none.
    const uint words = params.slot * kQueueWords;
    // Each lane keeps the most its traversals of one vector added to
    // gBvhTicks; the lanes' sum of that bounds any vector's ticks.
    uint laneMost = 0u, vectors = 1u, taken = 0u;
    for (uint take = 0u;; ++take) {
        uint base = 0u;
        if (subgroupElect()) base = atomicAdd(work[words], vectors * gl_SubgroupSize);
        base = subgroupBroadcastFirst(base);
        if (base >= params.count) break;
        for (uint k = 0u; k < vectors; ++k) {
            uint j = base + k * gl_SubgroupSize + gl_SubgroupInvocationID;
            uint before = gBvhTicks;
            if (j < params.count) traceOne(params.first + j);
            laneMost = max(laneMost, gBvhTicks - before);
        }
        taken += vectors;
        // Ticks besides the traversals': the two loops here, and 2 for each
        // traversal no lane enters (its loops still run once).
        uint spent = subgroupAdd(gBvhTicks) + (take + 1u) + 5u * taken;
        uint costliest = subgroupAdd(laneMost) + 5u;
        if (spent >= kQueueTickBudget) break;
        vectors = min(kQueueMaxVectors, (kLoopLimit - spent) / (4u * costliest));
        if (vectors == 0u) break;
    }
    if (params.pass == 0u) {
        uint finished = 0u;
        memoryBarrierBuffer();  // the last take before the count of finished subgroups
        if (subgroupElect()) finished = atomicAdd(work[words + 1u], 1u);
        finished = subgroupBroadcastFirst(finished);
        if (finished + 1u == gl_NumWorkGroups.x * gl_NumSubgroups && subgroupElect()) {
            // Every other subgroup has taken its last rays: no take failed
            // unless the queue is empty, so the counter is the next ray.
            memoryBarrierBuffer();
            uint next = min(atomicAdd(work[words], 0u), params.count);
            work[words + 2u] = (params.count - next + 63u) / 64u;
            work[words + 3u] = 1u;
            work[words + 4u] = 1u;
        }
    }
}
