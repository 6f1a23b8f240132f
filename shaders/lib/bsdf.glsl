// The glTF 2.0 metallic-roughness BSDF (the spec's Appendix B mix) with
// KHR_materials_transmission, _ior and _specular (factor and colour):
//
//   f = mix(dielectric, metal, metallic)
//   metal      = GGX reflection with F = baseColor + (1 - baseColor)(1 - |wo.h|)^5
//   dielectric = specular * Fd(wo.h) * GGX reflection
//              + (1 - specular * Fd(wo.h)) * mix(baseColor / pi, baseColor * GGX transmission, transmission)
//
// Fd is the exact dielectric Fresnel of ior (the spec's Schlick form is an
// approximation it allows replacing). KHR_materials_specular's colour
// (kFeatureSpecularColor) makes it RGB with the extension's F0 and F90:
//
//   Fd = specular * mix(F0c, 1, (F(wo.h) - F0) / (1 - F0)),  F0c = min(F0 * specularColor, 1)
//
// F the exact Fresnel and F0 = ((ior - 1) / (ior + 1))^2 its value at
// normal incidence (so a colour of 1 is the exact Fresnel), and the layer
// beneath keeps 1 - max(Fd), as the extension's fresnel_mix does.
// Transmission refracts into a closed volume (not thin-walled) and scales
// radiance by 1/eta^2 (Veach 1997, sec. 5.2). GGX (Trowbridge-Reitz) with height-correlated Smith shadowing,
// alpha = roughness^2; the visible normals are sampled with spherical caps
// (Dupuy & Benyoub 2023) and transmission follows Walter et al. 2007. Below
// alpha kDeltaAlpha the reflection and transmission lobes are exact (delta)
// mirror and refraction, so roughness 0 is a perfect mirror.
//
// KHR_materials_sheen (kFeatureSheen) lays a sheen over that base, and
// KHR_materials_clearcoat (kFeatureClearcoat) a GGX coat of ior 1.5 with
// its own roughness and normal over both, as the extensions do:
//
//   f = (1 - coatF) (sheen + base * sheenScale) + coatF * GGX(coat alpha, coat normal)
//   sheen = sheenColor * Charlie D * V / max(1, E(wo.z))
//   sheenScale = 1 - max3(sheenColor) min(1, E(wo.z))
//   coatF = clearcoat * Schlick(F0 0.04, wo . coat normal)
//
// with E the sheen lobe's directional albedo (lib/sheen.glsl): the
// extension's albedo scaling in its view-only form. Where the extension's
// lobe reflects more than it receives (E > 1: small sheen roughness at
// grazing views), it is divided by E. The coat lobe is evaluated in the
// coat's frame, with |cos| of its own normal.
//
// The layers and the specular colour are compiled only with STRATA_LAYERS
// (the layers axis, host/spirv/features.cpp), and then each under its
// feature bit; KHR_materials_iridescence's thin film (kFeatureIridescence)
// only with STRATA_IRIDESCENCE as well (the iridescence axis), which mixes
// the film's Fresnel (thinFilmFresnel) into the dielectric's and the metal's
// by its factor.
//
// KHR_materials_anisotropy (kFeatureAnisotropy, compiled only with
// STRATA_ANISOTROPY, the aniso axis) stretches the base's GGX reflection and
// transmission along the shading frame's x, which lib/path.glsl turns to
// the anisotropy's direction: alpha_x = mix(alpha, 1, strength^2), alpha_y =
// alpha (the extension's), with the anisotropic D, Smith Lambda and visible
// normals of lib/ggx.glsl. The coat stays isotropic.
//
// KHR_materials_diffuse_transmission (kFeatureDiffuseTransmission, compiled
// only with STRATA_DIFFUSE_TRANSMISSION, the difftrans axis) sends a share of
// the dielectric's diffuse light through the surface, as the extension's
// mix does:
//
//   diffuse = (1 - Fd) mix(baseColor / pi (wi.z > 0), diffuseTransmissionColor / pi (wi.z < 0), factor)
//
// Fd at the half vector of wo and wi mirrored to wo's side (symmetric in wo
// and wi). The transmitted lobe is one more sampling strategy (cosine below
// the surface, `pDiffuseT`). The path tracer makes such a surface
// thin-walled unless it bounds a volume (lib/path.glsl): both faces see the
// outside's ior.
//
// All directions are in the local shading frame: z is the shading normal on
// the side the ray came from, so wo.z > 0; reflection has wi.z > 0 and
// transmission wi.z < 0. `etap` is the ratio of the indices of refraction
// of the far side over wo's side.
#ifndef STRATA_LIB_BSDF_GLSL
#define STRATA_LIB_BSDF_GLSL

#include "shared/types.h"
#include "shared/bindings.h"
#include "lib/features.glsl"
#include "lib/sampling.glsl"
#include "lib/ggx.glsl"
#ifdef STRATA_LAYERS
#include "lib/sheen.glsl"
#endif

const float kDeltaAlpha = 1.0e-3;

// The base's GGX alpha: a vec2 with KHR_materials_anisotropy (lib/ggx.glsl's
// anisotropic overloads), else the float.
#ifdef STRATA_ANISOTROPY
#define BASE_ALPHA(b) ((b).alphaXY)
#else
#define BASE_ALPHA(b) ((b).alpha)
#endif

struct Bsdf {
    vec3 baseColor;
    float metallic;
    float alpha;         // GGX alpha = roughness^2
#ifdef STRATA_ANISOTROPY
    vec2 alphaXY;        // KHR_materials_anisotropy: alpha along the direction (x) and across it (y)
#endif
    float transmission;
    float etap;          // far-side ior / near-side ior
    float specular;      // KHR_materials_specular factor on the dielectric Fresnel
    bool delta;          // alpha < kDeltaAlpha: mirror / refraction lobes are deltas
    // Probabilities of the base's sampling strategies (set by makeBsdf): the
    // microfacet lobes (then reflection or transmission by specularSplit)
    // and the diffuse lobe.
    float pSpecular, pDiffuse;
#ifdef STRATA_DIFFUSE_TRANSMISSION
    // KHR_materials_diffuse_transmission (factor 0 without it).
    float diffTrans;     // the share of the diffuse light sent through
    vec3 diffTransColor;
    float pDiffuseT;     // probability of its strategy (cosine below the surface)
    float fdInside;      // seen from inside a volume: the GGX lobe's albedo at wo, which the diffuse lobes leave
#endif
#ifdef STRATA_LAYERS
    // KHR_materials_specular's colour (kFeatureSpecularColor).
    vec3 f0Tint;         // min(F0 * specularColor, 1)
    float f0;            // F0 = ((ior - 1) / (ior + 1))^2
    // KHR_materials_clearcoat (kFeatureClearcoat; coat 0 without one).
    float coat;          // clearcoat factor x texture
    float coatAlpha;     // GGX alpha of the coat
    bool coatDelta;      // coatAlpha < kDeltaAlpha: the coat is a mirror
    vec3 coatN;          // the coat's normal in the shading frame (wo . coatN > 0)
    float coatF;         // coat * Schlick(0.04, wo . coatN): the coat's weight
    // KHR_materials_sheen (kFeatureSheen; sheen 0 without one).
    vec3 sheen;          // sheenColor (1 - coatF) / max(1, E(wo.z)): the Charlie lobe's weight
    float sheenAlpha;    // Charlie alpha = roughness^2
    float sheenLambdaO;  // the visibility fit's Lambda(wo.z)
    float baseScale;     // what the layers leave the base: (1 - coatF) sheenScale
    float pCoat, pSheen; // probabilities of the layers' strategies
#ifdef STRATA_IRIDESCENCE
    // KHR_materials_iridescence (kFeatureIridescence; film 0 without one).
    float film;          // iridescence factor x texture, in [0, 1]
    float filmIor;
    float filmThickness; // nanometres
#endif
#endif
};

// The layers over the base a surface point gives makeBsdf; each is read
// only under its feature bit.
struct BsdfLayers {
    vec3 specularColor;   // KHR_materials_specular: linear, factor x texture (1: none)
    float coat;           // KHR_materials_clearcoat: clearcoat factor x texture (0: none)
    float coatRoughness;  // perceptual
    vec3 coatNormal;      // unit, in the shading frame
    vec3 sheenColor;      // KHR_materials_sheen: linear, factor x texture (0: none)
    float sheenRoughness;
#ifdef STRATA_IRIDESCENCE
    float iridescence;    // KHR_materials_iridescence: factor x texture (0: none)
    float iridescenceIor;
    float iridescenceThickness;  // nanometres
#endif
#ifdef STRATA_ANISOTROPY
    float anisotropy;                // KHR_materials_anisotropy: strength along the frame's x (0: none)
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
    float diffuseTransmission;       // KHR_materials_diffuse_transmission: factor x texture (0: none)
    vec3 diffuseTransmissionColor;   // linear, factor x texture
#endif
};

BsdfLayers noLayers() {
    return BsdfLayers(vec3(1.0), 0.0, 0.0, vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0
#ifdef STRATA_IRIDESCENCE
                      , 0.0, 1.3, 0.0
#endif
#ifdef STRATA_ANISOTROPY
                      , 0.0
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
                      , 0.0, vec3(1.0)
#endif
    );
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

#ifdef STRATA_LAYERS
float max3(vec3 v) { return max(v.x, max(v.y, v.z)); }
#endif

#include "lib/fresnel.glsl"

#ifdef STRATA_LAYERS
#include "lib/bsdf_layers.glsl"
#endif

// ior < 1 (KHR_materials_ior allows 0) is treated as 1.5, the default.
// wo weighs the sampling strategies (wo.z > 0). A coat normal facing away
// from wo is replaced by the shading normal.
#ifdef STRATA_DIFFUSE_TRANSMISSION
// A bound on the directional albedo of the base's GGX reflection at wo: the
// dielectric Fresnel over its visible normals (the lobe's albedo also has
// G2 / G1 <= 1), by 16 fixed stratified normals, so the same number for a
// given wo everywhere it is used.
float ggxLobeAlbedo(Bsdf b, vec3 wo) {
    float sum = 0.0;
    for (int i = 0; i < 16; ++i) {
        vec2 u = vec2((float(i & 3) + 0.5) * 0.25, (float(i >> 2) + 0.5) * 0.25);
        sum += dielectricMax(b, dot(wo, ggxSampleVisible(wo, BASE_ALPHA(b), u)));
    }
    return sum * 0.0625;
}
#endif

Bsdf makeBsdf(vec3 baseColor, float metallic, float roughness, float transmission, float ior,
              float specular, BsdfLayers layers, bool entering, vec3 wo) {
    float cosO = wo.z;
    Bsdf b;
#ifdef STRATA_LAYERS
    clearLayers(b);
#endif
    b.baseColor = clamp(baseColor, 0.0, 1.0);
    b.metallic = clamp(metallic, 0.0, 1.0);
    float r = clamp(roughness, 0.0, 1.0);
    b.alpha = r * r;
    b.delta = b.alpha < kDeltaAlpha;
#ifdef STRATA_ANISOTROPY
    // KHR_materials_anisotropy: mix(alpha, 1, strength^2) along the
    // direction, alpha across it; a delta only when both are below
    // kDeltaAlpha (else the smaller is kept above 1e-4).
    float strength = hasFeature(kFeatureAnisotropy) ? clamp(layers.anisotropy, 0.0, 1.0) : 0.0;
    b.alphaXY = vec2(mix(b.alpha, 1.0, strength * strength), b.alpha);
    b.delta = b.alphaXY.x < kDeltaAlpha;
    if (!b.delta) b.alphaXY.y = max(b.alphaXY.y, 1.0e-4);
#endif
    b.transmission = clamp(transmission, 0.0, 1.0);
    float eta = ior >= 1.0 ? ior : 1.5;
    b.etap = entering ? eta : 1.0 / eta;
    b.specular = clamp(specular, 0.0, 1.0);
#ifdef STRATA_LAYERS
#ifndef STRATA_IRIDESCENCE
    if (hasFeature(kFeatureSpecularColor)) {
        b.f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
        b.f0Tint = min(b.f0 * max(layers.specularColor, vec3(0.0)), vec3(1.0));
    }
#else
    if (hasFeature(kFeatureSpecularColor | kFeatureIridescence)) {
        b.f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
        b.f0Tint = hasFeature(kFeatureSpecularColor) ? min(b.f0 * max(layers.specularColor, vec3(0.0)), vec3(1.0))
                                                     : vec3(b.f0);
    }
    if (hasFeature(kFeatureIridescence)) {
        b.film = clamp(layers.iridescence, 0.0, 1.0);
        b.filmIor = max(layers.iridescenceIor, 1.0);
        b.filmThickness = max(layers.iridescenceThickness, 0.0);
    }
#endif
#endif
    // Strategy weights: the lobes' albedos estimated at the macro normal.
    // The floors keep every lobe that can be non-zero at some microfacet
    // samplable (a black metal at normal incidence, a diffuse base behind
    // total internal reflection), so the estimator stays unbiased.
    float fd = dielectricMax(b, cosO);
    float lumBase = luminance(b.baseColor);
    float ws = b.metallic * max(luminance(fresnelSchlick(b.baseColor, cosO)), 1.0e-3) +
               (1.0 - b.metallic) * (fd + (1.0 - fd) * b.transmission * lumBase);
    float wd = (1.0 - b.metallic) * (1.0 - b.transmission) * max(1.0 - fd, 0.05) * lumBase;
#ifdef STRATA_DIFFUSE_TRANSMISSION
    // The diffuse light split between the two sides by the factor, each
    // weighed by its colour.
    float wdt = 0.0;
    b.diffTrans = 0.0;
    b.diffTransColor = vec3(0.0);
    b.fdInside = 0.0;
    if (hasFeature(kFeatureDiffuseTransmission) && layers.diffuseTransmission > 0.0) {
        b.diffTrans = clamp(layers.diffuseTransmission, 0.0, 1.0);
        b.diffTransColor = clamp(layers.diffuseTransmissionColor, 0.0, 1.0);
        // Seen from inside a volume (etap < 1), the GGX lobe's microfacets
        // reach total internal reflection well before the macro normal does
        // and reflect far more than F(wo): the diffuse lobes keep 1 - its
        // albedo (`fdInside`), and the strategies are weighed by it.
        if (b.etap < 1.0) {
            b.fdInside = b.delta ? fd : ggxLobeAlbedo(b, wo);
            fd = b.fdInside;
            ws = b.metallic * max(luminance(fresnelSchlick(b.baseColor, cosO)), 1.0e-3) +
                 (1.0 - b.metallic) * (fd + (1.0 - fd) * b.transmission * lumBase);
        }
        float wdAll = (1.0 - b.metallic) * (1.0 - b.transmission) * max(1.0 - fd, 0.05);
        wd = wdAll * (1.0 - b.diffTrans) * lumBase;
        wdt = wdAll * b.diffTrans * luminance(b.diffTransColor);
    }
    b.pDiffuseT = wdt;
#endif
#ifdef STRATA_LAYERS
    if (hasFeature(kFeatureClearcoat | kFeatureSheen)) {
        addLayers(b, layers, wo, ws, wd);
        return b;
    }
#endif
#ifdef STRATA_DIFFUSE_TRANSMISSION
    float total = ws + wd + wdt;
    b.pDiffuseT = total > 0.0 ? wdt / total : 0.0;
#else
    float total = ws + wd;
#endif
    b.pSpecular = total > 0.0 ? ws / total : 0.0;
    b.pDiffuse = total > 0.0 ? wd / total : 0.0;
    return b;
}

// Lambert alone (metallic 0, specular 0, no transmission): the diffuse lobe
// with probability 1.
Bsdf makeLambert(vec3 baseColor) {
    Bsdf b;
    b.baseColor = clamp(baseColor, 0.0, 1.0);
    b.metallic = 0.0;
    b.alpha = 1.0;
#ifdef STRATA_ANISOTROPY
    b.alphaXY = vec2(1.0);
#endif
    b.transmission = 0.0;
    b.etap = 1.5;
    b.specular = 0.0;
    b.delta = false;
    b.pSpecular = 0.0;
    b.pDiffuse = 1.0;
#ifdef STRATA_DIFFUSE_TRANSMISSION
    b.diffTrans = 0.0;
    b.diffTransColor = vec3(0.0);
    b.pDiffuseT = 0.0;
    b.fdInside = 0.0;
#endif
#ifdef STRATA_LAYERS
    clearLayers(b);
#endif
    return b;
}

// The base's non-delta part times |wi.z| (before the layers' scaling), and
// the density of its strategies (their choice included).
vec3 evalBase(Bsdf b, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    vec3 f = vec3(0.0);
    if (wo.z <= 0.0 || wi.z == 0.0) return f;
    if (wi.z > 0.0) {
        vec3 h = normalize(wo + wi);
        float c = dot(wo, h);
        if (b.pDiffuse > 0.0) {
            float fd = b.specular > 0.0 ? dielectricMax(b, c) : 0.0;
#ifdef STRATA_DIFFUSE_TRANSMISSION
            if (b.diffTrans > 0.0 && b.etap < 1.0) fd = b.fdInside;
            f += (1.0 - b.metallic) * (1.0 - b.transmission) * (1.0 - fd) * (1.0 - b.diffTrans) * b.baseColor *
                 (kInvPi * wi.z);
#else
            f += (1.0 - b.metallic) * (1.0 - b.transmission) * (1.0 - fd) * b.baseColor * (kInvPi * wi.z);
#endif
            pdf += b.pDiffuse * wi.z * kInvPi;
        }
        if (!b.delta && b.pSpecular > 0.0) {
            f += reflectance(b, c) * (ggxD(h, BASE_ALPHA(b)) * ggxG2(wo, wi, BASE_ALPHA(b)) / (4.0 * wo.z));
            pdf += b.pSpecular * specularSplit(b, c) * ggxVisiblePdf(wo, h, BASE_ALPHA(b)) / (4.0 * c);
        }
    } else {
#ifdef STRATA_DIFFUSE_TRANSMISSION
        if (b.pDiffuseT > 0.0) {
            // Fd at the half vector of wo and wi mirrored to wo's side; seen
            // from inside a volume (etap < 1) the GGX lobe's albedo instead:
            // at the mirrored half vector the two lobes would together
            // reflect up to 1.6 where total internal reflection sets in.
            vec3 m = vec3(wi.xy, -wi.z);
            float fd = b.etap < 1.0 ? b.fdInside
                                    : (b.specular > 0.0 ? dielectricMax(b, dot(wo, normalize(wo + m))) : 0.0);
            f += (1.0 - b.metallic) * (1.0 - b.transmission) * (1.0 - fd) * b.diffTrans * b.diffTransColor *
                 (kInvPi * m.z);
            pdf += b.pDiffuseT * m.z * kInvPi;
        }
#endif
        if (!(!b.delta && b.pSpecular > 0.0 && b.transmission > 0.0)) return f;
        // Generalised half vector (Walter et al. 2007), on wo's side.
        vec3 h = wi * b.etap + wo;
        if (dot(h, h) == 0.0) return f;
        h = normalize(h);
        if (h.z < 0.0) h = -h;
        float ci = dot(wi, h), co = dot(wo, h);
        if (ci >= 0.0 || co <= 0.0) return f;  // back-facing microfacet
        float fd = dielectricMax(b, co);
        float denom = ci + co / b.etap;
        denom *= denom;
        float d = ggxD(h, BASE_ALPHA(b));
        float ft = d * ggxG2(wo, wi, BASE_ALPHA(b)) * (1.0 - fd) * (-ci) * co / (denom * wo.z);
        f += (1.0 - b.metallic) * b.transmission * b.baseColor * (ft / (b.etap * b.etap));
        float dhdwi = -ci / denom;
        pdf += b.pSpecular * (1.0 - specularSplit(b, co)) * ggxVisiblePdf(wo, h, BASE_ALPHA(b)) * dhdwi;
    }
    return f;
}

#ifdef STRATA_LAYERS
// w in the coat's frame (coatN as z, a tangent frame by basis()).
vec3 toCoatFrame(vec3 n, vec3 w) {
    vec3 t, bt;
    basis(n, t, bt);
    return vec3(dot(w, t), dot(w, bt), dot(w, n));
}

vec3 fromCoatFrame(vec3 n, vec3 w) {
    vec3 t, bt;
    basis(n, t, bt);
    return w.x * t + w.y * bt + w.z * n;
}
#endif

// The non-delta part of the BSDF times |cos| (each lobe's own normal), and
// the density with which sampleBsdf produces wi (solid angle, strategy and
// lobe choice included).
vec3 evalBsdf(Bsdf b, vec3 wo, vec3 wi, out float pdf) {
#ifndef STRATA_LAYERS
    return evalBase(b, wo, wi, pdf);
#else
    if (!hasFeature(kFeatureClearcoat | kFeatureSheen)) return evalBase(b, wo, wi, pdf);
    vec3 f = evalBase(b, wo, wi, pdf) * b.baseScale;
    if (hasFeature(kFeatureSheen) && b.pSheen > 0.0 && wo.z > 0.0 && wi.z > 0.0) {
        vec3 h = normalize(wo + wi);
        float d = charlieD(h.z, b.sheenAlpha);
        f += b.sheen * (d / ((1.0 + b.sheenLambdaO + charlieLambda(wi.z, b.sheenAlpha)) * 4.0 * wo.z));
        pdf += b.pSheen * d * h.z / (4.0 * dot(wo, h));
    }
    if (hasFeature(kFeatureClearcoat) && b.pCoat > 0.0 && !b.coatDelta && wo.z > 0.0) {
        vec3 o = toCoatFrame(b.coatN, wo), i = toCoatFrame(b.coatN, wi);
        if (o.z > 0.0 && i.z > 0.0) {
            vec3 h = normalize(o + i);
            f += vec3(b.coatF * ggxD(h, b.coatAlpha) * ggxG2(o, i, b.coatAlpha) / (4.0 * o.z));
            pdf += b.pCoat * ggxVisiblePdf(o, h, b.coatAlpha) / (4.0 * dot(o, h));
        }
    }
    return f;
#endif
}

struct BsdfSample {
    vec3 wi;
    vec3 weight;   // f |wi.z| / pdf (delta lobes: their reflectance / choice probability)
    float pdf;     // solid-angle density of the non-delta lobes; 0 for a delta sample
    bool delta;    // sampled from a delta lobe (no MIS with light sampling)
    bool valid;
};

BsdfSample noSample() { return BsdfSample(vec3(0.0, 0.0, 1.0), vec3(0.0), 0.0, false, false); }

// The weight and pdf of a non-delta sample s.wi: the whole BSDF's.
BsdfSample finishSample(Bsdf b, vec3 wo, BsdfSample s) {
    vec3 f = evalBsdf(b, wo, s.wi, s.pdf);
    if (s.pdf <= 0.0) return s;
    s.weight = f / s.pdf;
    s.valid = true;
    return s;
}

#ifdef STRATA_LAYERS
// The coat strategy's direction: a GGX visible normal in the coat's frame
// (its mirror normal when the coat is smooth), reflected; false when the
// direction leaves below the coat.
bool sampleCoatDirection(vec3 n, float alpha, bool delta, vec3 wo, vec2 u, out vec3 wi) {
    vec3 o = toCoatFrame(n, wo);
    vec3 h = delta ? vec3(0.0, 0.0, 1.0) : ggxSampleVisible(o, alpha, u);
    vec3 i = reflect(-o, h);
    wi = fromCoatFrame(n, i);
    return dot(o, h) > 0.0 && i.z > 0.0;
}

// The sheen strategy's direction: a Charlie normal (density D h.z), reflected.
bool sampleSheenDirection(float alpha, vec3 wo, vec2 u, out vec3 wi) {
    vec3 h = charlieSample(alpha, u);
    wi = reflect(-wo, h);
    return dot(wo, h) > 0.0 && wi.z > 0.0;
}
#endif

// One direction: uLobe picks the coat, sheen, microfacet or diffuse
// (reflected, then transmitted) strategy by the probabilities of makeBsdf
// and then, rescaled, reflection or transmission at the sampled
// microfacet; u is the direction within the lobe. A non-delta direction gets the whole BSDF's weight and pdf from one
// evalBsdf (one copy of it in the compiled shader).
BsdfSample sampleBsdf(Bsdf b, vec3 wo, float uLobe, vec2 u) {
    BsdfSample s = noSample();
    if (wo.z <= 0.0) return s;
#ifdef STRATA_LAYERS
    uint layer = 0u;  // the layers' strategies: 1 the coat, 2 the sheen
    if (hasFeature(kFeatureClearcoat) && b.pCoat > 0.0) {
        if (uLobe < b.pCoat) layer = 1u;
        else uLobe -= b.pCoat;
    }
    if (hasFeature(kFeatureSheen) && layer == 0u && b.pSheen > 0.0) {
        if (uLobe < b.pSheen) layer = 2u;
        else uLobe -= b.pSheen;
    }
    if (layer == 1u) {
        if (!sampleCoatDirection(b.coatN, b.coatAlpha, b.coatDelta, wo, u, s.wi)) return s;
        if (b.coatDelta) {
            s.weight = vec3(b.coatF / b.pCoat);
            s.delta = s.valid = true;
            return s;
        }
    } else if (layer == 2u) {
        if (!sampleSheenDirection(b.sheenAlpha, wo, u, s.wi)) return s;
    } else
#endif
    if (uLobe < b.pSpecular) {
        float uSplit = uLobe / b.pSpecular;
        vec3 h = b.delta ? vec3(0.0, 0.0, 1.0) : ggxSampleVisible(wo, BASE_ALPHA(b), u);
        float c = dot(wo, h);
        if (c <= 0.0) return s;
        float pr = specularSplit(b, c);
        if (uSplit < pr) {
            s.wi = reflect(-wo, h);
            if (b.delta) {
                s.weight = reflectance(b, c) / (b.pSpecular * pr);
#ifdef STRATA_LAYERS
                if (hasFeature(kFeatureClearcoat | kFeatureSheen)) s.weight *= b.baseScale;
#endif
                s.delta = s.valid = true;
                return s;
            }
            if (s.wi.z <= 0.0) return s;
        } else {
            if (!refractDir(wo, h, b.etap, s.wi) || s.wi.z >= 0.0) return s;
            if (b.delta) {
                float fd = dielectricMax(b, c);
                s.weight = (1.0 - b.metallic) * b.transmission * (1.0 - fd) * b.baseColor /
                           (b.etap * b.etap * b.pSpecular * (1.0 - pr));
#ifdef STRATA_LAYERS
                if (hasFeature(kFeatureClearcoat | kFeatureSheen)) s.weight *= b.baseScale;
#endif
                s.delta = s.valid = true;
                return s;
            }
        }
    } else {
        s.wi = sampleCosineHemisphere(u);
#ifdef STRATA_DIFFUSE_TRANSMISSION
        // Past the reflected lobe's share: the transmitted one, below.
        if (uLobe >= b.pSpecular + b.pDiffuse) s.wi.z = -s.wi.z;
        if (s.wi.z == 0.0) return s;
#else
        if (s.wi.z <= 0.0) return s;
#endif
    }
    return finishSample(b, wo, s);
}

#endif
