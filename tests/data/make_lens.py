#!/usr/bin/env python3
"""Writes tests/data/lens/square.gltf, the scene of tests/test_lens.cpp: the
camera at the origin looks down -Z with yfov 2 atan(1/4) (tan of the half
angle 0.25); an emitting square of side 0.08 (radiance 1, black base
colour) faces it in the plane z = -4, centred on the view axis. Nothing
else: the background is black. Deterministic; Python 3 standard library
only. Our own data, CC0.
    python3 tests/data/make_lens.py
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))

from gltf_writer import GltfWriter  # noqa: E402


def main():
    w = GltfWriter("strata tests/data/make_lens.py", copyright="CC0 1.0 (public domain), the strata authors")
    lamp = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0, roughness=1, emissive=(1, 1, 1))
    h = 0.04
    pts = [(-h, -h, -4), (h, -h, -4), (h, h, -4), (-h, h, -4)]
    square = w.add_triangles("Square", pts, indices=[0, 1, 2, 0, 2, 3], material=lamp)
    cam = w.add_perspective("Camera", 2 * math.atan(0.25))
    w.set_scene([w.add_node("Square", mesh=square), w.add_node("Camera", camera=cam)])
    w.write_gltf(os.path.join(HERE, "lens", "square.gltf"))


if __name__ == "__main__":
    main()
