#include "pack/gpu_scene.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <type_traits>

#include "pack/env_tables.h"
#include "pack/instances.h"
#include "pack/light_tree.h"
#include "pack/textures.h"
#include "util/memory.h"

namespace strata {

// The loader's lower bound of a flattened triangle's device memory (scene.h).
static_assert(kDeviceBytesPerTriangle == sizeof(gpu::TriVerts) + sizeof(gpu::TriShading));
static_assert(kDeviceBytesPerEmitter == sizeof(gpu::Emitter));

std::vector<std::string> SceneFeatures::names() const {
    std::vector<std::string> out;
    if (emitters) out.push_back("lights");
    static const std::pair<std::uint32_t, const char*> kNames[] = {
        {gpu::kFeatureSpecular, "specular"},       {gpu::kFeatureTransmission, "transmission"},
        {gpu::kFeatureTextures, "textures"},       {gpu::kFeatureNormalMap, "normal-maps"},
        {gpu::kFeatureAlphaTest, "alpha-test"},    {gpu::kFeaturePunctual, "punctual-lights"},
        {gpu::kFeatureEnvironment, "environment"}, {gpu::kFeatureEnvMap, "environment-map"},
        {gpu::kFeatureUnlit, "unlit"},             {gpu::kFeatureVolume, "volume"},
        {gpu::kFeatureVertexColor, "vertex-colors"}, {gpu::kFeatureClearcoat, "clearcoat"},
        {gpu::kFeatureSheen, "sheen"},             {gpu::kFeatureSpecularColor, "specular-color"},
        {gpu::kFeatureInstancing, "instancing"},   {gpu::kFeatureIridescence, "iridescence"},
        {gpu::kFeatureLightTree, "light-tree"},
        {gpu::kFeatureInstancedEmitters, "moving-lights"}, {gpu::kFeatureTextureLod, "texture-lod"},
        {gpu::kFeatureDiffuseTransmission, "diffuse-transmission"}, {gpu::kFeatureAnisotropy, "anisotropy"},
        {gpu::kFeatureVolumeScatter, "volume-scatter"}, {gpu::kFeatureDispersion, "dispersion"}};
    for (const auto& [bit, name] : kNames) {
        if (bits & bit) out.push_back(name);
    }
    return out;
}

namespace {

// KHR_materials_volume's attenuation coefficient sigma = -ln(color) / distance
// per channel, for a material whose volume attenuates: thickness > 0 (not
// thin-walled), transmissive (KHR_materials_transmission or
// KHR_materials_diffuse_transmission), finite distance, a colour below 1.
// Zero otherwise. A channel of colour 0 absorbs everything (float max).
glm::vec3 volumeAttenuation(const MaterialDesc& m) {
    if (!m.hasVolume()) return glm::vec3(0.0f);
    glm::vec3 sigma;
    for (int k = 0; k < 3; ++k) {
        const double c = m.attenuationColor[k];
        sigma[k] = c > 0.0 ? static_cast<float>(-std::log(c) / double(m.attenuationDistance))
                           : std::numeric_limits<float>::max();
    }
    return sigma;
}

// KHR_materials_volume_scatter's single-scatter albedo from the
// multi-scatter albedo rho_ms, per channel (Kulla and Conty 2017, the
// draft's mapping): 1 - (4.09712 + 4.20863 rho_ms - sqrt(9.59217 +
// 41.6808 rho_ms + 17.7126 rho_ms^2))^2, clamped to [0, 1]. rho_ms 0 gives
// 0 (absorption only), rho_ms 1 gives 1 (no absorption).
glm::vec3 singleScatterAlbedo(glm::vec3 multiscatter) {
    glm::vec3 out;
    for (int k = 0; k < 3; ++k) {
        // At 0 the rounded constants leave 5.7e-6: absorption only is exact.
        const double a = multiscatter[k];
        const double r = 4.09712 + 4.20863 * a - std::sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
        out[k] = a > 0.0 ? static_cast<float>(std::clamp(1.0 - r * r, 0.0, 1.0)) : 0.0f;
    }
    return out;
}

// A scattering medium's boundary that light crosses without bending or
// reflecting, tinted by baseColorFactor alone (kMaterialIndexMatched): ior
// 1, transmission 1, metallic 0, smooth (alpha below the shader's delta
// threshold, 1e-3), opaque, no emission, no texture a crossing would read
// and no layer. Next-event estimation from inside the medium sees through
// it (lib/path.glsl).
bool indexMatched(const MaterialDesc& m) {
    return m.ior == 1.0f && m.transmission == 1.0f && m.metallic == 0.0f && m.roughness * m.roughness < 1.0e-3f &&
           m.alphaMode == MaterialDesc::AlphaMode::Opaque && m.emission() == glm::vec3(0.0f) &&
           !m.baseColorTexture.used() && !m.transmissionTexture.used() && !m.metallicRoughnessTexture.used() &&
           !m.emissiveTexture.used() && !m.coated() && !m.sheened() && !m.iridescent() &&
           !m.diffuselyTransmitting() && !m.anisotropic();
}

// The triangles' bounding sphere: radius (1 if none) and centre.
double sceneRadius(const Scene& scene, glm::dvec3& center) {
    center = glm::dvec3(0.0);
    if (scene.triangles.empty()) return 1.0;
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Triangle& t : scene.triangles)
        for (const glm::vec3& v : t.v) lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
    center = 0.5 * (lo + hi);
    const double r = 0.5 * glm::length(hi - lo);
    return r > 0.0 ? r : 1.0;
}

// Appends the punctual lights and the environment to g.emitters, their
// estimated powers to `weights` (packScene's comment lists them).
void packLights(const Scene& scene, GpuScene& g, std::vector<double>& weights) {
    const double pi = std::numbers::pi, r2 = g.sceneRadius * g.sceneRadius;
    for (const PunctualLight& l : scene.lights) {
        gpu::Emitter e{};
        e.radiance = l.intensityRgb();
        const double y = luminance(glm::dvec3(e.radiance));
        switch (l.type) {
            case PunctualLight::Type::Point:
                e.kind = gpu::kLightPoint;
                e.v0 = l.position;
                weights.push_back(4.0 * pi * y);
                break;
            case PunctualLight::Type::Spot: {
                e.kind = gpu::kLightSpot;
                e.v0 = l.position;
                e.e1 = l.direction;
                const double cosInner = std::cos(double(l.innerConeAngle)), cosOuter = std::cos(double(l.outerConeAngle));
                // KHR_lights_punctual's falloff: scale = 1 / max(0.001, cos inner - cos outer).
                const double scale = 1.0 / std::max(0.001, cosInner - cosOuter);
                e.e2 = glm::vec3(static_cast<float>(scale), static_cast<float>(-cosOuter * scale), 0.0f);
                weights.push_back(2.0 * pi * (1.0 - 0.5 * (cosInner + cosOuter)) * y);
                break;
            }
            case PunctualLight::Type::Directional:
                e.kind = gpu::kLightDirectional;
                e.e1 = l.direction;
                weights.push_back(pi * r2 * y);
                break;
        }
        g.emitters.push_back(e);
    }
    const Environment& env = scene.environment;
    if (!env.enabled) return;
    gpu::Emitter e{};
    e.kind = gpu::kLightEnvironment;
    g.environment = static_cast<std::uint32_t>(g.emitters.size());
    g.emitters.push_back(e);
    weights.push_back(pi * r2 * 4.0 * pi * envMeanLuminance(env));
    g.envScale = env.scale;
    g.envRotation = env.rotation;
    g.envWidth = static_cast<std::uint32_t>(env.width);
    g.envHeight = static_cast<std::uint32_t>(env.height);
    g.envTexels = envTexels(env);
    g.envTables = buildEnvTables(env);
    g.features.bits |= gpu::kFeatureEnvironment;
    if (env.width > 0) g.features.bits |= gpu::kFeatureEnvMap;
}

}  // namespace

void setLightUniforms(gpu::FrameUniforms& f, const GpuScene& g) {
    f.counts.x = static_cast<std::uint32_t>(g.emitters.size());
    f.envScale = glm::vec4(g.envScale, 0.0f);
    f.envRotation = glm::vec4(std::cos(g.envRotation), std::sin(g.envRotation), 0.0f, 0.0f);
    f.envInfo = glm::uvec4(g.environment, g.envWidth, g.envHeight, 0u);
    f.scene.y = static_cast<float>(g.lightTreeProb);
}

void buildAliasTable(const std::vector<double>& weights, std::vector<gpu::Emitter>& emitters) {
    const std::size_t n = weights.size();
    double total = 0.0;
    for (double w : weights) total += w;
    std::vector<double> scaled(n);
    std::vector<std::uint32_t> small, large;
    for (std::size_t i = 0; i < n; ++i) {
        emitters[i].pmf = static_cast<float>(weights[i] / total);
        scaled[i] = weights[i] / total * static_cast<double>(n);
        (scaled[i] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(i));
    }
    // Vose 1991: pair each under-full slot with an over-full one.
    while (!small.empty() && !large.empty()) {
        std::uint32_t s = small.back(), l = large.back();
        small.pop_back();
        emitters[s].aliasProb = static_cast<float>(scaled[s]);
        emitters[s].alias = l;
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    for (std::uint32_t i : large) emitters[i].aliasProb = 1.0f, emitters[i].alias = i;
    for (std::uint32_t i : small) emitters[i].aliasProb = 1.0f, emitters[i].alias = i;
}

namespace {

glm::dvec3 emissiveMean(const Scene& scene, const MaterialDesc& m) {
    const Texture& t = scene.textures[static_cast<std::size_t>(m.emissiveTexture.texture)];
    return meanColor(scene.images[static_cast<std::size_t>(t.image)], true);
}

// kFeatureTextures / kFeatureNormalMap / kFeatureAlphaTest / kFeatureAnisotropy for the used
// materials. Alpha testing is needed for MASK or BLEND unless the alpha is a
// constant that never makes a hole (no baseColor texture and factor >=
// alphaCutoff for MASK, factor >= 1 for BLEND).
std::uint32_t textureFeatures(const Scene& scene, const std::vector<bool>& used) {
    const bool colors = !scene.colors.empty();  // COLOR_0's alpha multiplies too
    std::uint32_t bits = 0;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const MaterialDesc& m = scene.materials[i];
        const bool coatTextures = m.coated() && (m.clearcoatTexture.used() || m.clearcoatRoughnessTexture.used() ||
                                                 m.clearcoatNormalTexture.used());
        const bool sheenTextures = m.sheened() && (m.sheenColorTexture.used() || m.sheenRoughnessTexture.used());
        const bool specularTextures = m.tinted() && (m.specularTexture.used() || m.specularColorTexture.used());
        const bool filmTextures =
            m.iridescent() && (m.iridescenceTexture.used() || m.iridescenceThicknessTexture.used());
        const bool diffuseTextures = m.diffuselyTransmitting() && (m.diffuseTransmissionTexture.used() ||
                                                                   m.diffuseTransmissionColorTexture.used());
        const bool anisotropyTexture = m.anisotropic() && m.anisotropyTexture.used();
        if (m.baseColorTexture.used() || m.metallicRoughnessTexture.used() || m.normalTexture.used() ||
            m.emissiveTexture.used() || m.transmissionTexture.used() || coatTextures || sheenTextures ||
            specularTextures || filmTextures || diffuseTextures || anisotropyTexture)
            bits |= gpu::kFeatureTextures;
        if (m.normalTexture.used() || (m.coated() && m.clearcoatNormalTexture.used()))
            bits |= gpu::kFeatureNormalMap;
        // Anisotropy reads the tangents as normal maps do; it stretches the specular lobes.
        if (m.anisotropic() && (m.metallic > 0.0f || m.specular > 0.0f)) bits |= gpu::kFeatureAnisotropy;
        const float alpha = m.baseColor.a;
        const bool textured = m.baseColorTexture.used() || colors;
        if ((m.alphaMode == MaterialDesc::AlphaMode::Mask && (textured || alpha < m.alphaCutoff)) ||
            (m.alphaMode == MaterialDesc::AlphaMode::Blend && (textured || alpha < 1.0f)))
            bits |= gpu::kFeatureAlphaTest;
    }
    return bits;
}

// Elements of a trivially copyable type in storage that nothing touches
// before it is written (no value-initialisation), so untouched pages cost no
// memory.
template <class T>
struct RawArray {
    static_assert(std::is_trivially_copyable_v<T>);
    std::unique_ptr<std::byte[]> bytes;
    explicit RawArray(std::size_t n = 0) : bytes(n > 0 ? new std::byte[n * sizeof(T)] : nullptr) {
        if (bytes) adviseHugePages(bytes.get(), n * sizeof(T));
    }
    bool empty() const { return !bytes; }
    void put(std::size_t i, const T& v) { std::memcpy(bytes.get() + i * sizeof(T), &v, sizeof(T)); }
    T get(std::size_t i) const {
        T v;
        std::memcpy(&v, bytes.get() + i * sizeof(T), sizeof(T));
        return v;
    }
    void discard(std::size_t begin, std::size_t end) {
        if (bytes) discardPages(bytes.get() + begin * sizeof(T), (end - begin) * sizeof(T));
    }
};

// A scene's triangles, texture coordinates and tangents made readable in BVH
// order without holding them twice: the constructor reads each source array
// front to back, handing back its pages as it goes, and drops every element
// into the chunk of kChunk BVH positions it belongs to (a bucket pass); the
// packing loop then reads chunk after chunk (random access within 19 MiB) and
// hands each chunk back once read: two streaming passes, not a walk along
// the permutation's cycles in place.
struct BvhOrderSource {
    static constexpr std::size_t kChunk = std::size_t(1) << 18;
    std::vector<std::uint32_t> slot;  // BVH position -> its index in the arrays below
    RawArray<Triangle> tris;
    RawArray<TriangleUv> uvs;
    RawArray<TriangleTangents> tangents;
    RawArray<TriangleColors> colors;

    BvhOrderSource(Scene& scene, const std::vector<std::uint32_t>& order)
        : slot(order.size()), tris(order.size()), uvs(scene.texcoords.empty() ? 0 : order.size()),
          tangents(scene.tangents.empty() ? 0 : order.size()), colors(scene.colors.empty() ? 0 : order.size()) {
        const std::size_t n = order.size();
        std::vector<std::uint32_t> position(n);  // source index -> BVH position
        for (std::size_t j = 0; j < n; ++j) position[order[j]] = std::uint32_t(j);
        std::vector<std::size_t> fill((n + kChunk - 1) / kChunk);
        for (std::size_t k = 0; k < fill.size(); ++k) fill[k] = k * kChunk;
        for (std::size_t i = 0; i < n; ++i) {
            if (i % kChunk == 0 && i > 0) {
                discardPages(scene.triangles.data() + (i - kChunk), kChunk * sizeof(Triangle));
                if (!uvs.empty()) discardPages(scene.texcoords.data() + (i - kChunk), kChunk * sizeof(TriangleUv));
                if (!tangents.empty()) discardPages(scene.tangents.data() + (i - kChunk), kChunk * sizeof(TriangleTangents));
                if (!colors.empty()) discardPages(scene.colors.data() + (i - kChunk), kChunk * sizeof(TriangleColors));
            }
            const std::uint32_t d = position[i];
            const std::size_t s = fill[d / kChunk]++;
            slot[d] = std::uint32_t(s);
            tris.put(s, scene.triangles[i]);
            if (!uvs.empty()) uvs.put(s, scene.texcoords[i]);
            if (!tangents.empty()) tangents.put(s, scene.tangents[i]);
            if (!colors.empty()) colors.put(s, scene.colors[i]);
        }
        std::vector<Triangle>().swap(scene.triangles);
        std::vector<TriangleUv>().swap(scene.texcoords);
        std::vector<TriangleTangents>().swap(scene.tangents);
        std::vector<TriangleColors>().swap(scene.colors);
    }
    // Called with i = 0, 1, 2, ...: chunk i / kChunk - 1 has been read.
    void advance(std::size_t i) {
        if (i % kChunk != 0 || i == 0) return;
        tris.discard(i - kChunk, i);
        uvs.discard(i - kChunk, i);
        tangents.discard(i - kChunk, i);
        colors.discard(i - kChunk, i);
    }
};

// S is Scene (its geometry consumed through a BvhOrderSource and released,
// so the host never holds it twice) or const Scene (gathered in BVH order,
// left as it was).
template <class S>
GpuScene pack(S& scene, SceneBvh&& sceneBvh, int bvhWidth, LightSampler lightSampler, TexturePacking textures) {
    constexpr bool consume = !std::is_const_v<S>;
    GpuScene g;
    g.source = scene.path;
    const std::size_t n = scene.triangles.size();
    g.triangleCount = n;
    Bvh& bvh = sceneBvh.binary;
    g.nodes = std::move(bvh.nodes);
    g.wide = std::move(sceneBvh.wide.nodes);
    g.wideDepth = sceneBvh.wide.maxDepth;
    g.wideSahCost = sceneBvh.wide.sahCost;
    g.wideBuildMs = sceneBvh.wide.buildMs;
    // The one place the traversed tree is chosen (GpuScene::bvhWidth).
    g.bvhWidth = bvhWidth == 4 && bvhRegsFor(g.wideDepth) > 0 && !g.wide.empty() ? 4 : 2;
    if (consume && g.bvhWidth == 4) std::vector<gpu::BvhNode>().swap(g.nodes);  // not traversed
    g.bvh = bvh.stats;

    for (const auto& m : scene.materials) {
        gpu::Material gm{};
        gm.baseColor = m.baseColor;
        gm.emission = m.emission();
        gm.metallic = m.metallic;
        gm.roughness = m.roughness;
        gm.ior = m.ior;
        gm.flags = m.doubleSided ? gpu::kMaterialDoubleSided : 0u;
        gm.alphaCutoff = m.alphaCutoff;
        gm.transmission = m.transmission;
        gm.specular = m.specular;
        gm.normalScale = 1.0f;
        gm.normalScale = m.normalScale;
        if (m.alphaMode == MaterialDesc::AlphaMode::Mask) gm.flags |= gpu::kMaterialAlphaMask;
        if (m.alphaMode == MaterialDesc::AlphaMode::Blend) gm.flags |= gpu::kMaterialAlphaBlend;
        if (m.unlit) gm.flags |= gpu::kMaterialUnlit;
        gm.attenuation = volumeAttenuation(m);
        gm.thickness = m.thickness;
        if (gm.attenuation != glm::vec3(0.0f)) gm.flags |= gpu::kMaterialVolume;
        gm.scatterAlbedo = singleScatterAlbedo(m.multiscatterColor);
        gm.scatterAnisotropy = m.scatterAnisotropy;
        if ((gm.flags & gpu::kMaterialVolume) != 0u && gm.scatterAlbedo != glm::vec3(0.0f))
            gm.flags |= gpu::kMaterialVolumeScatter | (indexMatched(m) ? gpu::kMaterialIndexMatched : 0u);
        else
            gm.scatterAlbedo = glm::vec3(0.0f), gm.scatterAnisotropy = 0.0f;
        if (m.coated()) {
            gm.flags |= gpu::kMaterialClearcoat;
            gm.clearcoat = m.clearcoat;
            gm.clearcoatRoughness = m.clearcoatRoughness;
            gm.clearcoatNormalScale = m.clearcoatNormalScale;
        }
        gm.specularColor = glm::vec3(1.0f);
        if (m.tinted()) {
            gm.flags |= gpu::kMaterialSpecularColor;
            gm.specularColor = m.specularColor;
        }
        if (m.iridescent()) {
            gm.flags |= gpu::kMaterialIridescence;
            gm.iridescence = m.iridescence;
            gm.iridescenceIor = m.iridescenceIor;
            gm.iridescenceThicknessMin = m.iridescenceThicknessMin;
            gm.iridescenceThicknessMax = m.iridescenceThicknessMax;
        }
        if (m.sheened()) {
            gm.flags |= gpu::kMaterialSheen;
            gm.sheenColor = m.sheenColor;
            gm.sheenRoughness = m.sheenRoughness;
        }
        if (m.diffuselyTransmitting()) {
            gm.flags |= gpu::kMaterialDiffuseTransmission;
            if (m.thickness == 0.0f) gm.flags |= gpu::kMaterialThinWalled;
            gm.diffuseTransmission = m.diffuseTransmission;
            gm.diffuseTransmissionColor = m.diffuseTransmissionColor;
        }
        if (m.anisotropic()) {
            gm.flags |= gpu::kMaterialAnisotropy;
            gm.anisotropyStrength = m.anisotropyStrength;
            gm.anisotropyRotation = m.anisotropyRotation;
        }
        // Dispersion spreads what refracts: a transmitting dielectric.
        if (m.dispersion > 0.0f && m.transmission > 0.0f && m.metallic < 1.0f && m.ior > 1.0f && !m.unlit) {
            gm.flags |= gpu::kMaterialDispersion;
            gm.dispersion = m.dispersion;
        }
        gm.baseColorTex = gm.metallicRoughnessTex = gm.normalTex = gm.emissiveTex = gm.transmissionTex =
            gm.clearcoatTex = gm.clearcoatRoughnessTex = gm.clearcoatNormalTex = gm.sheenColorTex =
                gm.sheenRoughnessTex = gm.specularColorTex = gm.specularTex = gm.iridescenceTex =
                    gm.iridescenceThicknessTex = gm.diffuseTransmissionTex = gm.diffuseTransmissionColorTex =
                        gm.anisotropyTex = gpu::kNoTexture;
        g.materials.push_back(gm);
    }
    std::vector<bool> used(g.materials.size(), false);
    for (const auto& t : scene.triangles) used[t.material] = true;
    g.sceneRadius = sceneRadius(scene, g.sceneCenter);  // before the triangles are consumed
    std::vector<PlacedRecord> records;  // per bottom level
    if (sceneBvh.instanced()) {
        packInstances(scene, sceneBvh, g, &records);
        const gpu::BvhNode& root = sceneBvh.top.nodes[0];  // every placement's world box
        const double r = 0.5 * glm::length(glm::dvec3(root.bmax) - glm::dvec3(root.bmin));
        g.sceneRadius = r > 0.0 ? r : 1.0;
        g.sceneCenter = 0.5 * (glm::dvec3(root.bmax) + glm::dvec3(root.bmin));
    } else {
        g.placedTriangles = n;
    }
    PackedTextures packed = packTextures(scene, used, g.materials, textures.maxSize, textures.mips);
    g.textureRefs = std::move(packed.refs);
    g.texels = std::move(packed.texels);
    g.images = std::move(packed.images);
    g.mipMs = packed.mipMs;
    for (const PackedImage& p : g.images)
        if (p.levels > 1) g.features.bits |= gpu::kFeatureTextureLod;
    g.features.bits |= textureFeatures(scene, used);
    const bool uvs = (g.features.bits & gpu::kFeatureTextures) != 0;
    const bool tangents = (g.features.bits & (gpu::kFeatureNormalMap | gpu::kFeatureAnisotropy)) != 0;
    const bool colors = !scene.colors.empty();
    if (colors) g.features.bits |= gpu::kFeatureVertexColor;

    std::optional<BvhOrderSource> reordered;
    if constexpr (consume) reordered.emplace(scene, bvh.triIndices);
    auto triangle = [&](std::size_t i) {
        if constexpr (consume) return reordered->tris.get(reordered->slot[i]);
        else return scene.triangles[bvh.triIndices[i]];
    };
    auto uvsOf = [&](std::size_t i) {
        if constexpr (consume) return reordered->uvs.get(reordered->slot[i]);
        else return scene.texcoords[bvh.triIndices[i]];
    };
    auto colorsOf = [&](std::size_t i) {
        if constexpr (consume) return reordered->colors.get(reordered->slot[i]);
        else return scene.colors[bvh.triIndices[i]];
    };
    auto tangentsOf = [&](std::size_t i) {
        if constexpr (consume) return reordered->tangents.get(reordered->slot[i]);
        else return scene.tangents[bvh.triIndices[i]];
    };
    const bool hasUvs = consume ? !reordered->uvs.empty() : !scene.texcoords.empty();
    const bool hasTangents = consume ? !reordered->tangents.empty() : !scene.tangents.empty();
    // Reserved, then appended: no page of the packed arrays is touched before
    // it is written (a zero-fill first would hold them whole next to the source).
    reserveHuge(g.tris, n);
    reserveHuge(g.shading, n);
    if (uvs) reserveHuge(g.texcoords, n);
    if (tangents) reserveHuge(g.tangents, n);
    if (colors) reserveHuge(g.colors, n);
    std::vector<double> weights;
    // The lights of moving meshes (SharedMesh::lights): their records and bounds over the shutter.
    const InstancedLights instancedLights(scene, sceneBvh, records);
    std::vector<SweptLight> swept;
    for (std::size_t i = 0; i < n; ++i) {
        if constexpr (consume) reordered->advance(i);
        const Triangle t = triangle(i);
        g.tris.push_back({glm::vec4(t.v[0], 0.0f), glm::vec4(t.v[1], 0.0f), glm::vec4(t.v[2], 0.0f)});
        gpu::TriShading& s = g.shading.emplace_back();
        s.n0 = t.n[0];
        s.n1 = t.n[1];
        s.n2 = t.n[2];
        s.material = t.material;
        s.light = gpu::kNoLight;
        if (uvs) {
            gpu::TriTexcoords& out = g.texcoords.emplace_back();
            if (hasUvs) {
                const TriangleUv uv = uvsOf(i);
                out = {uv[0], uv[1], uv[2]};
            }
        }
        if (tangents) {
            gpu::TriTangents& out = g.tangents.emplace_back();
            if (hasTangents) {
                const TriangleTangents tg = tangentsOf(i);
                out = {tg[0], tg[1], tg[2]};
            }
        }
        if (colors) {
            const TriangleColors c = colorsOf(i);
            g.colors.push_back({c[0], c[1], c[2]});
        }
        const MaterialDesc& m = scene.materials[t.material];
        if (isEmitter(scene, t)) {
            const glm::vec3 le = m.emission();
            // An emissive texture scales the power by its mean (whole image,
            // not the triangle's uv footprint: the pmf only steers sampling).
            const glm::dvec3 scaled =
                glm::dvec3(le) * (m.emissiveTexture.used() ? emissiveMean(scene, m) : glm::dvec3(1.0));
            const double lum = luminance(scaled);
            gpu::Emitter e{};
            const std::size_t placed = instancedLights.placementOf(bvh.triIndices[i]);
            const Triangle w = placed == SIZE_MAX ? t : instancedLights.atOpen(placed, t);
            e.v0 = w.v[0];
            e.e1 = w.v[1] - w.v[0];
            e.e2 = w.v[2] - w.v[0];
            e.triangle = static_cast<std::uint32_t>(i);
            e.area = triangleArea(w);
            e.radiance = le;
            e.flags = m.doubleSided ? gpu::kMaterialDoubleSided : 0u;
            if (placed != SIZE_MAX) swept.push_back(instancedLights.swept(placed, t, g.emitters.size()));
            const double sides = m.doubleSided ? 2.0 : 1.0;
            s.light = static_cast<std::uint32_t>(g.emitters.size());
            g.emitters.push_back(e);
            weights.push_back(lum * e.area * std::numbers::pi * sides);
        }
    }
    packLights(scene, g, weights);
    if (!scene.lights.empty()) g.features.bits |= gpu::kFeaturePunctual;
    for (double w : weights) g.totalPower += w;
    // Only black emissive textures: sample emitters by area instead.
    if (!weights.empty() && g.totalPower <= 0.0)
        for (std::size_t k = 0; k < weights.size(); ++k) weights[k] = g.emitters[k].area;
    if (!g.emitters.empty()) buildAliasTable(weights, g.emitters);
    g.features.emitters = !g.emitters.empty();
    std::size_t bounded = 0;
    double boundedPower = 0.0;
    for (std::size_t k = 0; k < g.emitters.size(); ++k)
        if (!isInfiniteLight(g.emitters[k])) ++bounded, boundedPower += weights[k];
    if (bounded > 0 && lightSampler != LightSampler::Power) {
        const auto t0 = std::chrono::steady_clock::now();
        LightTree tree = buildLightTree(g.emitters, weights, swept);
        g.lightTreeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        g.lightClusters = lightClusters(tree);
        if (useLightTree(lightSampler, g.lightClusters)) {
            g.lightTree = std::move(tree.nodes);
            g.lightTreeDepth = tree.depth;
            double total = 0.0;
            for (double w : weights) total += w;
            g.lightTreeProb = bounded == g.emitters.size() ? 1.0 : boundedPower / total;
            g.features.bits |= gpu::kFeatureLightTree;
        } else {
            for (gpu::Emitter& e : g.emitters) e.trail = 0;  // the emitters as without a tree
        }
    }
    // The lights of moving meshes as the shaders read them (kEmitterInstanced).
    for (const SweptLight& l : swept) {
        gpu::Emitter& e = g.emitters[l.emitter];
        const std::uint32_t record = records[instancedLights.bottomOf(bvh.triIndices[e.triangle])].texel;
        e.v0 = glm::vec3(std::bit_cast<float>(record), 0.0f, 0.0f);
        e.e1 = e.e2 = glm::vec3(0.0f);
        e.area = 0.0f;
        e.flags |= gpu::kEmitterInstanced;
    }
    if (!swept.empty()) g.features.bits |= gpu::kFeatureInstancedEmitters;
    // Features of the materials some triangle uses.
    for (std::size_t i = 0; i < g.materials.size(); ++i) {
        if (!used[i]) continue;
        const gpu::Material& m = g.materials[i];
        if ((m.flags & gpu::kMaterialUnlit) != 0u) {  // no lobes
            g.features.bits |= gpu::kFeatureUnlit;
            continue;
        }
        if (m.metallic > 0.0f || m.specular > 0.0f) g.features.bits |= gpu::kFeatureSpecular;
        if (m.transmission > 0.0f && m.metallic < 1.0f) g.features.bits |= gpu::kFeatureTransmission;
        if ((m.flags & gpu::kMaterialVolume) != 0u) g.features.bits |= gpu::kFeatureVolume;
        if ((m.flags & gpu::kMaterialVolumeScatter) != 0u) g.features.bits |= gpu::kFeatureVolumeScatter;
        if ((m.flags & gpu::kMaterialIndexMatched) != 0u) g.features.indexMatchedMedia = true;
        if ((m.flags & gpu::kMaterialDispersion) != 0u) g.features.bits |= gpu::kFeatureDispersion;
        if ((m.flags & gpu::kMaterialClearcoat) != 0u) g.features.bits |= gpu::kFeatureClearcoat;
        if ((m.flags & gpu::kMaterialSheen) != 0u) g.features.bits |= gpu::kFeatureSheen;
        if ((m.flags & gpu::kMaterialSpecularColor) != 0u) g.features.bits |= gpu::kFeatureSpecularColor;
        if ((m.flags & gpu::kMaterialIridescence) != 0u) g.features.bits |= gpu::kFeatureIridescence;
        if ((m.flags & gpu::kMaterialDiffuseTransmission) != 0u && m.metallic < 1.0f)
            g.features.bits |= gpu::kFeatureDiffuseTransmission;
    }
    if constexpr (consume) releaseGeometry(scene);
    return g;
}

}  // namespace

GpuScene packScene(const Scene& scene, SceneBvh bvh, int bvhWidth, LightSampler lights, TexturePacking textures) {
    return pack(scene, std::move(bvh), bvhWidth, lights, textures);
}

GpuScene packSceneAndRelease(Scene& scene, SceneBvh bvh, int bvhWidth, LightSampler lights,
                             TexturePacking textures) {
    return pack(scene, std::move(bvh), bvhWidth, lights, textures);
}

}  // namespace strata
