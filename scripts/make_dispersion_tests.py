#!/usr/bin/env python3
"""Known-answer scenes for KHR_materials_dispersion (tests/test_dispersion.cpp),
written to tests/data/dispersion/. Our own work, CC0.

wedge.gltf: a glass wedge (ior IOR, dispersion DISPERSION: Abbe number 20 /
DISPERSION) between a camera and a thin vertical emissive strip. The camera
at (0, 0, CAMERA_Z) looks down -Z through the wedge's front face, the plane
z = FRONT_Z, and out of its back face, the plane z = -tan(APEX) x, whose
outward normal is (-sin APEX, 0, -cos APEX); the wedge spans x, y in
[-HALF, HALF]. Refraction bends the rays towards +X, by an angle that grows
with the index: the strip at z = STRIP_Z, centred where the view's axis
lands after refraction at IOR (strip_x) and 2 pixels wide as the camera
sees it, shows as a spectrum across the image's columns. The test traces the
same geometry on the host, wavelength by wavelength, with the extension's
index, and compares each channel's centroid.

wedge-plain.gltf: the same without dispersion (the control: every channel
at the index IOR).

broken/: one bad KHR_materials_dispersion value each.

    python3 scripts/make_dispersion_tests.py
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
from make_scenes import Quads, cross, mesh, normalize, sub  # noqa: E402
from gltf_writer import GltfWriter, write_texts  # noqa: E402

GENERATOR = "strata scripts/make_dispersion_tests.py"
COPYRIGHT = "CC0 1.0 (public domain), the strata authors"

CAMERA_Z, FRONT_Z, HALF = 10.0, 2.0, 3.0
APEX = math.radians(20.0)
IOR, DISPERSION = 1.5, 1.0
WIDTH, HEIGHT, HFOV = 128, 16, math.radians(2.4)
STRIP_Z = -30.0  # the strip: 2 pixels wide as seen from the camera, 4 units tall


def refract(d, n, eta):
    """d refracted through a surface of unit normal n (against d), eta = n_in / n_out."""
    c = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2])
    k = 1.0 - eta * eta * (1.0 - c * c)
    return tuple(eta * d[i] + (eta * c - math.sqrt(k)) * n[i] for i in range(3))


def strip_x():
    """Where the view's axis, refracted at IOR, reaches z = STRIP_Z: the
    strip's centre (it crosses the front face head-on and leaves the back
    face at the origin)."""
    t = refract((0.0, 0.0, -1.0), (math.sin(APEX), 0.0, math.cos(APEX)), IOR)
    return t[0] * STRIP_Z / t[2]


def face(q, p):
    """The quad p[0..3], counter-clockwise seen from its front."""
    base = len(q.positions)
    q.positions += p
    q.normals += [normalize(cross(sub(p[1], p[0]), sub(p[3], p[0])))] * 4
    q.indices += [base, base + 1, base + 2, base, base + 2, base + 3]


def wedge_scene(dispersion):
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    # The extension builds on KHR_materials_volume: a volume without attenuation.
    ext = {"KHR_materials_volume": {"thicknessFactor": 1.0}}
    if dispersion is not None:
        ext["KHR_materials_dispersion"] = {"dispersion": dispersion}
    glass = w.add_material("Glass", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0, ior=IOR,
                           transmission=1.0, extensions=ext)
    tb = math.tan(APEX)
    # The wedge's corners: front face z = FRONT_Z, back face z = -tan(APEX) x.
    def back(x, y):
        return (x, y, -tb * x)
    f = [(-HALF, -HALF, FRONT_Z), (HALF, -HALF, FRONT_Z), (HALF, HALF, FRONT_Z), (-HALF, HALF, FRONT_Z)]
    b = [back(-HALF, -HALF), back(HALF, -HALF), back(HALF, HALF), back(-HALF, HALF)]
    q = Quads()
    face(q, [f[0], f[1], f[2], f[3]])  # front, facing +Z
    face(q, [b[1], b[0], b[3], b[2]])  # back, facing away from the camera
    face(q, [f[1], b[1], b[2], f[2]])  # +X side
    face(q, [b[0], f[0], f[3], b[3]])  # -X side
    face(q, [f[3], f[2], b[2], b[3]])  # top
    face(q, [b[0], b[1], f[1], f[0]])  # bottom
    x = strip_x()
    strip_w = 2.0 * (HFOV / WIDTH) * (CAMERA_Z - STRIP_Z)
    lamp = Quads().add((x - 0.5 * strip_w, -2.0, STRIP_Z), (strip_w, 0.0, 0.0), (0.0, 4.0, 0.0), (0.0, 0.0, 1.0))
    glow = w.add_material("Strip", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                          emissive=[1.0, 1.0, 1.0], specular=0.0)
    aspect = WIDTH / HEIGHT
    yfov = 2.0 * math.atan(math.tan(0.5 * HFOV) / aspect)
    roots = [w.add_node("Wedge", mesh=mesh(w, "Wedge", q, glass)),
             w.add_node("Strip", mesh=mesh(w, "Strip", lamp, glow)),
             w.add_node("Camera", camera=w.add_perspective("Camera", yfov, znear=0.1, aspect_ratio=aspect),
                        translation=[0, 0, CAMERA_Z])]
    w.set_scene(roots, name="Scene")
    used = ["KHR_materials_ior", "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume"]
    if dispersion is not None:
        used.append("KHR_materials_dispersion")
    w.use_extensions(sorted(used))
    return w.gltf_text()


BROKEN = {
    "dispersion-negative.gltf": -0.5,
    "dispersion-string.gltf": "flint",
}


def main():
    out = os.path.join(HERE, "..", "tests", "data", "dispersion")
    scenes = {"wedge.gltf": wedge_scene(DISPERSION), "wedge-plain.gltf": wedge_scene(None)}
    for name, value in BROKEN.items():
        scenes[os.path.join("broken", name)] = wedge_scene(value)
    write_texts(out, scenes)


if __name__ == "__main__":
    main()
