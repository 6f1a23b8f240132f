#!/usr/bin/env python3
"""Writes scenes/cook-1984.gltf, our own scene after the idea of Cook,
Porter and Carpenter's "1984" (distributed ray tracing): billiard balls on
felt under one square lamp, two of them rolling. With --shutter and a lens it
shows the four effects of that paper in one image: soft shadows (the lamp's
area), glossy reflection (the balls' coat and the brushed metal wall),
depth of field (--lens-radius) and motion blur (the animation "break").
Our own work, CC0; Python 3 standard library only; deterministic.

    python3 scripts/make_cook1984.py            # rewrites scenes/cook-1984.gltf

The README's picture (lavapipe, 2 cores: 167 s):
    strata render scenes/cook-1984.gltf --shutter 0,1 --lens-radius 0.05 \\
        --focus-distance 4.33 --spp 256 --width 640 --height 400 --denoise -o cook-1984.png
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)

from make_scenes import write  # noqa: E402
from make_showcase import (Sphere, add_sphere_accessors, emitter, finish, look_at_rotation,  # noqa: E402
                           rect, sphere_mesh)
from gltf_writer import GltfWriter  # noqa: E402

R = 0.25  # ball radius
BALLS = (  # name, colour, resting centre (x, z)
    ("Yellow", (0.85, 0.62, 0.05), (0.0, 0.0)),
    ("Blue", (0.05, 0.12, 0.6), (0.55, -0.35)),
    ("Red", (0.7, 0.04, 0.03), (-0.45, -0.7)),
    ("Black", (0.015, 0.015, 0.015), (0.9, 0.45)),
)


def roll(start, end, t0, t1, steps):
    """Keys of a ball rolling without slipping from `start` to `end` (x, z)
    between t0 and t1: translation and rotation (about the horizontal axis
    perpendicular to the motion), `steps` intervals so that no key turns by
    more than 180 degrees (slerp takes the shorter arc)."""
    dx, dz = end[0] - start[0], end[1] - start[1]
    dist = math.hypot(dx, dz)
    axis = (dz / dist, 0.0, -dx / dist)  # up x direction: rolling forward
    times, trans, rots = [], [], []
    for k in range(steps + 1):
        f = k / steps
        times.append(t0 + (t1 - t0) * f)
        trans.append((start[0] + dx * f, R, start[1] + dz * f))
        a = dist * f / R
        s = math.sin(a / 2)
        rots.append((axis[0] * s, axis[1] * s, axis[2] * s, math.cos(a / 2)))
    return times, trans, rots


def main():
    w = GltfWriter("strata scripts/make_cook1984.py", copyright="CC0 1.0 (public domain), the strata authors")
    felt = w.add_material("Felt", base_color=(0.05, 0.3, 0.12, 1.0), metallic=0.0, roughness=1.0, specular=0.2)
    wall = w.add_material("BrushedSteel", base_color=(0.8, 0.8, 0.82, 1.0), metallic=1.0, roughness=0.3)
    lamp = emitter(w, "Lamp", 12.0)
    floor = rect((0.0, 0.0, 0.0), (1, 0, 0), (0, 0, -1), 4.0, 3.0)
    backdrop = rect((0.0, 1.5, -2.0), (1, 0, 0), (0, 1, 0), 4.0, 1.5)
    light = rect((0.3, 3.0, 0.5), (1, 0, 0), (0, 0, 1), 0.5, 0.5)
    nodes = []
    for name, quads, mat in (("Felt", floor, felt), ("Wall", backdrop, wall), ("Lamp", light, lamp)):
        m = w.add_triangles(name, quads.positions, normals=quads.normals, indices=quads.indices, material=mat)
        nodes.append(w.add_node(name, mesh=m))
    sphere = add_sphere_accessors(w, Sphere(48, 24))
    balls = {}
    for name, colour, (x, z) in BALLS + (("Cue", (0.9, 0.88, 0.8), (-1.6, 0.9)),):
        mat = w.add_material(name, base_color=list(colour) + [1.0], metallic=0.0, roughness=0.35,
                             extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0,
                                                                     "clearcoatRoughness": 0.03}})
        balls[name] = w.add_node(name, mesh=sphere_mesh(w, name, sphere, mat), translation=[x, R, z],
                                 scale=[R, R, R])
        nodes.append(balls[name])
    # "break": the cue ball rolls towards the yellow one, the black one away.
    channels = []
    for name, start, end in (("Cue", (-1.6, 0.9), (-0.75, 0.45)), ("Black", (0.9, 0.45), (1.25, 0.75))):
        times, trans, rots = roll(start, end, 0.0, 1.0, 4)
        channels.append((balls[name], "translation", "LINEAR", times, trans))
        channels.append((balls[name], "rotation", "LINEAR", times, rots))
    w.add_animation("break", channels)
    eye, target = (0.0, 1.3, 4.2), (0.0, R, 0.0)
    cam = w.add_perspective("Camera", math.radians(35.0), znear=0.01, aspect_ratio=1.6)
    nodes.append(w.add_node("Camera", camera=cam, translation=list(eye), rotation=look_at_rotation(eye, target)))
    write(os.path.join(ROOT, "scenes"), "cook-1984.gltf", finish(w, nodes))


if __name__ == "__main__":
    main()
