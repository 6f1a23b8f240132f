// The camera effects of Cook et al. 1984 (STRATA_MOTION, the motion
// axis): a time for each camera sample within the shutter, the camera's
// pose at that time (an animated camera node), and a thin lens for depth of
// field. Each takes its own sampler pair, apart from the path's
// (lib/path.glsl), so stratification and Sobol reach them too. Included by
// lib/film.glsl.
#ifndef STRATA_LIB_CAMERA_GLSL
#define STRATA_LIB_CAMERA_GLSL

#include "lib/motion.glsl"

const uint kDimLens = 0xfffffffeu;  // the lens point's pair
const uint kDimTime = 0xfffffffcu;  // the time's pair (its first number)

// A point of the unit disk (concentric mapping, Shirley & Chiu 1997), or of
// the regular `blades`-gon inscribed in it (uniform by area), from u in [0,1)^2.
vec2 sampleAperture(vec2 u, uint blades) {
    if (blades >= 3u) {
        float fi = u.x * float(blades), i = floor(fi), r = sqrt(fi - i);
        float a0 = 6.283185307179586 * i / float(blades), a1 = 6.283185307179586 * (i + 1.0) / float(blades);
        return r * mix(vec2(cos(a0), sin(a0)), vec2(cos(a1), sin(a1)), u.y);
    }
    vec2 o = 2.0 * u - 1.0;
    if (o.x == 0.0 && o.y == 0.0) return vec2(0.0);
    float r, theta;
    if (abs(o.x) > abs(o.y)) {
        r = o.x;
        theta = 0.7853981633974483 * (o.y / o.x);
    } else {
        r = o.y;
        theta = 1.5707963267948966 - 0.7853981633974483 * (o.x / o.y);
    }
    return r * vec2(cos(theta), sin(theta));
}

// The camera ray through image position `pixel` (in pixels from the
// top-left corner): its time drawn uniformly in [shutter open, close] (set
// as gRayTime), the camera at that time (frame.cameraKeys when it moves:
// position lerped, orientation slerped), and with a lens (frame.lens.x > 0)
// from a point of the aperture towards where the pinhole ray meets the plane
// of focus (pbrt's thin lens).
void motionCameraRay(vec2 pixel, inout Sampler smp, out vec3 origin, out vec3 dir) {
    samplerSetDim(smp, kDimLens);
    vec2 uLens = sample2D(smp);
    samplerSetDim(smp, kDimTime);
    gRayTime = mix(frame.shutter.x, frame.shutter.y, sample1D(smp));
    origin = frame.camOrigin.xyz;
    vec3 forward = frame.camForward.xyz, right = frame.camRight.xyz, up = frame.camUp.xyz;
    uint keys = uint(frame.shutter.z);
    if (keys > 0u) {
        uint a = 0u;
        for (uint k = 1u; k < keys; ++k)
            if (frame.cameraKeys[2u * k].x <= gRayTime) a = k;
        uint b = min(a + 1u, keys - 1u);
        vec4 pa = frame.cameraKeys[2u * a], pb = frame.cameraKeys[2u * b];
        float w = pb.x > pa.x ? clamp((gRayTime - pa.x) / (pb.x - pa.x), 0.0, 1.0) : 0.0;
        vec4 q = quatSlerp(frame.cameraKeys[2u * a + 1u], frame.cameraKeys[2u * b + 1u], w);
        origin = mix(pa.yzw, pb.yzw, w);
        forward = quatRotate(q, vec3(0.0, 0.0, -1.0));
        right = quatRotate(q, vec3(1.0, 0.0, 0.0)) * length(frame.camRight.xyz);
        up = quatRotate(q, vec3(0.0, 1.0, 0.0)) * length(frame.camUp.xyz);
    }
    vec2 ndc = vec2(2.0 * pixel.x / float(frame.image.x) - 1.0, 1.0 - 2.0 * pixel.y / float(frame.image.y));
    dir = normalize(forward + ndc.x * right + ndc.y * up);
    if (frame.lens.x > 0.0) {
        vec2 a = frame.lens.x * sampleAperture(uLens, uint(frame.lens.z));
        vec3 focus = origin + dir * (frame.lens.y / dot(dir, forward));
        origin += a.x * normalize(right) + a.y * normalize(up);
        dir = normalize(focus - origin);
    }
}

#endif
