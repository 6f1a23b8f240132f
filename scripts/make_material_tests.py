#!/usr/bin/env python3
"""Known-answer scenes for the BSDF render tests (tests/test_materials.cpp),
written to tests/data/materials/. Our own work, CC0.

mirror-*.gltf: a 6 x 6 floor y = 0 of one material under a one-sided square
emitter (side 2 * LAMP_HALF, at height LAMP_HEIGHT, facing down, radiance
LAMP_LE), seen by a camera that looks at the emitter's mirror image. With
maxDepth 1 a pixel whose every reflected ray meets the emitter shows
LAMP_LE times the floor's specular reflectance at that angle, and one whose
reflected rays all miss shows 0.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_scenes import Quads, camera, mesh, rotation_x, writer  # noqa: E402

LAMP_HALF = 0.5
LAMP_HEIGHT = 1.0
LAMP_LE = 2.0
CAMERA = (0.0, 0.8, 2.5)


def mirror_scene(floor_material):
    w = writer()
    floor = floor_material(w)
    lamp = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                          emissive=(1.0, 1.0, 1.0), strength=LAMP_LE, specular=0.0)
    h, y = LAMP_HALF, LAMP_HEIGHT
    floor_quad = Quads().add((-3, 0, -3), (0, 0, 6), (6, 0, 0), (0, 1, 0))
    lamp_quad = Quads().add((-h, y, -h), (2 * h, 0, 0), (0, 0, 2 * h), (0, -1, 0))
    x, cy, cz = CAMERA
    pitch = -math.atan2(cy + y, cz)  # towards the mirror image (0, -y, 0)
    roots = [
        w.add_node("Floor", mesh=mesh(w, "Floor", floor_quad, floor)),
        w.add_node("Lamp", mesh=mesh(w, "Lamp", lamp_quad, lamp)),
        w.add_node("Camera", camera=camera(w, "Camera", 40.0), translation=list(CAMERA),
                   rotation=rotation_x(pitch)),
    ]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular"])
    return w.gltf_text()


def metal(roughness):
    return lambda w: w.add_material("Mirror", base_color=(1, 1, 1, 1), metallic=1.0,
                                    roughness=roughness)


def black_gloss(w):
    """Smooth black dielectric: only Fresnel reflection (ior 1.5)."""
    return w.add_material("BlackGloss", base_color=(0, 0, 0, 1), metallic=0.0, roughness=0.0)


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "materials")
    os.makedirs(out, exist_ok=True)
    scenes = {
        "mirror-r0.gltf": mirror_scene(metal(0.0)),
        "mirror-r1e-4.gltf": mirror_scene(metal(1e-4)),
        "black-gloss.gltf": mirror_scene(black_gloss),
    }
    for name, text in scenes.items():
        path = os.path.normpath(os.path.join(out, name))
        with open(path, "w") as f:
            f.write(text)
        print("wrote", path)


if __name__ == "__main__":
    main()
