#!/usr/bin/env python3
"""Writes scenes/many-lights.gltf (issue 43): a closed, exactly Lambertian
room lit only by 256 small emissive quads of varied colour and strength,
for time-to-error comparisons with the Cycles peer
(scripts/time_to_error.py); Python 3 stdlib only, deterministic output,
our own work (CC0).

    python3 scripts/make_many_lights.py [OUTDIR]     default: scenes/

The room is x in [-3, 3], y in [0, 3], z in [-3, 3], six walls facing in
(closed: no light leaves, no background is seen). Every material is
Lambert (metallic 0, roughness 1, KHR_materials_specular factor 0), so
Cycles' `--material lambert` gives the same BRDF as strata's.

The lamps are 0.1 x 0.1 quads: 160 hang 0.15 below the ceiling (a 16 x 10
grid, facing down) and 48 stand 0.1 off each side wall (facing in). Their
materials are `doubleSided` and black: strata emits from both sides of a
doubleSided emitter, and Cycles always emits from both sides, so the two
renderers see the same lights (the backs light the ceiling and the side
walls). Sixteen lamp materials, four hues times four strengths from 0.4 to
12 (a factor of 30 in power), are dealt to the lamps by a fixed
pseudo-random permutation. Four Lambert boxes stand on the floor. The
camera is inside the room at (0, 1.4, 2.9), looking down -Z, pitched down
8 degrees, yfov 65 degrees.
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
sys.path.insert(0, HERE)

from gltf_writer import GltfWriter  # noqa: E402
from make_scenes import (Quads, box_faces, camera, lambert, mesh,  # noqa: E402
                         rotation_x, rotation_y, write)

GENERATOR = "strata scripts/make_many_lights.py"
COPYRIGHT = "CC0 1.0 (public domain), the strata authors"

HALF = 3.0          # room half-width and half-depth
HEIGHT = 3.0
LAMP = 0.1          # lamp side
CEILING_DROP = 0.15
WALL_GAP = 0.1
HUES = ((1.0, 0.85, 0.6), (0.6, 0.8, 1.0), (1.0, 0.45, 0.3), (0.55, 1.0, 0.6))
STRENGTHS = (0.4, 1.5, 4.5, 12.0)
BOXES = (  # name, centre on the floor (x, z), rotation about +Y (deg), size (x, y, z), colour
    ("BoxA", (-1.4, -1.2), 20.0, (0.9, 0.9, 0.9), (0.7, 0.7, 0.7)),
    ("BoxB", (1.3, -1.6), -25.0, (0.8, 1.8, 0.8), (0.6, 0.55, 0.45)),
    ("BoxC", (0.3, 0.2), 40.0, (0.6, 0.4, 0.6), (0.35, 0.5, 0.65)),
    ("BoxD", (-0.6, -2.3), -10.0, (1.4, 0.5, 0.5), (0.75, 0.3, 0.25)),
)


def room():
    """The six walls facing in: (name, quads, material name)."""
    h, y = HALF, HEIGHT
    return (
        ("Floor", Quads().add((-h, 0, -h), (0, 0, 2 * h), (2 * h, 0, 0), (0, 1, 0)), "Floor"),
        ("Ceiling", Quads().add((-h, y, -h), (2 * h, 0, 0), (0, 0, 2 * h), (0, -1, 0)), "White"),
        ("BackWall", Quads().add((-h, 0, -h), (2 * h, 0, 0), (0, y, 0), (0, 0, 1)), "White"),
        ("FrontWall", Quads().add((-h, 0, h), (0, y, 0), (2 * h, 0, 0), (0, 0, -1)), "White"),
        ("LeftWall", Quads().add((-h, 0, -h), (0, y, 0), (0, 0, 2 * h), (1, 0, 0)), "Warm"),
        ("RightWall", Quads().add((h, 0, -h), (0, 0, 2 * h), (0, y, 0), (-1, 0, 0)), "Cool"),
    )


def lamp_quads():
    """The 256 lamps' quads, in a fixed order."""
    lamps = []
    y = HEIGHT - CEILING_DROP
    for i in range(16):          # along x
        for k in range(10):      # along z
            x = -HALF + (i + 0.5) * (2 * HALF / 16) - LAMP / 2
            z = -HALF + (k + 0.5) * (2 * HALF / 10) - LAMP / 2
            lamps.append(Quads().add((x, y, z), (LAMP, 0, 0), (0, 0, LAMP), (0, -1, 0)))
    for side in (-1.0, 1.0):     # 4 rows of 12 on each side wall
        x = side * (HALF - WALL_GAP)
        for r in range(4):
            for k in range(12):
                y0 = 0.6 + r * 0.55 - LAMP / 2
                z = -HALF + (k + 0.5) * (2 * HALF / 12) - LAMP / 2
                u, v = (0, 0, LAMP), (0, LAMP, 0)
                if side < 0:
                    u, v = v, u
                lamps.append(Quads().add((x, y0, z), u, v, (-side, 0, 0)))
    return lamps


def dealt(count, kinds, seed=43):
    """A fixed pseudo-random assignment of `kinds` kinds to `count` lamps,
    each kind count / kinds times (a linear congruential shuffle)."""
    order = [i % kinds for i in range(count)]
    state = seed
    for i in range(count - 1, 0, -1):
        state = (state * 1103515245 + 12345) % 2 ** 31
        j = state % (i + 1)
        order[i], order[j] = order[j], order[i]
    return order


def merged(quads_list):
    out = Quads()
    for q in quads_list:
        for i in range(0, len(q.positions), 4):
            p = q.positions[i:i + 4]
            out.add(p[0], tuple(b - a for a, b in zip(p[0], p[1])),
                    tuple(b - a for a, b in zip(p[0], p[3])), q.normals[i])
    return out


def box_mesh():
    """Unit box x, z in [-0.5, 0.5], y in [0, 1], closed; front faces out."""
    cube = box_faces(inward=False)
    out = Quads()
    for i in range(0, len(cube.positions), 4):
        p = [(x * 0.5, y * 0.5 + 0.5, z * 0.5) for x, y, z in cube.positions[i:i + 4]]
        out.add(p[0], tuple(b - a for a, b in zip(p[0], p[1])),
                tuple(b - a for a, b in zip(p[0], p[3])), cube.normals[i])
    return out


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def many_lights():
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    mats = {
        "White": lambert(w, "White", (0.75, 0.75, 0.75)),
        "Floor": lambert(w, "Floor", (0.5, 0.45, 0.4)),
        "Warm": lambert(w, "Warm", (0.7, 0.5, 0.35)),
        "Cool": lambert(w, "Cool", (0.35, 0.5, 0.7)),
    }
    roots = [w.add_node(name, mesh=mesh(w, name, q, mats[m])) for name, q, m in room()]
    unit = box_mesh()
    for name, (x, z), deg, size, rgb in BOXES:
        m = mesh(w, name, unit, lambert(w, name, rgb))
        roots.append(w.add_node(name, mesh=m, translation=[x, 0.0, z], rotation=rotation_y(deg),
                                scale=list(size)))
    lamps = lamp_quads()
    kinds = [(hue, s) for s in STRENGTHS for hue in HUES]
    order = dealt(len(lamps), len(kinds))
    for kind, (hue, strength) in enumerate(kinds):
        mat = w.add_material("Lamp%d" % kind, base_color=[0.0, 0.0, 0.0, 1.0], metallic=0.0,
                             roughness=1.0, emissive=hue, strength=strength, specular=0.0,
                             double_sided=True)
        group = merged([q for q, k in zip(lamps, order) if k == kind])
        name = "Lamps%d" % kind
        # No NORMAL: flat quads get their geometric normal (glTF 3.7.2.1), and a
        # doubleSided emitter's sides both emit; it keeps the file small.
        m = w.add_triangles(name, group.positions, indices=group.indices, material=mat)
        roots.append(w.add_node(name, mesh=m))
    pitch = rotation_x(math.radians(-8.0))
    roots.append(w.add_node("Camera", camera=camera(w, "Camera", 65.0),
                            translation=[0.0, 1.4, HALF - 0.1],
                            rotation=quat_mul(rotation_y(0.0), pitch)))
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular"])
    return w.gltf_text(), len(lamps)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "scenes")
    text, lamps = many_lights()
    write(out, "many-lights.gltf", text)
    print("  %d lamps, %d bytes" % (lamps, len(text)))


if __name__ == "__main__":
    main()
