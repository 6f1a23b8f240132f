// The layers over lib/bsdf.glsl's base (STRATA_LAYERS: KHR_materials_sheen
// and _clearcoat): clearing them, and weighing them over the base with the
// sampling strategies' probabilities (makeBsdf's last step). Included by
// lib/bsdf.glsl after its Bsdf struct and the Fresnel terms.
#ifndef STRATA_LIB_BSDF_LAYERS_GLSL
#define STRATA_LIB_BSDF_LAYERS_GLSL

// No layers: what makeBsdf and makeLambert start from.
void clearLayers(inout Bsdf b) {
    b.coat = 0.0;
    b.coatAlpha = 1.0;
    b.coatDelta = false;
    b.coatN = vec3(0.0, 0.0, 1.0);
    b.coatF = 0.0;
    b.f0Tint = vec3(0.04);
    b.f0 = 0.04;
    b.sheen = vec3(0.0);
    b.sheenAlpha = 1.0;
    b.sheenLambdaO = 0.0;
    b.baseScale = 1.0;
    b.pCoat = 0.0;
    b.pSheen = 0.0;
#ifdef STRATA_IRIDESCENCE
    b.film = 0.0;
    b.filmIor = 1.3;
    b.filmThickness = 0.0;
#endif
}

// The layers over the base (makeBsdf's last step): their weights, the base's
// scale, and the strategies' probabilities from the base's albedo
// estimates ws (microfacet) and wd (diffuse) and the layers' own.
void addLayers(inout Bsdf b, BsdfLayers layers, vec3 wo, float ws, float wd) {
    float wSheen = 0.0, wCoat = 0.0;
    if (hasFeature(kFeatureSheen) && max3(layers.sheenColor) > 0.0) {
        vec3 color = clamp(layers.sheenColor, 0.0, 1.0);
        float r = max(clamp(layers.sheenRoughness, 0.0, 1.0), kSheenRoughnessMin);
        b.sheenAlpha = r * r;
        float e = sheenAlbedo(wo.z, r);
        b.sheen = color / max(e, 1.0);
        b.sheenLambdaO = charlieLambda(wo.z, b.sheenAlpha);
        b.baseScale = 1.0 - max3(color) * min(e, 1.0);
        // The lobe's albedo estimate, floored as the base's are.
        wSheen = max3(color) * max(min(e, 1.0), 0.01);
    }
    if (hasFeature(kFeatureClearcoat) && layers.coat > 0.0) {
        b.coat = min(layers.coat, 1.0);
        float rc = clamp(layers.coatRoughness, 0.0, 1.0);
        b.coatAlpha = rc * rc;
        b.coatDelta = b.coatAlpha < kDeltaAlpha;
        if (dot(wo, layers.coatNormal) > 0.0) b.coatN = layers.coatNormal;
        b.coatF = b.coat * fresnelSchlick(vec3(0.04), dot(wo, b.coatN)).x;
        b.baseScale *= 1.0 - b.coatF;
        b.sheen *= 1.0 - b.coatF;
        wSheen *= 1.0 - b.coatF;
        wCoat = b.coatF;  // the coat's albedo estimate: its Fresnel weight
    }
    ws *= b.baseScale;
    wd *= b.baseScale;
#ifdef STRATA_DIFFUSE_TRANSMISSION
    // makeBsdf left the transmitted lobe's weight in pDiffuseT.
    float wdt = b.pDiffuseT * b.baseScale;
    float total = ws + wd + wdt + wSheen + wCoat;
    b.pDiffuseT = total > 0.0 ? wdt / total : 0.0;
#else
    float total = ws + wd + wSheen + wCoat;
#endif
    b.pSpecular = total > 0.0 ? ws / total : 0.0;
    b.pDiffuse = total > 0.0 ? wd / total : 0.0;
    b.pSheen = total > 0.0 ? wSheen / total : 0.0;
    b.pCoat = total > 0.0 ? wCoat / total : 0.0;
}

#endif
