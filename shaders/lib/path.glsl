// What the two path tracers (pathtrace.comp, the megakernel, and
// wavefront.comp's stages) share along a path: the sampler's dimensions per
// vertex and the shading of a path's vertex (emission found, the next-event
// shadow ray, the BSDF-sampled next ray); the traversals are the callers',
// the camera ray and the film lib/film.glsl's. Needs kHasEmitters
// (SPEC_HAS_EMITTERS) and kMis (SPEC_MIS) declared by the includer, after
// lib/scene.glsl, lib/film.glsl, lib/lights.glsl and lib/bsdf.glsl.
#ifndef STRATA_LIB_PATH_GLSL
#define STRATA_LIB_PATH_GLSL

// A colour that joins the path's throughput or radiance: its value at the
// path's wavelength under the dispersion axis (lib/spectrum.glsl), itself
// otherwise.
#ifdef STRATA_DISPERSION
#include "lib/spectrum.glsl"
#define PATH_SPECTRAL(c) pathSpectral(c)
#else
#define PATH_SPECTRAL(c) (c)
#endif

#ifdef STRATA_VOLUME_SCATTER
#include "lib/medium.glsl"
// The megakernel (STRATA_MEDIUM_SHADOWS) traces a medium's shadow rays
// through its index-matched boundary (pathMediumShadow); the wavefront
// integrator's shadow rays stop there, as at any surface.
#ifdef STRATA_MEDIUM_SHADOWS
#define PATH_MEDIUM_SHADOWS
#endif
#endif

// Dimensions: 0-1 pixel position; then kDimsPerVertex per path vertex, in
// 2D pairs: light choice and point, BSDF lobe (1D in a pair; the light
// tree's choice takes the pair's second), BSDF direction, roulette (1D in a
// pair; a medium's free flight to this vertex takes the pair's second).
const uint kDimsPerVertex = 8u;
const float kRayMax = 3.0e38;
// A shadow ray towards a point on an emitter ends this fraction of the way
// there. The end point is moved off the emitter by the rounding error of its
// coordinates (spawnOriginOnEmitter), but the hit distance the triangle test
// computes for the emitter itself has an error relative to the ray's length;
// where the emitter's coordinates are 0 along its normal (a lamp in the plane
// y = 0) the first is 0 and the shadow ray would find the emitter it aims at.
// 1 - 2^-16: an occluder closer to the emitter than 1.5e-5 of the ray's
// length is not seen (pbrt-v4's ShadowEpsilon is 1e-4).
const float kShadowEnd = 1.0 - 1.52587890625e-5;

// Lambert only: no material of the scene has a specular, transmission, coat,
// sheen or diffuse transmission lobe.
const bool kLambertOnly = (kFeatures & (kFeatureSpecular | kFeatureTransmission | kFeatureClearcoat |
                                        kFeatureSheen | kFeatureDiffuseTransmission)) == 0u;

// MIS weight of a light found by BSDF sampling with density bsdfPdf, which
// light sampling finds with density lightPdf.
float misWeightBsdf(bool prevDelta, float bsdfPdf, float lightPdf) {
    if (prevDelta || kMis == kMisBsdf) return 1.0;
    if (kMis == kMisLight) return 0.0;
    return powerHeuristic(bsdfPdf, lightPdf);
}

// A path between two vertices: its throughput, the radiance it has
// gathered, and how its last direction was sampled (for the MIS weight of
// the emission that direction finds).
struct PathVertex {
    vec3 beta;
    vec3 L;
    float prevBsdfPdf;
    bool prevDelta;  // the camera ray or a delta lobe: emission found gets weight 1
#ifdef STRATA_LIGHT_TREE
    vec3 prevP;      // the last vertex's point and the normal the light tree
    vec3 prevN;      // was asked with (lightPdfTriangle)
#endif
#ifdef PATH_MEDIUM_SHADOWS
    float travelled; // the distance along the last direction before this segment (index-matched crossings)
#endif
};

#if defined(STRATA_LIGHT_TREE) && defined(PATH_MEDIUM_SHADOWS)
PathVertex pathStart() { return PathVertex(vec3(1.0), vec3(0.0), 0.0, true, vec3(0.0), vec3(0.0), 0.0); }
#elif defined(STRATA_LIGHT_TREE)
PathVertex pathStart() { return PathVertex(vec3(1.0), vec3(0.0), 0.0, true, vec3(0.0), vec3(0.0)); }
#elif defined(PATH_MEDIUM_SHADOWS)
PathVertex pathStart() { return PathVertex(vec3(1.0), vec3(0.0), 0.0, true, 0.0); }
#else
PathVertex pathStart() { return PathVertex(vec3(1.0), vec3(0.0), 0.0, true); }
#endif

#ifdef STRATA_TEXTURE_LOD
// The path's ray cone (texture LOD, lib/material.glsl texLodAt): its width
// at the last vertex and its spread angle; tracePath starts it at the camera.
float gConeWidth = 0.0;
float gConeSpread = 0.0;

// A pinhole camera's cone starts with no width and the angle of the pixel
// filter's diameter (frame.scene.z pixels: 1 for the box filter of radius 0.5).
float cameraConeSpread() { return 2.0 * length(frame.camUp.xyz) / float(frame.image.y) * frame.scene.z; }
#endif

// Russian roulette after depth 4 with number u: the path goes on with
// probability p = min(1, cbrt(max(beta))) and a survivor's beta is divided
// by p. The cube root ends dim paths later than p = max(beta) (pbrt-v4's
// rule) or Cycles' sqrt: survivors' weights jump less, and the error they
// added outweighed the time longer paths take (1.04-1.37x the efficiency
// on four scenes: docs/experiments/integrators.md, Russian roulette).
// Starting after depth 4 rather than 3 cut the error at equal spp by
// 7-12% for 9-12% more time: even in efficiency (0.98-1.02x on three
// scenes, the same section). A weight never grows past 1 here (beta / p
// = beta^(2/3)); the floor of 5% that strata had before 2026-12-07 ended
// lossless paths too, and their survivors' weights grew as 1/0.95 a
// bounce, which made the glass furnace heavy-tailed. Lossless paths end at
// maxDepth.
bool pathSurvives(inout PathVertex v, float u, uint depth) {
    if (depth < 4u) return true;
    float p = min(1.0, pow(max(v.beta.r, max(v.beta.g, v.beta.b)), 1.0 / 3.0));
    if (u < 1.0 - p) return false;
    v.beta /= p;
    return true;
}

// What shading a hit asks for next.
struct PathNext {
    bool shadowTried;  // a light sample the BSDF passes (SPEC_COUNT_RAYS counts a shadow ray)
    bool shadowOpen;   // ... with a segment to test: L += contrib if `shadow` is unoccluded
    TraceRay shadow;
    vec3 contrib;
    bool alive;        // the path goes on along `next`
    TraceRay next;
#ifdef PATH_MEDIUM_SHADOWS
    bool shadowMedium;  // `shadow` starts in a medium of attenuation shadowSigma (pathMediumShadow)
    vec3 shadowSigma;
#endif
};

// The ray along `dir` escaped: the environment, weighted against light sampling.
void pathEscaped(inout PathVertex v, vec3 dir) {
    if (kHasEmitters != 0u && hasFeature(kFeatureEnvironment)) {
        float w = misWeightBsdf(v.prevDelta, v.prevBsdfPdf, v.prevDelta ? 0.0 : lightPdfEnvironment(dir));
        v.L += v.beta * w * PATH_SPECTRAL(environmentRadiance(dir));
    }
#ifdef STRATA_AOV
    if (!gAov.done) { AOV_RECORD(vec3(1.0), vec3(0.0), 1.0); }
#endif
}

#ifdef STRATA_VOLUME_SCATTER
// A scattering event at `p` inside a medium of material `mat` (lib/
// medium.glsl), the path's vertex `depth`: below maxDepth, next-event
// estimation weighed by the phase function and the medium's transmittance
// along the shadow ray (its boundary occludes it as any surface does,
// unless it is index-matched and this is the megakernel: pathMediumShadow)
// and the next direction drawn from the phase function (weight 1). The
// dimensions are the surface vertex's: light pair, the tree's number,
// direction pair, roulette.
PathNext pathShadeMedium(inout PathVertex v, inout Sampler smp, vec3 dir, vec3 p, Material mat, uint depth) {
    const uint maxDepth = frame.image.z;
    PathNext o;
    o.shadowTried = false;
    o.shadowOpen = false;
    o.alive = false;
#ifdef PATH_MEDIUM_SHADOWS
    o.shadowMedium = false;
    v.travelled = 0.0;
#endif
#ifdef STRATA_AOV
    if (!gAov.done) { AOV_RECORD(mat.scatterAlbedo, -dir, 0.0); }
#endif
    if (depth >= maxDepth) return o;
#ifdef STRATA_TEXTURE_LOD
    gTexLod = vec2(kNoLod);  // lights' emission at their first level
#endif
    vec3 wo = -dir;
    float g = mat.scatterAnisotropy;
    samplerSetDim(smp, 2u + depth * kDimsPerVertex);
    if (kHasEmitters != 0u && kMis != kMisBsdf) {
#ifdef STRATA_LIGHT_TREE
        samplerSetDim(smp, 2u + depth * kDimsPerVertex + 2u);
        float uTree = sample2D(smp).y;
        samplerSetDim(smp, 2u + depth * kDimsPerVertex);
        LightSample ls = sampleLight(p, vec3(0.0), sample2D(smp), uTree);
#else
        LightSample ls = sampleLight(p, sample2D(smp));
#endif
#ifdef PATH_MEDIUM_SHADOWS
        // pathMediumShadow takes the transmittance to the boundary, and the
        // shadow ray on through it when it is index-matched.
        if (ls.pdf > 0.0 && any(greaterThan(ls.Li, vec3(0.0)))) {
            float phase = phaseHG(dot(wo, ls.wi), g);
            o.shadowTried = true;
            o.shadowOpen = true;
            o.shadow = TraceRay(p, 0.0, ls.wi, kRayMax);
            if (ls.dist < kLightFar) {
                vec3 seg = ls.target - p;
                float segLen = length(seg);
                o.shadowOpen = segLen > 0.0;
                o.shadow = TraceRay(p, 0.0, o.shadowOpen ? seg / segLen : ls.wi, segLen * kShadowEnd);
            }
            o.shadowMedium = true;
            o.shadowSigma = mat.attenuation;
            float w = ls.isDelta || kMis == kMisLight ? 1.0 : powerHeuristic(ls.pdf, phase);
#ifdef STRATA_LIGHT_TREE
            o.contrib = v.beta * phase * PATH_SPECTRAL(ls.Li) * (w / ls.pdf * ls.scale);
#else
            o.contrib = v.beta * phase * PATH_SPECTRAL(ls.Li) * (w / ls.pdf);
#endif
        }
#else
        // A light at infinity is behind the medium's boundary.
        if (ls.pdf > 0.0 && ls.dist < kLightFar && any(greaterThan(ls.Li, vec3(0.0)))) {
            vec3 seg = ls.target - p;
            float segLen = length(seg);
            float phase = phaseHG(dot(wo, ls.wi), g);
            o.shadowTried = true;
            o.shadowOpen = segLen > 0.0;
            o.shadow = TraceRay(p, 0.0, o.shadowOpen ? seg / segLen : ls.wi, segLen * kShadowEnd);
            float w = ls.isDelta || kMis == kMisLight ? 1.0 : powerHeuristic(ls.pdf, phase);
            o.contrib = v.beta * exp(-mat.attenuation * segLen) * phase * PATH_SPECTRAL(ls.Li) * (w / ls.pdf);
        }
#endif
    }
    samplerSetDim(smp, 2u + depth * kDimsPerVertex + 4u);
    float pdf;
    vec3 wi = samplePhaseHG(dir, g, sample2D(smp), pdf);
    v.prevBsdfPdf = pdf;
    v.prevDelta = false;
#ifdef STRATA_TEXTURE_LOD
    gConeSpread += 2.0;  // as a lobe of alpha 1
#endif
#ifdef STRATA_LIGHT_TREE
    v.prevP = p;
    v.prevN = vec3(0.0);
#endif
    o.alive = pathSurvives(v, sample1D(smp), depth);
    if (o.alive) o.next = TraceRay(p, 0.0, wi, kRayMax);
    return o;
}
#endif

// The ray along `dir` hit `hit` at bounce `depth` (maxDepth counts
// scattering events, pbrt's convention): the emission found there, then,
// below maxDepth, next-event estimation's shadow ray (one light sample) and
// the BSDF-sampled next ray, with Russian roulette after depth 4. `smp` is
// the path's sampler; its dimensions are set here.
PathNext pathShadeHit(inout PathVertex v, inout Sampler smp, vec3 dir, TraceHit hit, uint depth) {
    const uint maxDepth = frame.image.z;
    const bool lightSampling = kHasEmitters != 0u && kMis != kMisBsdf;
    PathNext o;
    o.shadowTried = false;
    o.shadowOpen = false;
    o.alive = false;
#ifdef PATH_MEDIUM_SHADOWS
    o.shadowMedium = false;
#endif

    // An instance's triangle is shaded in world space (lib/scene.glsl, shadeTri).
#ifdef STRATA_INSTANCING
    gInstance = gHitInstance;
    vec3 spawnErr = shadeSpawnError(bvhFetchTri(hit.triangle));
#define PATH_SPAWN(side) spawnOrigin(tv, hit.u, hit.v, side, spawnErr)
#define PATH_INSTANCE gInstance
#else
#define PATH_SPAWN(side) spawnOrigin(tv, hit.u, hit.v, side)
#define PATH_INSTANCE kNoInstance
#endif
    TriVerts tv = shadeTri(hit.triangle);
    vec3 e1 = tv.v1.xyz - tv.v0.xyz, e2 = tv.v2.xyz - tv.v0.xyz;
    vec3 ng = normalize(cross(e1, e2));
    bool front = dot(dir, ng) < 0.0;
    TriShading sh = shadeShading(hit.triangle);
    Material mat = sceneMaterial(sh.material);
#ifdef STRATA_TEXTURE_LOD
    // The ray cone reaches the hit; its footprint sets the texture levels
    // until the surface point is read.
    gConeWidth += gConeSpread * hit.t;
    texLodAt(hit.triangle, e1, e2, gConeWidth, hit.t, vec2(hit.u, hit.v), smp.sampleIndex);
#endif
#ifdef STRATA_AOV
    if (depth == 0u) gAov.depth = hit.t;
#endif

#ifdef STRATA_VOLUME_SCATTER
    // KHR_materials_volume_scatter: the ray travelled hit.t inside the
    // medium; a free flight (its number the roulette pair's second) either
    // scatters before the hit or reaches it.
    if (hasFeature(kFeatureVolumeScatter) && !front && (mat.flags & kMaterialVolumeScatter) != 0u) {
        samplerSetDim(smp, 2u + depth * kDimsPerVertex + 6u);
        float tFlight;
        vec3 w = mediumFreeFlight(mat.attenuation, mat.scatterAlbedo, v.beta, hit.t, sample2D(smp).y, tFlight);
        v.beta *= w;
        if (tFlight < hit.t) {
#ifdef STRATA_TEXTURE_LOD
            gConeWidth -= gConeSpread * (hit.t - tFlight);
#endif
#ifdef STRATA_AOV
            if (depth == 0u) gAov.depth = tFlight;
#endif
            vec3 p = tv.v0.xyz + hit.u * e1 + hit.v * e2 + (tFlight - hit.t) * dir;
            return pathShadeMedium(v, smp, dir, p, mat, depth);
        }
#ifdef PATH_MEDIUM_SHADOWS
        // Out through an index-matched boundary: straight on, tinted, a
        // bounce for maxDepth; the last scattering vertex keeps its MIS
        // state, as its shadow rays see through the boundary too.
        if ((mat.flags & kMaterialIndexMatched) != 0u) {
            if (depth >= maxDepth) return o;
            v.beta *= clamp(mat.baseColor.rgb, 0.0, 1.0);
#ifdef STRATA_AOV
            if (!gAov.done) gAov.tint *= clamp(mat.baseColor.rgb, 0.0, 1.0);
#endif
            v.travelled += hit.t;
            o.alive = true;
            o.next = TraceRay(PATH_SPAWN(ng), 0.0, dir, kRayMax);
            return o;
        }
#endif
    } else
#endif
    // KHR_materials_volume: a ray that reaches a back face of a volume has
    // travelled hit.t inside it (volumes closed and not nested): Beer-Lambert.
    if (hasFeature(kFeatureVolume) && !front && (mat.flags & kMaterialVolume) != 0u)
        v.beta *= exp(-mat.attenuation * hit.t);

    // Emission found by the previous vertex's BSDF sample (or directly).
    if (kHasEmitters != 0u && sh.light != kNoLight) {
        if (front || (mat.flags & kMaterialDoubleSided) != 0u) {
#ifdef PATH_MEDIUM_SHADOWS
            float dist = hit.t + v.travelled;  // from the vertex before index-matched crossings
#else
            float dist = hit.t;
#endif
#ifdef STRATA_LIGHT_TREE
            float lightPdf = v.prevDelta ? 0.0 : lightPdfTriangle(sh.light, dist, abs(dot(dir, ng)), v.prevP, v.prevN);
#else
            // The ray's origin: the previous vertex moved off its surface by
            // its rounding error, where the light sample was taken from.
            vec3 from = tv.v0.xyz + hit.u * e1 + hit.v * e2 - dist * dir;
            float lightPdf = v.prevDelta ? 0.0 : lightPdfTriangle(sh.light, dist, abs(dot(dir, ng)), from);
#endif
            float w = misWeightBsdf(v.prevDelta, v.prevBsdfPdf, lightPdf);
            vec2 bary = vec2(hit.u, hit.v);
            vec3 le = emissionAt(sh.material, hit.triangle, bary);
            v.L += v.beta * w * PATH_SPECTRAL(coatedEmission(sh.material, hit.triangle, bary, le, -dir, PATH_INSTANCE));
#ifdef STRATA_AOV
            if (!gAov.done) { AOV_RECORD(vec3(1.0), front ? ng : -ng, 1.0); }
#endif
        }
    }
    // KHR_materials_unlit: the surface's colour, seen from either side, and no scattering.
    if (hasFeature(kFeatureUnlit) && (mat.flags & kMaterialUnlit) != 0u) {
        v.L += v.beta * PATH_SPECTRAL(unlitColor(mat, hit.triangle, vec2(hit.u, hit.v)));
#ifdef STRATA_AOV
        if (!gAov.done) { AOV_RECORD(unlitColor(mat, hit.triangle, vec2(hit.u, hit.v)), front ? ng : -ng, 1.0); }
#endif
        return o;
    }
    if (depth < maxDepth) {

        vec3 n = front ? ng : -ng;  // geometric normal on the incoming side
        vec3 wo = -dir;
        vec3 ns = normalize((1.0 - hit.u - hit.v) * sh.n0 + hit.u * sh.n1 + hit.v * sh.n2);
        if (dot(ns, n) < 0.0) ns = -ns;
        SurfacePoint sp = surfacePoint(mat, hit.triangle, vec2(hit.u, hit.v), n, ns);
#ifdef STRATA_ANISOTROPY
        float anisotropy = 0.0;
        vec3 anisotropyDir = vec3(0.0);
        if (hasFeature(kFeatureAnisotropy) && (mat.flags & kMaterialAnisotropy) != 0u)
            anisotropy = anisotropyAt(mat, hit.triangle, vec2(hit.u, hit.v), n, ns, anisotropyDir);
#endif
#ifdef STRATA_TEXTURE_LOD
        gTexLod = vec2(kNoLod);  // lights' emission at their first level
#endif
        ns = sp.ns;
        if (dot(ns, wo) <= 0.0) ns = n;  // the viewer is behind the shading normal
        vec3 t, b;
        basis(ns, t, b);
#ifdef STRATA_ANISOTROPY
        // The shading frame's x along the anisotropy's direction.
        vec3 along = anisotropyDir - ns * dot(anisotropyDir, ns);
        if (anisotropy > 0.0 && dot(along, along) > 1.0e-12) {
            t = normalize(along);
            b = cross(ns, t);
        }
#endif
        vec3 woL = vec3(dot(wo, t), dot(wo, b), dot(wo, ns));
        Bsdf bsdf;
        if (kLambertOnly) {
            bsdf = makeLambert(sp.baseColor);
        } else {
            BsdfLayers layers = noLayers();
#ifdef STRATA_LAYERS
            if (hasFeature(kFeatureClearcoat)) {
                layers.coat = sp.clearcoat;
                layers.coatRoughness = sp.clearcoatRoughness;
                layers.coatNormal = vec3(dot(sp.coatNormal, t), dot(sp.coatNormal, b), dot(sp.coatNormal, ns));
            }
            if (hasFeature(kFeatureSheen)) {
                layers.sheenColor = sp.sheenColor;
                layers.sheenRoughness = sp.sheenRoughness;
            }
            if (hasFeature(kFeatureSpecularColor)) layers.specularColor = sp.specularColor;
#ifdef STRATA_IRIDESCENCE
            if (hasFeature(kFeatureIridescence)) {
                layers.iridescence = sp.iridescence;
                layers.iridescenceIor = sp.iridescenceIor;
                layers.iridescenceThickness = sp.iridescenceThickness;
            }
#endif
#endif
            bool entering = front;
#ifdef STRATA_ANISOTROPY
            layers.anisotropy = anisotropy;
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
            if (hasFeature(kFeatureDiffuseTransmission)) {
                layers.diffuseTransmission = sp.diffuseTransmission;
                layers.diffuseTransmissionColor = sp.diffuseTransmissionColor;
                // A thin-walled surface: its back face sees the outside too.
                if ((mat.flags & kMaterialThinWalled) != 0u) entering = true;
            }
#endif
#ifdef STRATA_DISPERSION
            // KHR_materials_dispersion: the path draws its wavelength at the
            // first dispersive surface it reaches (its throughput weighed by
            // the draw, lib/spectrum.glsl) and refracts with that
            // wavelength's index here and at every dispersive surface after.
            if (hasFeature(kFeatureDispersion) && (mat.flags & kMaterialDispersion) != 0u) {
                if (gWavelength == 0.0) {
                    samplerSetDim(smp, kDimWavelength);
                    float lambda = sampleVisibleWavelength(sample1D(smp));
                    v.beta *= wavelengthRgb(lambda) / visibleWavelengthPdf(lambda);
                    gWavelength = lambda;
                }
                sp.ior = dispersiveIor(sp.ior, mat.dispersion, gWavelength);
            }
#endif
            bsdf = makeBsdf(sp.baseColor, sp.metallic, sp.roughness, sp.transmission, sp.ior,
                            sp.specular, layers, entering, woL);
        }
        // The AOVs' vertex: the first whose lobes are not all deltas (a
        // smooth metal or a smooth fully transmitting dielectric is followed).
#ifdef STRATA_AOV
        bool aovFollow = false;
        if (!gAov.done) {
            aovFollow = !kLambertOnly && bsdf.delta && (sp.metallic >= 1.0 || sp.transmission >= 1.0);
            if (!aovFollow) { AOV_RECORD(sp.baseColor, ns, 0.0); }
        }
#endif
        vec3 p = tv.v0.xyz + hit.u * e1 + hit.v * e2;
        samplerSetDim(smp, 2u + depth * kDimsPerVertex);

        // Next-event estimation: one light sample, one shadow ray.
        if (lightSampling) {
#ifdef STRATA_LIGHT_TREE
            // The tree's number is the lobe pair's second, which BSDF sampling leaves unused.
            samplerSetDim(smp, 2u + depth * kDimsPerVertex + 2u);
            float uTree = sample2D(smp).y;
            samplerSetDim(smp, 2u + depth * kDimsPerVertex);
            LightSample ls = sampleLight(p, ns, sample2D(smp), uTree);
#else
            LightSample ls = sampleLight(p, sample2D(smp));
#endif
            vec3 wiL = vec3(dot(ls.wi, t), dot(ls.wi, b), dot(ls.wi, ns));
            float geoSide = dot(n, ls.wi);
            // The shading and geometric normals must agree on the side wi leaves to.
            if (ls.pdf > 0.0 && any(greaterThan(ls.Li, vec3(0.0))) && geoSide != 0.0 &&
                (geoSide > 0.0) == (wiL.z > 0.0)) {
                float bsdfPdf;
                vec3 f = evalBsdf(bsdf, woL, wiL, bsdfPdf);
                if (any(greaterThan(f, vec3(0.0)))) {
                    vec3 from = PATH_SPAWN(geoSide > 0.0 ? n : -n);
                    o.shadowTried = true;
                    vec3 shadowDir = ls.wi;
                    float shadowMax = kRayMax;
                    bool open = true;
                    if (ls.dist < kLightFar) {
                        vec3 seg = ls.target - from;
                        float segLen = length(seg);
                        open = segLen > 0.0;
                        shadowDir = open ? seg / segLen : ls.wi;
                        shadowMax = segLen * kShadowEnd;
                    }
                    o.shadowOpen = open;
                    o.shadow = TraceRay(from, 0.0, shadowDir, shadowMax);
                    float w = ls.isDelta || kMis == kMisLight ? 1.0 : powerHeuristic(ls.pdf, bsdfPdf);
#ifdef STRATA_LIGHT_TREE
                    o.contrib = v.beta * PATH_SPECTRAL(f) * PATH_SPECTRAL(ls.Li) * (w / ls.pdf * ls.scale);
#else
                    o.contrib = v.beta * PATH_SPECTRAL(f) * PATH_SPECTRAL(ls.Li) * (w / ls.pdf);
#endif
                }
            }
        }

        // BSDF sampling: lobe choice, direction, then Russian roulette.
        samplerSetDim(smp, 2u + depth * kDimsPerVertex + 2u);
        float uLobe = sample1D(smp);
        BsdfSample bs = sampleBsdf(bsdf, woL, uLobe, sample2D(smp));
        vec3 wi = bs.wi.x * t + bs.wi.y * b + bs.wi.z * ns;
        float geoSide = dot(n, wi);
        if (bs.valid && !(geoSide == 0.0 || (geoSide > 0.0) != (bs.wi.z > 0.0))) {
            v.beta *= PATH_SPECTRAL(bs.weight);
#ifdef STRATA_AOV
            if (aovFollow) gAov.tint *= bs.weight;
#endif
            v.prevBsdfPdf = bs.pdf;
            v.prevDelta = bs.delta;
#ifdef PATH_MEDIUM_SHADOWS
            v.travelled = 0.0;
#endif
#ifdef STRATA_TEXTURE_LOD
            // A rough lobe widens the cone by twice its GGX alpha; a
            // reflection off a curved surface turns it by twice the normal's
            // turn across its width (convex widens, concave narrows).
            if (!bs.delta) gConeSpread += 2.0 * sp.roughness * sp.roughness;
            if (bs.wi.z > 0.0) gConeSpread += 2.0 * triCurvature(tv, sh, n) * gConeWidth;
#endif
#ifdef STRATA_LIGHT_TREE
            v.prevP = p;
            v.prevN = ns;
#endif

            o.alive = pathSurvives(v, sample1D(smp), depth);
            if (o.alive) o.next = TraceRay(PATH_SPAWN(geoSide > 0.0 ? n : -n), 0.0, wi, kRayMax);
        }
    }
    return o;
}
#undef PATH_SPAWN
#undef PATH_INSTANCE

#ifdef PATH_MEDIUM_SHADOWS
// A scattering vertex's shadow ray (o.shadowMedium), before its any-hit
// test: the medium's transmittance up to the first surface, which must be
// the back face of an index-matched boundary (the ray then goes on from its
// far side, tinted by its colour), or nothing (a light inside the medium).
// Returns false where another surface blocks it.
bool pathMediumShadow(inout PathNext o) {
    TraceHit bh;
    if (!bvhTraceClosest(o.shadow.origin, o.shadow.dir, 0.0, o.shadow.tmax, bh)) {
        o.contrib *= exp(-o.shadowSigma * o.shadow.tmax);
        o.shadow.tmax = 0.0;
        return true;
    }
#ifdef STRATA_INSTANCING
    gInstance = gHitInstance;
#endif
    TriVerts tv = shadeTri(bh.triangle);
    vec3 ng = normalize(cross(tv.v1.xyz - tv.v0.xyz, tv.v2.xyz - tv.v0.xyz));
    Material mat = sceneMaterial(shadeShading(bh.triangle).material);
    if (dot(o.shadow.dir, ng) <= 0.0 || (mat.flags & kMaterialIndexMatched) == 0u) return false;
    o.contrib *= exp(-o.shadowSigma * bh.t) * clamp(mat.baseColor.rgb, 0.0, 1.0);
#ifdef STRATA_INSTANCING
    o.shadow.origin = spawnOrigin(tv, bh.u, bh.v, ng, shadeSpawnError(bvhFetchTri(bh.triangle)));
#else
    o.shadow.origin = spawnOrigin(tv, bh.u, bh.v, ng);
#endif
    o.shadow.tmax = max(o.shadow.tmax - bh.t, 0.0);
    return true;
}
#endif

#endif
