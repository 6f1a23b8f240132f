#!/usr/bin/env python3
"""Writes the README's gallery scene of the newer glTF materials; Python 3
stdlib only. Our own work, CC0: every number below was chosen for this
project.

On the materials board's studio sweep: three brushed gold spheres
(KHR_materials_anisotropy, strength 0, 0.6 and 1 along their lines of
latitude), a paper lamp shade around a small bright lamp and a row of
paper screens lit from behind (KHR_materials_diffuse_transmission), a
ball of haze, a scattering medium behind an index-matched boundary
(KHR_materials_volume_scatter), and a cut gem of strongly dispersive glass
(KHR_materials_dispersion), under a softbox and a rim light.

    python3 scripts/make_material_gallery.py OUT.gltf
    strata render OUT.gltf -o gallery.png --width 640 --height 360 --spp 512 --light-sampler tree --max-depth 64
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "data"))

from make_scenes import cross, lambert, mesh, normalize, sub, writer  # noqa: E402
from make_showcase import (Sphere, add_sphere_accessors, emitter, finish, look_at_rotation,  # noqa: E402
                           rect, sphere_mesh, sphere_node, sweep, sweep_profile)

EYE, TARGET, YFOV = (0.0, 2.6, 7.2), (0.0, 0.7, 0.0), 32.0
GOLD = (1.0, 0.78, 0.34, 1.0)
BRUSHED = ((-2.6, 0.0), (-1.6, 0.6), (-0.6, 1.0))  # x, anisotropy strength
SPHERE_RADIUS = 0.45
SHADE = ((1.4, 0.0, 0.2), 0.45, 0.9)  # base centre, radius, height
SCREENS = (1.2, 2.0, 2.8)             # x of the paper screens behind the shade
CLOUD = ((0.45, 0.42, 1.45), 0.42)     # centre, radius
GEM = ((-1.15, 0.36, 2.0), 0.42)        # girdle centre (the culet on the floor), girdle radius


def brushed(w, name, strength):
    extensions = {"KHR_materials_anisotropy": {"anisotropyStrength": strength}} if strength > 0 else None
    return w.add_material(name, base_color=GOLD, metallic=1.0, roughness=0.25, extensions=extensions)


def paper(w, name, color, factor):
    return w.add_material(name, base_color=(0.92, 0.9, 0.85, 1.0), metallic=0.0, roughness=0.9, double_sided=True,
                          extensions={"KHR_materials_diffuse_transmission": {
                              "diffuseTransmissionFactor": factor, "diffuseTransmissionColorFactor": list(color)}})


def cloud(w):
    """A ball of warm haze (KHR_materials_volume_scatter): an index-matched
    boundary (ior 1, clear, smooth: light crosses it unchanged, and the
    scattering events' shadow rays see the lights through it) around a
    medium whose attenuation (colour 0.3 at 0.25 units: about 4 of optical
    depth across the ball) mostly scatters, forward."""
    return w.add_material("Cloud", base_color=(1.0, 1.0, 1.0, 1.0), metallic=0.0, roughness=0.0, ior=1.0,
                          transmission=1.0, volume=(0.8, 0.25, (0.3, 0.3, 0.3)),
                          extensions={"KHR_materials_volume_scatter": {
                              "multiscatterColor": [0.97, 0.85, 0.7], "scatterAnisotropy": 0.5}})


def gem_material(w):
    """Dense flint-like glass: ior 1.75, Abbe number 20 (dispersion 1),
    clear, a volume without attenuation."""
    return w.add_material("Gem", base_color=(1.0, 1.0, 1.0, 1.0), metallic=0.0, roughness=0.0, ior=1.75,
                          transmission=1.0, extensions={"KHR_materials_volume": {"thicknessFactor": 0.5},
                                                        "KHR_materials_dispersion": {"dispersion": 1.0}})


def gem(centre, radius, sides=8):
    """A simple brilliant: an octagonal table, a crown of quads down to the
    girdle, a pavilion of triangles down to the culet; flat facets (each
    triangle its own vertices and normal), closed, normals outward."""
    cx, cy, cz = centre
    table, crown, depth = 0.55 * radius, 0.35 * radius, cy

    def ring(r, y, turn=0.0):
        return [(cx + r * math.cos(2 * math.pi * (k + turn) / sides), y, cz - r * math.sin(2 * math.pi * (k + turn) / sides))
                for k in range(sides)]
    top, girdle = ring(table, cy + crown, 0.5), ring(radius, cy)
    apex, culet = (cx, cy + crown, cz), (cx, cy - depth, cz)
    tris = []
    for k in range(sides):
        n = (k + 1) % sides
        tris.append((apex, top[k], top[n]))
        tris += [(top[k], girdle[k], girdle[n]), (top[k], girdle[n], top[n])]
        tris.append((girdle[n], girdle[k], culet))
    points, normals = [], []
    for a, b, c in tris:
        normal = normalize(cross(sub(b, a), sub(c, a)))
        if sum((p - q) * m for p, q, m in zip(a, centre, normal)) < 0:  # face outward
            b, c, normal = c, b, tuple(-x for x in normal)
        points += [a, b, c]
        normals += [normal] * 3
    return points, normals, list(range(len(points)))


def cylinder(centre, radius, height, segments=48):
    """An open cylinder about +Y from `centre` up, normals outward."""
    points, normals, indices = [], [], []
    for j in range(segments + 1):
        phi = 2.0 * math.pi * (j % segments) / segments
        n = (math.cos(phi), 0.0, -math.sin(phi))
        for y in (0.0, height):
            points.append((centre[0] + radius * n[0], centre[1] + y, centre[2] + radius * n[2]))
            normals.append(n)
    for j in range(segments):
        a, b, c, d = 2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3
        indices += [a, c, b, b, c, d]
    return points, normals, indices


def gallery():
    w = writer()
    acc = add_sphere_accessors(w, Sphere(64, 32))
    roots = []
    for i, (x, strength) in enumerate(BRUSHED):
        name = f"Brushed{i}"
        roots.append(sphere_node(w, name, sphere_mesh(w, name, acc, brushed(w, name, strength)),
                                 (x, SPHERE_RADIUS, 0.6), SPHERE_RADIUS))
    centre, radius, height = SHADE
    pos, nrm, idx = cylinder(centre, radius, height)
    shade = paper(w, "Shade", (1.0, 0.78, 0.5), 0.75)
    roots.append(w.add_node("Shade", mesh=w.add_triangles("Shade", pos, nrm, idx, shade)))
    bulb = emitter(w, "Bulb", 10.0, (1.0, 0.85, 0.6))
    roots.append(sphere_node(w, "Bulb", sphere_mesh(w, "Bulb", add_sphere_accessors(w, Sphere(16, 8)), bulb),
                             (centre[0], centre[1] + 0.45, centre[2]), 0.16))
    for i, x in enumerate(SCREENS):
        screen = rect((x, 0.75, -1.2), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), 0.4, 0.75)
        material = paper(w, f"Screen{i}", ((0.5, 0.9, 0.3), (0.95, 0.6, 0.3), (0.4, 0.6, 1.0))[i], 0.9)
        roots.append(w.add_node(f"Screen{i}", mesh=mesh(w, f"Screen{i}", screen, material)))
    roots.append(sphere_node(w, "Cloud", sphere_mesh(w, "Cloud", acc, cloud(w)), CLOUD[0], CLOUD[1]))
    pos, nrm, idx = gem(*GEM)
    roots.append(w.add_node("Gem", mesh=w.add_triangles("Gem", pos, nrm, idx, gem_material(w))))
    ground = lambert(w, "Ground", (0.35, 0.35, 0.35))
    pos, nrm, idx = sweep(sweep_profile(front=9.0, floor_back=-3.0, radius=2.5, top=9.0), -12, 12)
    roots.append(w.add_node("Sweep", mesh=w.add_triangles("Sweep", pos, nrm, idx, ground)))
    # Key: a softbox above the camera side; back: a panel behind the screens.
    key_centre = (0.0, 5.0, 4.0)
    facing = normalize(sub((0.0, 0.0, 0.3), key_centre))
    right = (1.0, 0.0, 0.0)
    up = normalize(cross(facing, right))
    roots.append(w.add_node("Key", mesh=mesh(w, "Key", rect(key_centre, right, up, 2.4, 1.0), emitter(w, "Key", 8.0))))
    back = rect((2.0, 0.75, -1.6), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), 1.1, 0.6)  # faces +Z
    roots.append(w.add_node("Back", mesh=mesh(w, "Back", back, emitter(w, "Back", 4.0))))
    cam = w.add_perspective("Camera", math.radians(YFOV), znear=0.05, aspect_ratio=16 / 9)
    roots.append(w.add_node("Camera", camera=cam, translation=list(EYE), rotation=look_at_rotation(EYE, TARGET)))
    return finish(w, roots)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_material_gallery.py OUT.gltf")
    with open(sys.argv[1], "w") as f:
        f.write(gallery())


if __name__ == "__main__":
    main()
