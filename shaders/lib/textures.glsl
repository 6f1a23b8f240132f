// Texture lookups by hand from the packed texel words (BINDING_TEXELS, an
// R32UI texel view; layout in shared/types.h, TextureRef): KHR_texture_transform,
// wrap modes REPEAT / CLAMP_TO_EDGE / MIRRORED_REPEAT (OpenGL 4.6 sec. 8.14.2),
// and NEAREST or bilinear filtering of the level a TextureRef names (texture
// LOD picks the mip level: lib/material.glsl textureLevel). sRGB texels are
// decoded before filtering, as GPUs do for sRGB formats.
#ifndef STRATA_LIB_TEXTURES_GLSL
#define STRATA_LIB_TEXTURES_GLSL

#include "shared/types.h"
#include "shared/bindings.h"
#include "lib/reads.glsl"

layout(std430, set = 0, binding = BINDING_TEXREFS) readonly buffer TextureRefBuffer { TextureRef textureRefs[]; };
layout(set = 0, binding = BINDING_TEXREFS_TEXEL) uniform usamplerBuffer textureRefsTexel;

// textureRefs[i], through its RGBA32UI texel view (shared/texel_layout.h) with kTexelAll.
TextureRef textureRefAt(uint i) {
    if (!kTexelAll) return textureRefs[i];
    uvec4 t[kTextureRefTexels] = texels3(textureRefsTexel, i);
    return TextureRef(TEXEL_UINT(t, kTextureRefWordOffset), TEXEL_UINT(t, kTextureRefWordWidth),
                      TEXEL_UINT(t, kTextureRefWordHeight), TEXEL_UINT(t, kTextureRefWordFlags),
                      TEXEL_VEC4(t, kTextureRefWordRow0), TEXEL_VEC4(t, kTextureRefWordRow1));
}

#include "lib/texel_words.glsl"

// The exact sRGB decoding curve (IEC 61966-2-1).
vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

// Texel index i wrapped into [0, size) by `mode` (kWrap*).
int wrapTexel(int i, int size, uint mode) {
    if (mode == kWrapClamp) return clamp(i, 0, size - 1);
    if (mode == kWrapMirror) {
        int period = 2 * size;
        int m = i % period;
        m = m < 0 ? m + period : m;
        return m < size ? m : period - 1 - m;
    }
    int m = i % size;
    return m < 0 ? m + size : m;
}

// Texel (x, y) (already wrapped), rgba in [0, 1], rgb linear.
vec4 fetchTexel(TextureRef ref, int x, int y) {
    uint texel = uint(y) * ref.width + uint(x);
    vec4 c;
    if ((ref.flags & kTex16Bit) != 0u) {
        int word = int(ref.offset + 2u * texel);
        c = vec4(unpackUnorm2x16(texelFetch(texelWords, word).r),
                 unpackUnorm2x16(texelFetch(texelWords, word + 1).r));
    } else {
        c = unpackUnorm4x8(texelFetch(texelWords, int(ref.offset + texel)).r);
    }
    if ((ref.flags & kTexSrgb) != 0u) c.rgb = srgbToLinear(c.rgb);
    return c;
}

// The texture of `ref` at texture coordinates `uvIn` (before the transform).
vec4 sampleTextureRef(TextureRef ref, vec2 uvIn) {
    vec2 uv = vec2(dot(ref.row0.xy, uvIn) + ref.row0.z, dot(ref.row1.xy, uvIn) + ref.row1.z);
    ivec2 size = ivec2(ref.width, ref.height);
    uint wrapS = ref.flags & 3u;
    uint wrapT = (ref.flags >> 2u) & 3u;
    // Texel space, clamped so the int conversion below is defined.
    vec2 x = clamp(uv * vec2(size), vec2(-1.0e9), vec2(1.0e9));
    if ((ref.flags & kTexNearest) != 0u) {
        ivec2 p = ivec2(floor(x));
        return fetchTexel(ref, wrapTexel(p.x, size.x, wrapS), wrapTexel(p.y, size.y, wrapT));
    }
    // Bilinear between the four texel centres around x.
    vec2 c = x - 0.5;
    vec2 base = floor(c);
    vec2 f = c - base;
    ivec2 p = ivec2(base);
    int x0 = wrapTexel(p.x, size.x, wrapS), x1 = wrapTexel(p.x + 1, size.x, wrapS);
    int y0 = wrapTexel(p.y, size.y, wrapT), y1 = wrapTexel(p.y + 1, size.y, wrapT);
    vec4 top = mix(fetchTexel(ref, x0, y0), fetchTexel(ref, x1, y0), f.x);
    vec4 bottom = mix(fetchTexel(ref, x0, y1), fetchTexel(ref, x1, y1), f.x);
    return mix(top, bottom, f.y);
}

#endif
