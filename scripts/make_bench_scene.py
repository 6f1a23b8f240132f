#!/usr/bin/env python3
"""Writes a benchmark scene of about N triangles as .glb (our own, CC0):
a floor, a grid of bumpy spheres (baked into one mesh, so every triangle is
real geometry), an emissive quad above them and a camera looking down at
the field. Deterministic for given arguments. Not shipped: generate it on
demand, e.g.

    python3 scripts/make_bench_scene.py --triangles 100000 -o /tmp/spheres-100k.glb
"""

import argparse
import math
import os
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from gltf_writer import GltfWriter, UNSIGNED_INT  # noqa: E402


def sphere(cx, cz, radius, rings, segments, phase):
    """A bumpy UV sphere resting on y = 0: points and triangle indices."""
    pts, idx = [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments):
            ph = 2.0 * math.pi * j / segments
            bump = 1.0 + 0.08 * math.sin(5 * th + phase) * math.cos(7 * ph + phase)
            r = radius * bump
            pts.append((cx + r * math.sin(th) * math.cos(ph), radius + r * math.cos(th),
                        cz + r * math.sin(th) * math.sin(ph)))
    for i in range(rings):
        for j in range(segments):
            a = i * segments + j
            b = i * segments + (j + 1) % segments
            c = a + segments
            d = b + segments
            idx += [a, c, b, b, c, d]
    return pts, idx


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--triangles", type=int, default=100000)
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()

    grid = 10
    per_sphere = max(8, args.triangles // (grid * grid))
    segments = max(4, int(math.sqrt(per_sphere / 2)))
    rings = max(2, per_sphere // (2 * segments))
    points, indices = [], []
    for gx in range(grid):
        for gz in range(grid):
            p, i = sphere(gx - grid / 2 + 0.5, gz - grid / 2 + 0.5, 0.42, rings, segments, gx * 1.3 + gz * 0.7)
            base = len(points)
            points += p
            indices += [base + k for k in i]
    w = GltfWriter("strata scripts/make_bench_scene.py")
    grey = w.add_material("Grey", base_color=(0.6, 0.6, 0.6, 1), metallic=0, roughness=1)
    lamp = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0, roughness=1, emissive=(1, 1, 1))
    s = grid / 2 + 1
    floor = w.add_triangles("Floor", [(-s, 0, -s), (-s, 0, s), (s, 0, s), (s, 0, -s)], indices=[0, 1, 2, 0, 2, 3],
                            material=grey)
    field = w.add_triangles("Spheres", points, indices=indices, material=grey, index_type=UNSIGNED_INT)
    light = w.add_triangles("Lamp", [(-2, 6, -2), (2, 6, -2), (2, 6, 2), (-2, 6, 2)], indices=[0, 1, 2, 0, 2, 3],
                            material=lamp)
    cam = w.add_perspective("Camera", math.radians(50))
    # At (0, 7, 9) looking at the origin: rotation about +X by -atan(7/9).
    a = -math.atan2(7, 9) / 2
    nodes = [w.add_node("Floor", mesh=floor), w.add_node("Spheres", mesh=field), w.add_node("Lamp", mesh=light),
             w.add_node("Camera", camera=cam, translation=[0, 7, 9], rotation=[math.sin(a), 0, 0, math.cos(a)])]
    w.set_scene(nodes)
    w.write_glb(args.output)
    print("wrote", args.output, len(indices) // 3 + 4, "triangles")


if __name__ == "__main__":
    main()
