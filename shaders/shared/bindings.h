// Descriptor set 0 bindings and specialization constant ids, shared by the
// host and every shader.
#ifndef STRATA_SHARED_BINDINGS_H
#define STRATA_SHARED_BINDINGS_H

#ifdef __cplusplus
namespace strata::gpu {
#define STRATA_BINDING(name, value) inline constexpr unsigned name = value
#else
#define STRATA_BINDING(name, value) const uint name = value
#endif

STRATA_BINDING(BINDING_FRAME, 0);         // uniform FrameUniforms
STRATA_BINDING(BINDING_NODES, 1);         // storage uvec4[]: BvhNode4, or BvhNode with STRATA_BVH2
STRATA_BINDING(BINDING_TRIS, 2);          // storage TriVerts[]
STRATA_BINDING(BINDING_SHADING, 3);       // storage TriShading[]
STRATA_BINDING(BINDING_MATERIALS, 4);     // storage Material[]
STRATA_BINDING(BINDING_EMITTERS, 5);      // storage Emitter[]
STRATA_BINDING(BINDING_ACCUM, 6);         // storage vec4[] (kAccumVec4PerPixel per pixel)
STRATA_BINDING(BINDING_COUNTERS, 7);      // storage RenderCounters
STRATA_BINDING(BINDING_NODES_TEXEL, 8);   // usamplerBuffer over BINDING_NODES (RGBA32UI)
STRATA_BINDING(BINDING_TRIS_TEXEL, 9);    // usamplerBuffer over BINDING_TRIS (RGBA32UI)
STRATA_BINDING(BINDING_RAYS, 10);         // storage: trace kernel input rays
STRATA_BINDING(BINDING_HITS, 11);         // storage: trace kernel output hits
STRATA_BINDING(BINDING_SAMPLES, 12);      // storage vec4[]: sampling test kernel output
STRATA_BINDING(BINDING_FILTER, 13);       // storage float[]: pixel filter inverse CDF (render/filter.h)
STRATA_BINDING(BINDING_TEXCOORDS, 14);    // storage: per-triangle texture coordinates (BVH order)
STRATA_BINDING(BINDING_TANGENTS, 15);     // storage: per-triangle tangents (BVH order)
STRATA_BINDING(BINDING_TEXREFS, 16);      // storage TextureRef[]
STRATA_BINDING(BINDING_TEXELS, 17);       // texel view over the packed texture texels
STRATA_BINDING(BINDING_ENV_TEXELS, 18);   // texel view over the environment map (RGBA32F)
STRATA_BINDING(BINDING_ENV_CDF, 19);      // storage float[]: environment map sampling tables
STRATA_BINDING(BINDING_SHADING_TEXEL, 20);    // usamplerBuffer over BINDING_SHADING (RGBA32UI)
STRATA_BINDING(BINDING_TEXCOORDS_TEXEL, 21);  // usamplerBuffer over BINDING_TEXCOORDS (RGBA32UI)
STRATA_BINDING(BINDING_TANGENTS_TEXEL, 22);   // usamplerBuffer over BINDING_TANGENTS (RGBA32UI)
STRATA_BINDING(BINDING_EMITTERS_TEXEL, 23);   // usamplerBuffer over BINDING_EMITTERS (RGBA32UI)
STRATA_BINDING(BINDING_WORK, 24);         // storage uint[]: work-queue counters (trace kernel, SPEC_WORK_QUEUE)
STRATA_BINDING(BINDING_MATERIALS_TEXEL, 25);  // usamplerBuffer over BINDING_MATERIALS (RGBA32UI)
STRATA_BINDING(BINDING_TEXREFS_TEXEL, 26);    // usamplerBuffer over BINDING_TEXREFS (RGBA32UI)
STRATA_BINDING(BINDING_ENV_CDF_TEXEL, 27);    // usamplerBuffer over BINDING_ENV_CDF (RGBA32UI)
// The wavefront integrator's lists (wavefront.comp, integrate/wavefront.cpp).
STRATA_BINDING(BINDING_WAVE_STATE, 28);        // storage PathState[], one per path of the tile
STRATA_BINDING(BINDING_WAVE_LIVE, 29);         // storage uint[]: the path of each ray traced
STRATA_BINDING(BINDING_WAVE_HITS, 30);         // storage TraceHit[]: their closest hits
STRATA_BINDING(BINDING_WAVE_NEXT_RAYS, 31);    // storage TraceRay[]: the next bounce's rays (appended)
STRATA_BINDING(BINDING_WAVE_SHADOW_RAYS, 32);  // storage TraceRay[]: shadow rays (appended)
STRATA_BINDING(BINDING_WAVE_CONTRIB, 33);      // storage vec4[]: each shadow ray's contribution
STRATA_BINDING(BINDING_WAVE_RAYS, 34);         // storage TraceRay[]: the rays traced
STRATA_BINDING(BINDING_WAVE_NEXT_LIVE, 35);    // storage uint[]: the path of each next ray
STRATA_BINDING(BINDING_WAVE_SHADOW_SLOTS, 36); // storage uint[]: the path of each shadow ray
STRATA_BINDING(BINDING_WAVE_COUNTS, 37);       // storage uint[2]: next rays, shadow rays appended
STRATA_BINDING(BINDING_WAVE_SHADOW_HITS, 38);  // storage TraceHit[]: the shadow rays' results
STRATA_BINDING(BINDING_INSTANCES, 39);        // storage uvec4[]: top-level nodes, then Instance records
STRATA_BINDING(BINDING_INSTANCES_TEXEL, 40);  // usamplerBuffer over BINDING_INSTANCES (RGBA32UI)
STRATA_BINDING(BINDING_COLORS, 41);        // storage TriColors[]: COLOR_0 per triangle (BVH order)
STRATA_BINDING(BINDING_COLORS_TEXEL, 42);  // usamplerBuffer over BINDING_COLORS (RGBA32UI)
STRATA_BINDING(BINDING_HIT_INSTANCES, 43);  // storage uint[]: each closest hit's instance (STRATA_INSTANCING: the
                                            // trace kernel writes it, the wavefront's shade stage reads it)
STRATA_BINDING(BINDING_LIGHT_TREE, 44);        // storage LightNode[] (kFeatureLightTree; 16 bytes otherwise)
STRATA_BINDING(BINDING_LIGHT_TREE_TEXEL, 45);  // usamplerBuffer over BINDING_LIGHT_TREE (RGBA32UI)
STRATA_BINDING(BINDING_ACTIVE_BLOCKS, 46);  // storage uint[]: 1 per 8x8 block of the image still sampled
                                            // (SPEC_ADAPTIVE; 16 bytes otherwise)
STRATA_BINDING(BINDING_WAVE_CONES, 47);  // storage vec2[]: each path's ray cone, width and spread
                                         // (STRATA_TEXTURE_LOD; 16 bytes otherwise)
STRATA_BINDING(BINDING_WAVE_TREE_VERTEX, 48);  // storage vec4[2]: each path's last point and normal
                                               // (STRATA_LIGHT_TREE's MIS; 16 bytes otherwise)
STRATA_BINDING(BINDING_COUNT, 49);

// Specialization constant ids.
STRATA_BINDING(SPEC_TEXEL_FETCH, 0);      // kReads* (types.h): which scene arrays are read through texel views
STRATA_BINDING(SPEC_HAS_EMITTERS, 1);     // 0: no emissive triangles, NEE compiled out
STRATA_BINDING(SPEC_SAMPLER, 2);          // kSampler* (types.h)
STRATA_BINDING(SPEC_FEATURES, 3);         // kFeature* bits (types.h): what the scene uses
STRATA_BINDING(SPEC_MIS, 4);              // kMis* (types.h): how light and BSDF samples combine
STRATA_BINDING(SPEC_COUNT_RAYS, 5);       // 1: count closest and shadow rays in RenderCounters
STRATA_BINDING(SPEC_BVH_REGS, 6);         // four-wide traversal stack entries: 16, 24 or 32
STRATA_BINDING(SPEC_TRACE_MODE, 7);       // trace kernel: kTraceClosest, kTraceAny or kTraceSpawn
STRATA_BINDING(SPEC_WORK_QUEUE, 8);       // 1 (CPU devices): trace.comp's subgroups take rays from a counter,
                                          // pathtrace.comp shades a tile's 8x8 blocks in a permuted order
STRATA_BINDING(SPEC_WAVE_STAGE, 9);       // wavefront.comp: kStage* (types.h), one pipeline each
STRATA_BINDING(SPEC_ADAPTIVE, 10);        // 1: adaptive sampling; converged 8x8 blocks skipped (lib/film.glsl)
                                          // BINDING_ACTIVE_BLOCKS marks converged
STRATA_BINDING(SPEC_LIGHT_CANDIDATES, 11);  // with the light tree: descents a light sample resamples
                                            // (lib/lights.glsl; 1 otherwise)

#ifdef __cplusplus
}  // namespace strata::gpu
#endif
#undef STRATA_BINDING
#endif
