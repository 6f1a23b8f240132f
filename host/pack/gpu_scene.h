// Scene + BVH packed into the exact structs the shaders read
// (shaders/shared/types.h), ready to upload.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bvh/scene_bvh.h"
#include "pack/light_tree.h"
#include "pack/textures.h"
#include "scene/scene.h"

namespace strata {

// Scene features detected at pack time; each becomes a specialization
// constant so a scene that does not use a feature pays nothing for it.
struct SceneFeatures {
    bool emitters = false;  // any light: next-event estimation compiled in
    std::uint32_t bits = 0; // gpu::kFeature* (SPEC_FEATURES)
    bool indexMatchedMedia = false;  // a kMaterialIndexMatched medium: the megakernel's shadow rays cross it
    std::vector<std::string> names() const;
};

struct GpuScene {
    std::string source;                     // Scene::path, for messages
    std::vector<gpu::BvhNode> nodes;        // BVH2 (CPU reference traversal; the bvh2 axis); dropped by
                                            // packSceneAndRelease where bvhWidth is 4
    std::vector<gpu::BvhNode4> wide;        // the same tree four-wide (bvh/wide.h)
    // The tree the shaders traverse, decided once, by packing (packScene's
    // bvhWidth): 4, `wide`, where it was asked for and its depth fits the
    // register stack (bvhRegsFor, kBvhMaxRegs); else 2, `nodes`. The upload
    // binds this tree and takes no width of its own.
    int bvhWidth = 2;
    std::uint32_t wideDepth = 0;            // WideBvh::maxDepth
    double wideSahCost = 0.0;               // WideBvh::sahCost
    double wideBuildMs = 0.0;               // WideBvh::buildMs
    std::uint64_t triangleCount = 0;        // triangles packed (stays when uploadAndRelease frees tris)
    std::vector<gpu::TriVerts> tris;        // BVH order
    std::vector<gpu::TriShading> shading;   // BVH order
    std::vector<gpu::Material> materials;
    // Filled only when features.bits has kFeatureTextures (texcoords,
    // textureRefs, texels) or kFeatureNormalMap or kFeatureAnisotropy
    // (tangents); empty otherwise.
    std::vector<gpu::TriTexcoords> texcoords;  // BVH order
    std::vector<gpu::TriTangents> tangents;    // BVH order
    std::vector<gpu::TriColors> colors;        // BVH order; only with kFeatureVertexColor
    std::vector<gpu::TextureRef> textureRefs;
    std::vector<std::uint32_t> texels;         // R32UI words (types.h, TextureRef)
    std::vector<PackedImage> images;           // what each packed image holds (--stats)
    double mipMs = 0.0;                        // building the mip chains (--texture-lod)
    std::vector<gpu::Emitter> emitters;     // triangles, then punctual lights, then the
                                            // environment; with the alias table filled in
    // With kFeatureLightTree: the light tree over the bounded emitters
    // (pack/light_tree.h; their Emitter::trail set) and the probability of
    // choosing through it rather than a directional or environment light.
    std::vector<gpu::LightNode> lightTree;
    double lightTreeProb = 0.0;
    std::uint32_t lightTreeDepth = 0;       // LightTree::depth
    std::size_t lightClusters = 0;          // of the tree built (lightClusters), kept or not
    double lightTreeMs = 0.0;               // its build's host time
    double totalPower = 0.0;                // sum of the emitters' estimated powers (packScene)
    double sceneRadius = 0.0;               // bounding sphere of the triangles' bounds (1 if none)
    glm::dvec3 sceneCenter{0.0};            // and its centre
    std::uint32_t environment = gpu::kNoLight;  // the environment's emitter index
    glm::vec3 envScale{0.0f};               // Environment::scale
    float envRotation = 0.0f;               // radians about +Y
    std::uint32_t envWidth = 0, envHeight = 0;  // 0 without a map
    std::vector<glm::vec4> envTexels;       // RGBA32F, row 0 at the top (pack/env_tables.h)
    std::vector<float> envTables;           // sampling tables (pack/env_tables.h)
    SceneFeatures features;
    BvhStats bvh;
    // Instancing (kFeatureInstancing; empty otherwise): the top level's BVH2
    // nodes, then one Instance record per placement in the top level's
    // order (shaders/shared/types.h), as RGBA32UI texels.
    std::vector<glm::uvec4> instances;
    std::uint64_t placementCount = 0;    // records (the world's triangles count as one)
    std::uint64_t sharedMeshCount = 0;   // bottom levels placed by instances
    std::uint64_t placedTriangles = 0;   // triangles the placements show (flattened, the scene would store these)
    BvhStats top;                        // the top level's build
};

// Lays the scene out in the order of its BVH (bvh/scene_bvh.h) and packs
// everything. Emitters are the triangles for which
// isEmitter (scene.h) holds, the punctual lights and the environment. The
// alias table's weights are estimated powers (any positive choice is
// unbiased; these make the choice roughly proportional to contribution),
// with Y = Rec. 709 luminance and R = sceneRadius:
//   triangle     Y(Le) * area * pi * sides
//   point        4 pi Y(I)
//   spot         2 pi (1 - (cos inner + cos outer) / 2) Y(I)
//   directional  pi R^2 Y(E)
//   environment  pi R^2 * 4 pi * (solid-angle mean of Y(L))   (as pbrt-v4)
// `bvhWidth` (2 or 4: --bvh) decides GpuScene::bvhWidth, the tree the
// shaders will traverse; both trees are kept. `lights` (--light-sampler)
// decides whether the light tree is built (pack/light_tree.h; the alias
// table is built either way).
// `textures`: --texture-max-size (halving each texture until neither side
// exceeds it, downsampledTexture in pack/textures.h) and --texture-lod
// (mip chains, kFeatureTextureLod).
struct TexturePacking {
    std::uint32_t maxSize = 0;  // 0: every texture whole
    bool mips = false;
};
GpuScene packScene(const Scene& scene, SceneBvh bvh, int bvhWidth = 4, LightSampler lights = LightSampler::Auto,
                   TexturePacking textures = {});

// The same, consuming the scene's geometry (releaseGeometry(scene) done):
// each page of the triangles is handed back as soon as it has been read, so
// packing a large scene needs little more memory than the packed arrays.
// Where the four-wide tree will be traversed (GpuScene::bvhWidth 4) it also
// drops `nodes`, the BVH2, once that tree is built.
GpuScene packSceneAndRelease(Scene& scene, SceneBvh bvh, int bvhWidth = 4,
                             LightSampler lights = LightSampler::Auto, TexturePacking textures = {});

// The instances array alone (GpuScene::instances) of a scene posed again
// (--frames): `bvh` holds the bottom levels' roots and the new top level.
std::vector<glm::uvec4> packInstanceArray(const Scene& scene, const SceneBvh& bvh);

// Fills FrameUniforms.counts.x and the env* members from the packed scene.
void setLightUniforms(gpu::FrameUniforms& frame, const GpuScene& scene);

// Walker/Vose alias table over `weights` (all >= 0, sum > 0): fills
// aliasProb/alias/pmf of `emitters` in place.
void buildAliasTable(const std::vector<double>& weights, std::vector<gpu::Emitter>& emitters);

}  // namespace strata
