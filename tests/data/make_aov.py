#!/usr/bin/env python3
"""Writes tests/data/aov/walls.gltf, the scene of tests/test_aov.cpp: the
camera at the origin looks down -Z (yfov 0.7). The left half of the view is
a diffuse wall in the plane z = -3 facing +Z (base colour 0.2, 0.5, 0.8);
the right half, for x in [0, 0.6], a smooth mirror in the same plane (metal,
base colour 0.9, 0.6, 0.3), which shows a diffuse wall behind the camera in
the plane z = +3 facing -Z (base colour 0.3, 0.7, 0.2); beyond x = 0.6 the
background. Deterministic; Python 3 standard library only. Our own data, CC0.
    python3 tests/data/make_aov.py
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))

from gltf_writer import GltfWriter  # noqa: E402

GEN = "strata tests/data/make_aov.py"


def quad(w, name, x0, x1, z, facing, material):
    """The rectangle [x0, x1] x [-10, 10] in the plane z, facing +Z (facing > 0) or -Z."""
    pts = [(x0, -10, z), (x1, -10, z), (x1, 10, z), (x0, 10, z)]
    idx = [0, 1, 2, 0, 2, 3] if facing > 0 else [0, 2, 1, 0, 3, 2]
    n = (0, 0, 1 if facing > 0 else -1)
    return w.add_triangles(name, pts, normals=[n] * 4, indices=idx, material=material)


def main():
    w = GltfWriter(GEN, copyright="CC0 1.0 (public domain), the strata authors")
    front = w.add_material("Front", base_color=(0.2, 0.5, 0.8, 1), metallic=0, roughness=1, specular=0.0)
    mirror = w.add_material("Mirror", base_color=(0.9, 0.6, 0.3, 1), metallic=1, roughness=0)
    back = w.add_material("Back", base_color=(0.3, 0.7, 0.2, 1), metallic=0, roughness=1, specular=0.0)
    nodes = [w.add_node("Front", mesh=quad(w, "Front", -10, 0, -3, 1, front)),
             w.add_node("Mirror", mesh=quad(w, "Mirror", 0, 0.6, -3, 1, mirror)),
             w.add_node("Back", mesh=quad(w, "Back", -10, 10, 3, -1, back)),
             w.add_node("Camera", camera=w.add_perspective("Camera", 0.7))]
    w.use_extensions(["KHR_materials_specular"])
    w.set_scene(nodes)
    w.write_gltf(os.path.join(HERE, "aov", "walls.gltf"))


if __name__ == "__main__":
    main()
