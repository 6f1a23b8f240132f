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

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tests", "data"))
from make_lights import add_sphere  # noqa: E402
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


def glass_sphere():
    """A faceted glass icosphere (level 3, flat facets: no normals), smooth,
    ior 1.5, white: under a uniform environment it vanishes (radiance 1 up
    to the depth cap). Camera at (0, 0, 3) looking down -Z."""
    w = writer()
    glass = w.add_material("Glass", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0,
                           transmission=1.0, ior=1.5)
    sphere = add_sphere(w, 3, glass, inward=False)
    roots = [w.add_node("Sphere", mesh=sphere),
             w.add_node("Camera", camera=camera(w, "Camera", 40.0), translation=[0, 0, 3])]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_ior", "KHR_materials_transmission"])
    return w.gltf_text()


def plate(roughness, view_degrees):
    """A 40 x 40 white GGX metal plate z = 0 facing +Z, seen at `view_degrees`
    from its normal by a camera 5 units away with a 2-degree field of view:
    under a uniform environment each pixel is the directional albedo E(mu)."""
    w = writer()
    metal = w.add_material("Metal", base_color=(1, 1, 1, 1), metallic=1.0, roughness=roughness)
    quad = Quads().add((-20, -20, 0), (40, 0, 0), (0, 40, 0), (0, 0, 1))
    t = math.radians(view_degrees)
    roots = [w.add_node("Plate", mesh=mesh(w, "Plate", quad, metal)),
             w.add_node("Camera", camera=camera(w, "Camera", 2.0),
                        translation=[0.0, -5.0 * math.sin(t), 5.0 * math.cos(t)],
                        rotation=rotation_x(t))]
    w.set_scene(roots, name="Scene")
    return w.gltf_text()


def metal(roughness):
    return lambda w: w.add_material("Mirror", base_color=(1, 1, 1, 1), metallic=1.0,
                                    roughness=roughness)


def black_gloss(w):
    """Smooth black dielectric: only Fresnel reflection (ior 1.5)."""
    return w.add_material("BlackGloss", base_color=(0, 0, 0, 1), metallic=0.0, roughness=0.0)


def unlit():
    """KHR_materials_unlit: a 4 x 4 quad at z = 0 of base colour UNLIT (and an
    emissive factor, which unlit ignores) fills the view of a camera at
    (0, 0, 2) looking down -Z (yfov 40 degrees), next to a point light and
    under a lit white floor; every pixel shows UNLIT exactly."""
    w = writer()
    flat = w.add_material("Flat", base_color=UNLIT + (1,), emissive=(5, 5, 5), unlit=True)
    white = w.add_material("White", base_color=(1, 1, 1, 1), metallic=0.0, roughness=1.0)
    lamp = w.add_light("Lamp", "point", intensity=10.0)
    quad = Quads().add((-2, -2, 0), (4, 0, 0), (0, 4, 0), (0, 0, 1))
    floor = Quads().add((-3, -2.5, -3), (0, 0, 6), (6, 0, 0), (0, 1, 0))
    roots = [
        w.add_node("Flat", mesh=mesh(w, "Flat", quad, flat)),
        w.add_node("Floor", mesh=mesh(w, "Floor", floor, white)),
        w.add_node("Lamp", light=lamp, translation=[0, 0, 1]),
        w.add_node("Camera", camera=camera(w, "Camera", 40.0), translation=[0, 0, 2]),
    ]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_unlit", "KHR_lights_punctual"])
    return w.gltf_text()


UNLIT = (0.2, 0.5, 0.9)


def volume_slab():
    """KHR_materials_volume: a closed 10 x 10 x 1 slab (z in [-0.5, 0.5]) of
    clear glass of ior 1 (no reflection, no bending), attenuation distance 2
    and colour VOLUME_COLOR, seen by a camera at (0, 0, 3) looking down -Z
    (yfov 1 degree) against the default white environment (no light in the
    file): every pixel shows VOLUME_COLOR^(1 / 2) to within 1e-4."""
    w = writer()
    glass = w.add_material("Tinted", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0, ior=1.0,
                           transmission=1.0, volume=(1.0, 2.0, VOLUME_COLOR))
    h, t = 5.0, 0.5
    box = Quads()
    box.add((-h, -h, t), (2 * h, 0, 0), (0, 2 * h, 0), (0, 0, 1))       # front, +Z
    box.add((-h, -h, -t), (0, 2 * h, 0), (2 * h, 0, 0), (0, 0, -1))     # back, -Z
    box.add((-h, -h, -t), (0, 0, 2 * t), (0, 2 * h, 0), (-1, 0, 0))     # -X
    box.add((h, -h, -t), (0, 2 * h, 0), (0, 0, 2 * t), (1, 0, 0))       # +X
    box.add((-h, -h, -t), (2 * h, 0, 0), (0, 0, 2 * t), (0, -1, 0))     # -Y
    box.add((-h, h, -t), (0, 0, 2 * t), (2 * h, 0, 0), (0, 1, 0))       # +Y
    roots = [w.add_node("Slab", mesh=mesh(w, "Slab", box, glass)),
             w.add_node("Camera", camera=camera(w, "Camera", 1.0), translation=[0, 0, 3])]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_ior", "KHR_materials_transmission", "KHR_materials_volume"])
    return w.gltf_text()


VOLUME_COLOR = (0.5, 0.25, 0.8)


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "materials")
    os.makedirs(out, exist_ok=True)
    scenes = {
        "mirror-r0.gltf": mirror_scene(metal(0.0)),
        "mirror-r1e-4.gltf": mirror_scene(metal(1e-4)),
        "black-gloss.gltf": mirror_scene(black_gloss),
        "glass-sphere.gltf": glass_sphere(),
        # alpha = roughness^2: 0.5 seen at mu = 1 and 0.5, 0.1 at mu = 1
        "plate-a0.5-mu1.gltf": plate(math.sqrt(0.5), 0.0),
        "plate-a0.5-mu0.5.gltf": plate(math.sqrt(0.5), 60.0),
        "plate-a0.1-mu1.gltf": plate(math.sqrt(0.1), 0.0),
        "unlit.gltf": unlit(),
        "volume-slab.gltf": volume_slab(),
    }
    for name, text in scenes.items():
        path = os.path.normpath(os.path.join(out, name))
        with open(path, "w") as f:
            f.write(text)
        print("wrote", path)


if __name__ == "__main__":
    main()
