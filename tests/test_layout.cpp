// Byte layout of the structs shared with GLSL (std430: a vec3 is 16-byte
// aligned and 12 bytes long, so the scalar after it fills the last 4 bytes).
#include <doctest/doctest.h>

#include <cstddef>

#include "../shaders/shared/types.h"

using namespace strata::gpu;

TEST_SUITE_BEGIN("unit");

TEST_CASE("shared structs have the std430 offsets the shaders assume") {
    CHECK(offsetof(BvhNode, leftOrFirst) == 12);
    CHECK(offsetof(BvhNode, bmax) == 16);
    CHECK(offsetof(BvhNode, count) == 28);
    CHECK(offsetof(TriShading, material) == 12);
    CHECK(offsetof(TriShading, light) == 28);
    CHECK(offsetof(Material, emission) == 16);
    CHECK(offsetof(Material, metallic) == 28);
    CHECK(offsetof(Material, alphaCutoff) == 44);
    CHECK(offsetof(Material, transmission) == 48);
    CHECK(offsetof(Material, baseColorTex) == 60);
    CHECK(offsetof(Material, transmissionTex) == 76);
    CHECK(offsetof(Emitter, kind) == 72);
    CHECK(offsetof(Emitter, triangle) == 12);
    CHECK(offsetof(Emitter, area) == 28);
    CHECK(offsetof(Emitter, pmf) == 44);
    CHECK(offsetof(Emitter, radiance) == 48);
    CHECK(offsetof(Emitter, aliasProb) == 64);
    CHECK(offsetof(FrameUniforms, image) == 64);
    CHECK(offsetof(FrameUniforms, scene) == 96);
    CHECK(offsetof(FrameUniforms, envScale) == 112);
    CHECK(offsetof(FrameUniforms, envRotation) == 128);
    CHECK(offsetof(FrameUniforms, envInfo) == 144);
    CHECK(offsetof(FrameUniforms, lens) == 160);
    CHECK(offsetof(FrameUniforms, shutter) == 176);
    CHECK(offsetof(FrameUniforms, cameraKeys) == 192);
    CHECK(offsetof(TraceRay, tmin) == 12);
    CHECK(offsetof(TraceHit, triangle) == 4);
    // Texel views read nodes as 2 and triangles as 3 RGBA32 texels.
    CHECK(sizeof(BvhNode) == 2 * 16);
    CHECK(sizeof(TriVerts) == 3 * 16);
    CHECK(sizeof(BvhNode4) == 7 * 16);
    CHECK(offsetof(BvhNode4, child) == 6 * 16);
}

TEST_SUITE_END();
