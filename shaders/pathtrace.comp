#version 460
// Progressive path tracer: one path per pixel of the dispatch's tile, one
// sample per dispatch, added into the accumulation buffer (sum, count, sum of
// squares). The glTF BSDF (lib/bsdf.glsl; plain Lambert when no material has
// a specular or transmission lobe); next-event estimation on all lights
// (emissive triangles, KHR_lights_punctual, the environment; lib/lights.glsl)
// combined with BSDF sampling by the power heuristic (Veach 1997; delta
// lights and delta lobes take no MIS; SPEC_MIS can keep one technique only);
// Russian roulette after depth 4 (lib/path.glsl pathSurvives). maxDepth
// counts scattering events (pbrt's convention): 0 shows emitters and the
// environment seen directly, 1 is direct lighting.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "lib/scene.glsl"
#include "lib/film.glsl"

layout(constant_id = SPEC_HAS_EMITTERS) const uint kHasEmitters = 1u;  // any light at all
layout(constant_id = SPEC_MIS) const uint kMis = kMisPower;             // kMis* (types.h)
layout(constant_id = SPEC_COUNT_RAYS) const uint kCountRays = 1u;       // count rays in RenderCounters
layout(constant_id = SPEC_WORK_QUEUE) const uint kWorkQueue = 0u;       // 1: blocks in a permuted order

layout(push_constant) uniform Push { DispatchParams params; };

#include "lib/lights.glsl"
#include "lib/bsdf.glsl"
#define STRATA_MEDIUM_SHADOWS  // a medium's shadow rays through its index-matched boundary (lib/path.glsl)
#include "lib/path.glsl"

// Rays this invocation traced (SPEC_COUNT_RAYS).
uint gClosestRays = 0u;
uint gShadowRays = 0u;

// A path's state at its start: the vertex, and the globals its shading keeps.
PathVertex pathBegin() {
#ifdef STRATA_DISPERSION
    gWavelength = 0.0;  // each sample's path starts RGB
#endif
#ifdef STRATA_TEXTURE_LOD
    gConeWidth = 0.0;
    gConeSpread = cameraConeSpread();
#endif
#ifdef STRATA_AOV
    aovStart();
#endif
#if defined(STRATA_MOTION) && defined(STRATA_INSTANCING)
    gPoseRecord = kNoInstance;  // the poses cached were at the last sample's time
#endif
    return pathStart();
}

// Samples params.sampleIndex to params.sampleIndex + params.sampleCount - 1
// of the pixel at `local` of the dispatch's tile, each path added to the
// pixel's sums as it ends, in sample order. One loop of path segments runs
// them all: a path that ends starts the invocation's next sample in the
// next segment, so a subgroup's lanes trace together until each has taken
// its samples, instead of each sample waiting for the subgroup's longest
// path.
void shadePixel(uvec2 local) {
    if (local.x >= params.tileW || local.y >= params.tileH) return;
    uvec2 pixel = uvec2(params.tileX, params.tileY) + local;
    if (!pixelSampled(pixel)) return;  // adaptive: a converged block
    // The sampler keeps the pixel and the sample's index: no more live values in the loop.
    Sampler smp;
    vec3 origin, dir;
    cameraSample(pixel, params.sampleIndex, smp, origin, dir);
    PathVertex v = pathBegin();
    uint depth = 0u;
    for (;;) {
        TraceHit hit;
        bool ended = false;
        if (kCountRays != 0u) ++gClosestRays;
        if (!bvhTraceClosest(origin, dir, 0.0, kRayMax, hit)) {
            pathEscaped(v, dir);
            ended = true;
        } else {
            PathNext o = pathShadeHit(v, smp, dir, hit, depth);
            if (o.shadowTried) {
                if (kCountRays != 0u) ++gShadowRays;
#ifdef PATH_MEDIUM_SHADOWS
                if (o.shadowOpen && o.shadowMedium) {
                    if (kCountRays != 0u) ++gClosestRays;
                    o.shadowOpen = pathMediumShadow(o);
                }
#endif
                // One call site for both kinds of light: each call is inlined,
                // and a second copy of the traversal adds to pipeline creation.
                bool visible = o.shadowOpen && !bvhTraceAny(o.shadow.origin, o.shadow.dir, 0.0, o.shadow.tmax);
                if (visible) v.L += o.contrib;
            }
            ended = !o.alive;
            origin = o.next.origin;
            dir = o.next.dir;
            ++depth;
        }
        if (ended) {
            accumulateSample(smp.pixelIndex, v.L);
#ifdef STRATA_AOV
            accumulateAov(smp.pixelIndex, smp.sampleIndex, v.L);
#endif
            if (smp.sampleIndex - params.sampleIndex + 1u >= params.sampleCount) break;
            cameraSample(smp.pixel, smp.sampleIndex + 1u, smp, origin, dir);
            v = pathBegin();
            depth = 0u;
        }
    }
}

void main() {
    uvec2 local = gl_GlobalInvocationID.xy;
    if (kWorkQueue != 0u) {
        // lavapipe gives each thread one contiguous share of the workgroups:
        // with blocks in row order, one thread takes the tile's top rows and
        // the other its bottom ones, and one waits for the other. Workgroup
        // w shades block (w * blockStride) mod blocks instead (a permutation;
        // each share spreads over the whole tile). A path's loops cannot be
        // bounded, so the trace kernel's work queue, which takes rays until
        // lavapipe's loop budget runs low, is not an option here
        // (lib/bvh_common.glsl, gBvhTicks); the host keeps a CPU device's
        // paths an invocation to kCpuSamplesPerDispatch (integrate/megakernel.cpp).
        uint blocksX = (params.tileW + 7u) / 8u, blocks = blocksX * ((params.tileH + 7u) / 8u);
        uint w = (gl_WorkGroupID.y * blocksX + gl_WorkGroupID.x) * params.blockStride % blocks;
        local = uvec2(w % blocksX, w / blocksX) * 8u + gl_LocalInvocationID.xy;
    }
    shadePixel(local);
    if (kCountRays != 0u) {
        // One pair of atomics per subgroup; a carry into the high word when the low one wraps.
        uint closest = subgroupAdd(gClosestRays), shadow = subgroupAdd(gShadowRays);
        if (subgroupElect()) {
            uint old = atomicAdd(counters.closestLo, closest);
            if (old + closest < old) atomicAdd(counters.closestHi, 1u);
            old = atomicAdd(counters.shadowLo, shadow);
            if (old + shadow < old) atomicAdd(counters.shadowHi, 1u);
        }
    }
}
