#!/usr/bin/env python3
"""Writes tests/data/lights/: the scenes and the environment map of
tests/test_lights.cpp, and lights/broken/: one bad KHR_lights_punctual value
per file. Deterministic; Python 3 standard library only. Our own data, CC0.
    python3 tests/data/make_lights.py
"""

import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))

from gltf_writer import GltfWriter, UNSIGNED_INT  # noqa: E402

OUT = os.path.join(HERE, "lights")
GEN = "strata tests/data/make_lights.py"
DOWN = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -90 deg about X: local -Z -> world -Y


def icosphere(level):
    """Unit icosphere: vertices on the unit sphere, faces CCW seen from outside."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][i] + verts[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(c * c for c in m))
                verts.append(tuple(c / n for c in m))
                cache[key] = len(verts) - 1
            return cache[key]

        nxt = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nxt += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = nxt
    return verts, faces


def add_sphere(w, level, material, inward):
    verts, faces = icosphere(level)
    idx = [i for f in faces for i in ((f[0], f[2], f[1]) if inward else f)]
    return w.add_triangles("Sphere", verts, indices=idx, material=material, index_type=UNSIGNED_INT)


def add_plane(w, material, half=10.0):
    """The square [-half, half]^2 at y = 0, facing +Y."""
    pts = [(-half, 0, -half), (-half, 0, half), (half, 0, half), (half, 0, -half)]
    return w.add_triangles("Plane", pts, indices=[0, 1, 2, 0, 2, 3], material=material)


def grey(w, albedo):
    """Exactly Lambertian: metallic 0 and no specular layer (KHR_materials_specular 0)."""
    return w.add_material("Grey", base_color=(albedo, albedo, albedo, 1), metallic=0, roughness=1,
                          specular=0.0)


def camera_down(w, height, yfov):
    cam = w.add_perspective("Camera", yfov)
    return w.add_node("Camera", camera=cam, translation=[0, height, 0], rotation=DOWN)


def frame_matrix(z, origin):
    """Column-major node matrix whose local +Z is the unit vector z."""
    up = (0.0, 1.0, 0.0) if abs(z[1]) < 0.9 else (1.0, 0.0, 0.0)
    x = cross(up, z)
    x = [c / math.sqrt(sum(v * v for v in x)) for c in x]
    y = cross(z, x)
    return list(x) + [0] + list(y) + [0] + list(z) + [0] + list(origin) + [1]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def finish(w, name, roots, bin_name=None):
    w.use_extensions((["KHR_lights_punctual"] if "extensions" in w.doc else []) +
                     ["KHR_materials_specular"])
    w.set_scene(roots)
    w.write_gltf(os.path.join(OUT, name), bin_name)


def point_in_sphere():
    """Closed unit icosphere (level 5, faces inward), albedo 0.5, point light of
    intensity pi at the centre; the camera at the centre looks down -Z."""
    w = GltfWriter(GEN)
    sphere = add_sphere(w, 5, grey(w, 0.5), inward=True)
    light = w.add_light("Point", "point", color=[1, 1, 1], intensity=math.pi)
    cam = w.add_perspective("Camera", 1.0)
    finish(w, "point-in-sphere.gltf", [w.add_node("Sphere", mesh=sphere), w.add_node("Point", light=light),
                                       w.add_node("Camera", camera=cam)], "point-in-sphere.bin")


def spot_plane():
    """Plane y = 0 (albedo 0.5) under a spot at (0, 2, 0) pointing down,
    intensity 20, cone 0.25 / 0.5 rad; camera at (0, 5, 0) looking down, yfov 0.6."""
    w = GltfWriter(GEN)
    plane = add_plane(w, grey(w, 0.5))
    light = w.add_light("Spot", "spot", color=[1, 1, 1], intensity=20.0, spot=(0.25, 0.5))
    finish(w, "spot-plane.gltf", [w.add_node("Plane", mesh=plane),
                                  w.add_node("Spot", light=light, translation=[0, 2, 0], rotation=DOWN),
                                  camera_down(w, 5.0, 0.6)])


def directional_plane():
    """Plane y = 0 (albedo 0.5) lit by a directional light travelling along
    normalize(1, -2, 0.5), color (1, 0.8, 0.6), intensity 3 (irradiance)."""
    w = GltfWriter(GEN)
    plane = add_plane(w, grey(w, 0.5))
    light = w.add_light("Sun", "directional", color=[1, 0.8, 0.6], intensity=3.0)
    travel = normalize((1.0, -2.0, 0.5))
    node = w.add_node("Sun", light=light, matrix=frame_matrix(tuple(-c for c in travel), (0, 7, 0)))
    finish(w, "directional-plane.gltf", [w.add_node("Plane", mesh=plane), node, camera_down(w, 5.0, 0.6)])


def convex_sphere():
    """Unit icosphere (level 3, faces outward), albedo 0.8, no light (the
    environment lights it); camera at (0, 0, 3) looking down -Z, yfov 0.8."""
    w = GltfWriter(GEN)
    sphere = add_sphere(w, 3, grey(w, 0.8), inward=False)
    cam = w.add_perspective("Camera", 0.8)
    finish(w, "sphere.gltf", [w.add_node("Sphere", mesh=sphere), w.add_node("Camera", camera=cam, translation=[0, 0, 3])])


def bare_sphere():
    """sphere.gltf's sphere moved to (1, 2, -3), with no camera and no light:
    strata frames it and lights it with its default white environment."""
    w = GltfWriter(GEN)
    sphere = add_sphere(w, 3, grey(w, 0.8), inward=False)
    finish(w, "bare-sphere.gltf", [w.add_node("Sphere", mesh=sphere, translation=[1, 2, -3])])


def env_plane():
    """A 40 x 40 plane through the origin facing n = normalize(1, 1.5, -0.5),
    albedo 0.5, no light; camera at 3 n looking along -n, yfov 0.5."""
    w = GltfWriter(GEN)
    n = normalize((1.0, 1.5, -0.5))
    plane = add_plane(w, grey(w, 0.5), half=20.0)
    cam = w.add_perspective("Camera", 0.5)
    finish(w, "env-plane.gltf", [w.add_node("Plane", mesh=plane, matrix=frame_matrix_y(n)),
                                 w.add_node("Camera", camera=cam, matrix=frame_matrix(n, tuple(3 * c for c in n)))])


def frame_matrix_y(n):
    """Node matrix taking +Y to the unit vector n (a rotation)."""
    m = frame_matrix(n, (0, 0, 0))  # columns x, y, z with z = n
    x, y, z = m[0:3], m[4:7], m[8:11]
    return list(x) + [0] + list(z) + [0] + [-c for c in y] + [0, 0, 0, 0, 1]


def rgbe(r, g, b):
    v = max(r, g, b)
    if v < 1e-32:
        return bytes(4)
    m, e = math.frexp(v)
    s = m * 256.0 / v
    return bytes((int(r * s), int(g * s), int(b * s), e + 128))


def sky_texel(x, y, w, h):
    """Sky above the horizon (blue-white, brighter towards +u), ground below,
    and a 2 x 2 texel sun at x 44-45, y 8-9 (about 92% of the power)."""
    u, v = (x + 0.5) / w, (y + 0.5) / h
    if x in (44, 45) and y in (8, 9):
        return (4000.0, 3600.0, 3000.0)
    if v < 0.5:
        k = 1.0 + 0.5 * u
        return ((0.25 + 0.5 * v) * k, (0.4 + 0.4 * v) * k, 0.9 * k)
    return (0.3 * (0.5 + u), 0.22 * (0.5 + u), 0.12 * (0.5 + u))


def sky_hdr(w=64, h=32):
    """Radiance RGBE, flat (uncompressed) scanlines, row 0 at the top (+Y)."""
    data = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {h} +X {w}\n".encode())
    for y in range(h):
        for x in range(w):
            data += rgbe(*sky_texel(x, y, w, h))
    with open(os.path.join(OUT, "sky.hdr"), "wb") as f:
        f.write(bytes(data))


def broken(name, light_index=0, **light):
    w = GltfWriter(GEN)
    plane = add_plane(w, grey(w, 0.5))
    w.add_light("Bad", **light)
    node = w.add_node("Bad", light=light_index, translation=[0, 2, 0], rotation=DOWN)
    w.use_extensions(["KHR_lights_punctual", "KHR_materials_specular"])
    w.set_scene([w.add_node("Plane", mesh=plane), node, camera_down(w, 5.0, 0.6)])
    w.write_gltf(os.path.join(OUT, "broken", name))


def range_warning():
    """The spot-plane scene with a point light that gives a range (ignored, one warning)."""
    w = GltfWriter(GEN)
    plane = add_plane(w, grey(w, 0.5))
    light = w.add_light("Ranged", "point", intensity=5.0, range_=3.0)
    finish(w, "range.gltf", [w.add_node("Plane", mesh=plane), w.add_node("Ranged", light=light, translation=[0, 2, 0]),
                             camera_down(w, 5.0, 0.6)])


def main():
    os.makedirs(os.path.join(OUT, "broken"), exist_ok=True)
    point_in_sphere()
    spot_plane()
    directional_plane()
    convex_sphere()
    bare_sphere()
    env_plane()
    sky_hdr()
    broken("negative-intensity.gltf", type_="point", intensity=-1.0)
    broken("outer-cone-too-wide.gltf", type_="spot", spot=(0.1, 2.0))
    broken("inner-not-below-outer.gltf", type_="spot", spot=(0.5, 0.5))
    broken("unknown-type.gltf", type_="area")
    broken("light-out-of-range.gltf", light_index=3, type_="point")
    broken("spot-without-cone.gltf", type_="spot")
    broken("zero-intensity-only-light.gltf", type_="point", intensity=0.0)
    range_warning()


if __name__ == "__main__":
    main()
