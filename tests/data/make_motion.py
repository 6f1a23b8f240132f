#!/usr/bin/env python3
"""Writes the scenes of tests/test_motion.cpp (motion blur from glTF
animations), our own data, CC0:

- motion/quad.gltf: the camera at the origin looks down -Z with yfov
  2 atan(1/16); an unlit white quad (x in [-0.25, 0.25], y in [-0.5, 0.5])
  stands at z = -4, so a 64x16 image spans x in [-1, 1] at its depth. Its
  animations: "slide" moves the quad from x = -0.5 to 0.5 over t in [0, 1]
  (LINEAR); "step" puts it at x = -0.5, then at x = 0.5 from t = 0.25
  (STEP); "pan" moves the camera from x = 0.5 to -0.5 instead (LINEAR);
  "lamp" brings the emitter from behind the camera to (0.5, 0, -3.9),
  facing it, beside the quad (the lamp and the unlit quad are both 1).
- motion/glow.gltf: quad.gltf's camera and quad, the quad emitting 1 (black,
  no specular layer) instead of unlit; "slide" as in quad.gltf.
- motion/lamp-plane.gltf: the plane y = 0 (x, z in [-3, 3], albedo 0.5,
  Lambertian: no specular layer) under a lamp, a 1 x 1 quad at y = 0.5
  facing down (one-sided, emitting 1, black), which "slide" moves from
  x = -1 to 1 over t in [0, 1] (LINEAR); the camera at (0, 5, 0) looks down
  with yfov 0.8.
- motion/bar.gltf: the same camera with yfov 2 atan(1/4) (a square image
  spans [-1, 1]^2 at z = -4); an unlit white bar (half length 0.8 along x,
  half width 0.05) at z = -4, which "spin" turns about the view axis from 0
  to 90 degrees over t in [0, 1] (LINEAR, slerp).

Both have a small emitter behind the camera, facing away, so the
background stays black. motion/bad-target.gltf, bad-times.gltf and
bad-quaternion.gltf have one broken animation each: a channel targeting a
missing node, key times not increasing, a rotation key of zero length. Deterministic; Python 3 standard library only.
    python3 tests/data/make_motion.py
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))

from gltf_writer import GltfWriter  # noqa: E402

CC0 = "CC0 1.0 (public domain), the strata authors"


def common(w, tan_half):
    """The unlit white material, the hidden lamp's node and the camera's node."""
    white = w.add_material("White", base_color=(1, 1, 1, 1), unlit=True)
    lamp_mat = w.add_material("Lamp", base_color=(0, 0, 0, 1), emissive=(1, 1, 1))
    lamp = w.add_triangles("Lamp", [(0, 0, 5), (0.1, 0, 5), (0, 0.1, 5)], material=lamp_mat)
    cam = w.add_perspective("Camera", 2 * math.atan(tan_half))
    w.use_extensions(["KHR_materials_unlit"])
    return white, w.add_node("Lamp", mesh=lamp), w.add_node("Camera", camera=cam)


def quad_node(w, white):
    """The white quad (x in [-0.25, 0.25], y in [-0.5, 0.5]) at z = -4."""
    pts = [(-0.25, -0.5, 0), (0.25, -0.5, 0), (0.25, 0.5, 0), (-0.25, 0.5, 0)]
    mesh = w.add_triangles("Quad", pts, indices=[0, 1, 2, 0, 2, 3], material=white)
    return w.add_node("Quad", mesh=mesh, translation=[0, 0, -4])


def quad():
    w = GltfWriter("strata tests/data/make_motion.py", copyright=CC0)
    white, lamp, camera = common(w, 1 / 16)
    q = quad_node(w, white)
    w.add_animation("slide", [(q, "translation", "LINEAR", [0, 1], [(-0.5, 0, -4), (0.5, 0, -4)])])
    w.add_animation("step", [(q, "translation", "STEP", [0, 0.25], [(-0.5, 0, -4), (0.5, 0, -4)])])
    w.add_animation("pan", [(camera, "translation", "LINEAR", [0, 1], [(0.5, 0, 0), (-0.5, 0, 0)])])
    w.add_animation("lamp", [(lamp, "translation", "LINEAR", [0, 1], [(0, 0, 0), (0.5, 0, -8.9)])])
    w.set_scene([q, camera, lamp])
    w.write_gltf(os.path.join(HERE, "motion", "quad.gltf"))


def glow():
    w = GltfWriter("strata tests/data/make_motion.py", copyright=CC0)
    white, lamp, camera = common(w, 1 / 16)
    glowing = w.add_material("Glow", base_color=(0, 0, 0, 1), metallic=0, emissive=(1, 1, 1), specular=0.0)
    pts = [(-0.25, -0.5, 0), (0.25, -0.5, 0), (0.25, 0.5, 0), (-0.25, 0.5, 0)]
    mesh = w.add_triangles("Quad", pts, indices=[0, 1, 2, 0, 2, 3], material=glowing)
    q = w.add_node("Quad", mesh=mesh, translation=[0, 0, -4])
    w.add_animation("slide", [(q, "translation", "LINEAR", [0, 1], [(-0.5, 0, -4), (0.5, 0, -4)])])
    w.use_extensions(["KHR_materials_unlit", "KHR_materials_specular"])
    w.set_scene([q, camera, lamp])
    w.write_gltf(os.path.join(HERE, "motion", "glow.gltf"))


def lamp_plane():
    w = GltfWriter("strata tests/data/make_motion.py", copyright=CC0)
    grey = w.add_material("Grey", base_color=(0.5, 0.5, 0.5, 1), metallic=0, roughness=1, specular=0.0)
    glowing = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0, emissive=(1, 1, 1), specular=0.0)
    h = 3.0
    plane = w.add_triangles("Plane", [(-h, 0, -h), (-h, 0, h), (h, 0, h), (h, 0, -h)], indices=[0, 1, 2, 0, 2, 3],
                            material=grey)
    a = 0.5
    lamp = w.add_triangles("Lamp", [(-a, 0, -a), (a, 0, -a), (a, 0, a), (-a, 0, a)], indices=[0, 1, 2, 0, 2, 3],
                           material=glowing)
    node = w.add_node("Lamp", mesh=lamp, translation=[0, 0.5, 0])
    cam = w.add_perspective("Camera", 0.8)
    down = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -90 deg about X: local -Z -> world -Y
    camera = w.add_node("Camera", camera=cam, translation=[0, 5, 0], rotation=down)
    w.add_animation("slide", [(node, "translation", "LINEAR", [0, 1], [(-1, 0.5, 0), (1, 0.5, 0)])])
    w.use_extensions(["KHR_materials_specular"])
    w.set_scene([w.add_node("Plane", mesh=plane), node, camera])
    w.write_gltf(os.path.join(HERE, "motion", "lamp-plane.gltf"))


def bar():
    w = GltfWriter("strata tests/data/make_motion.py", copyright=CC0)
    white, lamp, camera = common(w, 1 / 4)
    pts = [(-0.8, -0.05, 0), (0.8, -0.05, 0), (0.8, 0.05, 0), (-0.8, 0.05, 0)]
    mesh = w.add_triangles("Bar", pts, indices=[0, 1, 2, 0, 2, 3], material=white)
    b = w.add_node("Bar", mesh=mesh, translation=[0, 0, -4])
    s = math.sin(math.pi / 4)
    w.add_animation("spin", [(b, "rotation", "LINEAR", [0, 1], [(0, 0, 0, 1), (0, 0, s, s)])])
    w.set_scene([b, camera, lamp])
    w.write_gltf(os.path.join(HERE, "motion", "bar.gltf"))


def broken():
    """motion/bad-*.gltf: quad.gltf's scene with one broken animation each."""
    for name, channel in (
            ("bad-target", (99, "translation", "LINEAR", [0, 1], [(0, 0, -4), (1, 0, -4)])),
            ("bad-times", (None, "translation", "LINEAR", [0, 0.5, 0.5], [(0, 0, -4)] * 3)),
            ("bad-quaternion", (None, "rotation", "LINEAR", [0, 1], [(0, 0, 0, 1), (0, 0, 0, 0)]))):
        w = GltfWriter("strata tests/data/make_motion.py", copyright=CC0)
        white, lamp, camera = common(w, 1 / 16)
        q = quad_node(w, white)
        node = q if channel[0] is None else channel[0]
        w.add_animation("broken", [(node,) + channel[1:]])
        w.set_scene([q, camera, lamp])
        w.write_gltf(os.path.join(HERE, "motion", name + ".gltf"))


if __name__ == "__main__":
    quad()
    glow()
    lamp_plane()
    bar()
    broken()
