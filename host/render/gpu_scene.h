// Scene + BVH packed into the exact structs the shaders read
// (shaders/shared/types.h), ready to upload.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "scene/scene.h"

namespace strata {

// Scene features detected at pack time; each becomes a specialization
// constant so a scene that does not use a feature pays nothing for it.
struct SceneFeatures {
    bool emitters = false;  // any light: next-event estimation compiled in
    std::uint32_t bits = 0; // gpu::kFeature* (SPEC_FEATURES)
    std::vector<std::string> names() const;
};

struct GpuScene {
    std::string source;                     // Scene::path, for messages
    std::vector<gpu::BvhNode> nodes;
    std::vector<gpu::TriVerts> tris;        // BVH order
    std::vector<gpu::TriShading> shading;   // BVH order
    std::vector<gpu::Material> materials;
    std::vector<gpu::Emitter> emitters;     // with the alias table filled in
    // Filled only when features.bits has kFeatureTextures (texcoords,
    // textureRefs, texels) or kFeatureNormalMap (tangents); empty otherwise.
    std::vector<gpu::TriTexcoords> texcoords;  // BVH order
    std::vector<gpu::TriTangents> tangents;    // BVH order
    std::vector<gpu::TextureRef> textureRefs;
    std::vector<std::uint32_t> texels;         // R32UI words (types.h, TextureRef)
    double totalPower = 0.0;                // sum of luminance(Le) * area * pi * sides
    SceneFeatures features;
    BvhStats bvh;
    std::uint64_t bytes() const;
};

// Builds the BVH and packs everything. Emitters are the triangles for which
// isEmitter (scene.h) holds.
GpuScene packScene(const Scene& scene, const BvhBuildOptions& options = {});

// Walker/Vose alias table over `weights` (all >= 0, sum > 0): fills
// aliasProb/alias/pmf of `emitters` in place.
void buildAliasTable(const std::vector<double>& weights, std::vector<gpu::Emitter>& emitters);

}  // namespace strata
