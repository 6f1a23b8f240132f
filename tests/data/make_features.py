#!/usr/bin/env python3
"""Writes tests/data/features/: small valid glTF files, one per loader feature.

tests/test_gltf.cpp holds the expected values (worked out by hand in the
comments there). Run from anywhere:
    python3 tests/data/make_features.py
"""

import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts")  # gltf_writer.py
sys.path.insert(0, SCRIPTS)

from gltf_writer import (GltfWriter, FLOAT, UNSIGNED_BYTE, UNSIGNED_INT,  # noqa: E402
                         UNSIGNED_SHORT)

OUT = os.path.join(HERE, "features")

S45 = math.sqrt(0.5)
ROT_Y90 = [0.0, S45, 0.0, S45]          # quaternion (x, y, z, w): +90 deg about +Y
TRI = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]  # CCW seen from +Z
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
QUAD_INDICES = [0, 1, 2, 0, 2, 3]


def hierarchy():
    w = GltfWriter("strata tests/data/make_features.py")
    tri = w.add_triangles("Tri", TRI, normals=[(0, 0, 1)] * 3)
    slope = w.add_triangles("Slope", [(0, 0, 0), (1, 0, -1), (0, 1, 0)],
                            normals=[(S45, 0, S45)] * 3)
    # Child: matrix = translate(0, 0, 1) * scale(1, 2, 1), column-major.
    child = w.add_node("Child", mesh=tri,
                       matrix=[1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1])
    parent = w.add_node("Parent", children=[child], translation=[1, 2, 3],
                        rotation=ROT_Y90, scale=[2, 2, 2])
    moved = w.add_node("Moved", mesh=tri,
                       matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1])
    skew = w.add_node("Skew", mesh=slope, scale=[2, 1, 1])
    w.set_scene([parent, moved, skew])
    w.write_gltf(os.path.join(OUT, "hierarchy.gltf"))


def negative_scale():
    w = GltfWriter("strata tests/data/make_features.py")
    wall = [(1, 0, 0), (1, 1, 0), (1, 0, 1)]   # plane x = 1, CCW seen from +X
    lit = w.add_triangles("Wall", wall, normals=[(1, 0, 0)] * 3)
    bare = w.add_triangles("WallNoNormal", wall)
    inner = w.add_node("FlipY", mesh=lit, scale=[1, -1, 1])
    roots = [
        w.add_node("Original", mesh=lit),
        w.add_node("Mirror", mesh=lit, scale=[-1, 1, 1]),
        w.add_node("FlipX", children=[inner], scale=[-1, 1, 1]),
        w.add_node("MirrorNoNormal", mesh=bare, scale=[-1, 1, 1]),
    ]
    w.set_scene(roots)
    w.write_gltf(os.path.join(OUT, "negative-scale.gltf"))


def indices():
    """One mesh, four primitives: u8, u16, u32 indexed and non-indexed quads."""
    w = GltfWriter("strata tests/data/make_features.py")
    prims = []
    for k, ctype in enumerate([UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT]):
        pos = w.add_vec3([(x + 2 * k, y, z) for x, y, z in QUAD])
        prims.append(w.primitive(pos, indices=w.add_indices(QUAD_INDICES, ctype)))
    pos = w.add_vec3([(QUAD[i][0] + 6, QUAD[i][1], QUAD[i][2]) for i in QUAD_INDICES])
    prims.append(w.primitive(pos))
    mesh = w.add_mesh("Quads", prims)
    w.set_scene([w.add_node("Quads", mesh=mesh)])
    w.write_gltf(os.path.join(OUT, "indices.gltf"))


def stride():
    """Interleaved POSITION/NORMAL with byteStride 32 in a bufferView that
    starts 16 bytes into the buffer; u16 indices at accessor byteOffset 2."""
    w = GltfWriter("strata tests/data/make_features.py")
    w.add_view(b"\xee" * 16)  # filler: bufferView 0, unused
    points = [(0, 0, 0), (2, 0, 0), (0, 3, 0)]
    normals = [(0, 0, 1), (0, 1, 1), (1, 0, 1)]  # not unit: the loader normalises
    data = b"".join(b"\xaa" * 4 + struct.pack("<3f", *p) + struct.pack("<3f", *n) + b"\xbb" * 4
                    for p, n in zip(points, normals))
    view = w.add_view(data, stride=32)
    pos = w.add_accessor(view, FLOAT, 3, "VEC3", 4, [0, 0, 0], [2, 3, 0])
    nrm = w.add_accessor(view, FLOAT, 3, "VEC3", 16)
    ind_view = w.add_view(b"\xcc\xcc" + struct.pack("<3H", 0, 1, 2))
    ind = w.add_accessor(ind_view, UNSIGNED_SHORT, 3, "SCALAR", 2)
    mesh = w.add_mesh("Interleaved", [w.primitive(pos, nrm, ind)])
    w.set_scene([w.add_node("Interleaved", mesh=mesh)])
    w.write_gltf(os.path.join(OUT, "stride.gltf"))


def binary():
    """A complete scene (camera, emitter) as .glb, and the same bytes named .gltf."""
    w = GltfWriter("strata tests/data/make_features.py")
    light = w.add_material("Light", emissive=(1, 0.5, 0.25), strength=2.0)
    mesh = w.add_triangles("Tri", TRI, normals=[(0, 0, 1)] * 3, indices=[0, 1, 2],
                           material=light)
    cam = w.add_perspective("Camera", 0.6)
    w.set_scene([w.add_node("Tri", mesh=mesh),
                 w.add_node("Camera", camera=cam, translation=[0.25, 0.25, 4])])
    w.use_extensions(["KHR_materials_emissive_strength"])
    w.write_glb(os.path.join(OUT, "binary.glb"))
    w.write_glb(os.path.join(OUT, "binary-named-gltf.gltf"))


def cameras():
    """Cameras in node order (depth-first), not camera-array order."""
    w = GltfWriter("strata tests/data/make_features.py")
    second = w.add_perspective("Second", 0.5)
    first = w.add_perspective("First", 0.7)
    first_node = w.add_node("FirstCam", camera=first, translation=[1, 0, 0], rotation=ROT_Y90)
    rig = w.add_node("Rig", children=[first_node], translation=[0, 0, 5], scale=[3, 3, 3])
    # translate(0, 10, 0) * rotateX(-90 deg) * scale(2, 1, 0.5), column-major.
    second_node = w.add_node("SecondCam", camera=second,
                             matrix=[2, 0, 0, 0, 0, 0, -1, 0, 0, 0.5, 0, 0, 0, 10, 0, 1])
    w.set_scene([rig, second_node])
    w.write_gltf(os.path.join(OUT, "cameras.gltf"))


def materials():
    w = GltfWriter("strata tests/data/make_features.py")
    full = w.add_material("Full", base_color=(0.1, 0.2, 0.3, 0.4), metallic=0.25,
                          roughness=0.75, emissive=(0.5, 0.25, 1.0), strength=4.0, ior=1.33,
                          double_sided=True, alpha_mode="MASK", alpha_cutoff=0.3)
    blend = w.add_material("Blend", alpha_mode="BLEND")
    prims = []
    for k, mat in enumerate([full, blend, None]):
        pos = w.add_vec3([(x + 2 * k, y, z) for x, y, z in TRI])
        prims.append(w.primitive(pos, material=mat))
    mesh = w.add_mesh("Tris", prims)
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_ior"])
    w.set_scene([w.add_node("Tris", mesh=mesh)])
    w.write_gltf(os.path.join(OUT, "materials.gltf"))


def unknown_extension():
    """Unsupported extensions in extensionsUsed only: one warning, still loads."""
    w = GltfWriter("strata tests/data/make_features.py")
    light = w.add_material("Light", emissive=(1, 1, 1), strength=3.0)
    mesh = w.add_triangles("Tri", TRI, material=light)
    cam = w.add_perspective("Camera", 0.8)
    w.use_extensions(["EXT_strata_test_unknown", "KHR_materials_emissive_strength",
                      "EXT_lights_image_based"])
    w.set_scene([w.add_node("Tri", mesh=mesh),
                 w.add_node("Camera", camera=cam, translation=[0, 0, 3])])
    w.write_gltf(os.path.join(OUT, "unknown-extension.gltf"))


def main():
    os.makedirs(OUT, exist_ok=True)
    hierarchy()
    negative_scale()
    indices()
    stride()
    binary()
    cameras()
    materials()
    unknown_extension()
    print("wrote", OUT)


if __name__ == "__main__":
    main()
