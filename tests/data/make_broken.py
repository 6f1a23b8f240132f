#!/usr/bin/env python3
"""Writes tests/data/broken/: one small glTF file per loader error case.

Each file is the same minimal valid scene (a floor, an emissive quad, a
camera) with exactly one defect; tests/test_gltf.cpp lists the key phrase
each error message must contain. Run from anywhere:
    python3 tests/data/make_broken.py
"""

import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts")  # gltf_writer.py
sys.path.insert(0, SCRIPTS)

from gltf_writer import GltfWriter  # noqa: E402

OUT = os.path.join(HERE, "broken")

FLOOR = [(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)]   # CCW seen from +Y
LIGHT = [(-0.25, 1, -0.25), (0.25, 1, -0.25), (0.25, 1, 0.25), (-0.25, 1, 0.25)]  # faces -Y
QUAD = [0, 1, 2, 0, 2, 3]


def scene(camera=True, light_points=LIGHT, light_indices=QUAD):
    """The valid base scene; returns (writer, list of root nodes)."""
    w = GltfWriter("strata tests/data/make_broken.py")
    white = w.add_material("White", base_color=(0.8, 0.8, 0.8, 1), metallic=0, roughness=1)
    light = w.add_material("Light", base_color=(0, 0, 0, 1), metallic=0, roughness=1,
                           emissive=(1, 1, 1))
    floor = w.add_triangles("Floor", FLOOR, indices=QUAD, material=white)
    lamp = w.add_triangles("Light", light_points, indices=light_indices, material=light)
    roots = [w.add_node("Floor", mesh=floor), w.add_node("Light", mesh=lamp)]
    if camera:
        cam = w.add_perspective("Camera", 0.7)
        roots.append(w.add_node("Camera", camera=cam, translation=[0, 0.5, 3]))
    return w, roots


def write(name, w, roots=None, **kwargs):
    if roots is not None:
        w.set_scene(roots)
    w.write_gltf(os.path.join(OUT, name), **kwargs)


def main():
    os.makedirs(OUT, exist_ok=True)

    # Parse failures.
    w, roots = scene()
    w.set_scene(roots)
    text = w.gltf_text()
    with open(os.path.join(OUT, "truncated-json.gltf"), "w", encoding="utf-8") as f:
        f.write(text[: len(text) // 2])
    glb = w.glb_bytes()
    with open(os.path.join(OUT, "truncated.glb"), "wb") as f:
        f.write(glb[: len(glb) // 2])
    with open(os.path.join(OUT, "not-binary.glb"), "w", encoding="utf-8") as f:
        f.write(text)
    # Not glTF at all: an empty file, and a Radiance HDR header under a .gltf name.
    open(os.path.join(OUT, "empty.gltf"), "wb").close()
    with open(os.path.join(OUT, "not-json.gltf"), "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x80\x80\x80")

    # The buffer names a .bin file that is not there.
    w, roots = scene()
    w.set_scene(roots)
    with open(os.path.join(OUT, "missing-bin.gltf"), "w", encoding="utf-8", newline="\n") as f:
        f.write(w.gltf_text(bin_uri="missing-bin.bin"))
    # The buffer names a directory (this one), or an empty file.
    with open(os.path.join(OUT, "buffer-uri-directory.gltf"), "w", encoding="utf-8", newline="\n") as f:
        f.write(w.gltf_text(bin_uri="."))
    with open(os.path.join(OUT, "buffer-uri-empty.gltf"), "w", encoding="utf-8", newline="\n") as f:
        f.write(w.gltf_text(bin_uri="empty.gltf"))

    # Accessor reads past the end of its bufferView.
    w, roots = scene()
    w.doc["accessors"][w.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]]["count"] = 100
    write("accessor-out-of-range.gltf", w, roots)

    # An unsupported extension (a warning) in a file that then fails: the
    # error line alone.
    w, roots = scene()
    w.use_extensions(["EXT_unknown_vendor_thing"])
    w.doc["accessors"][w.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]]["count"] = 100
    write("warned-then-broken.gltf", w, roots)

    # Index 7 into a 4-vertex primitive.
    w, roots = scene(light_indices=[0, 1, 2, 0, 2, 7])
    write("index-out-of-range.gltf", w, roots)

    # A NaN coordinate in POSITION (min/max cannot hold NaN: omitted).
    w, roots = scene()
    pos = w.add_accessor(
        w.add_view(struct.pack("<9f", 0, 0, 0, float("nan"), 0, 0, 0, 1, 0)),
        5126, 3, "VEC3")
    mesh = w.add_mesh("Bad", [w.primitive(pos, material=0)])
    roots.append(w.add_node("Bad", mesh=mesh))
    write("nan-position.gltf", w, roots)

    # The lamp's POSITION attribute is not an accessor index (tinygltf drops
    # the attribute and loads on).
    w, roots = scene()
    w.doc["meshes"][1]["primitives"][0]["attributes"]["POSITION"] = "0"
    write("attribute-not-an-index.gltf", w, roots)

    w, roots = scene()
    w.use_extensions(["EXT_lights_image_based"], required=["EXT_lights_image_based"])
    write("unsupported-required-extension.gltf", w, roots)

    # A zero-area emissive triangle next to a valid emitter: loads, warns,
    # counts one dropped emitter.
    w, roots = scene()
    sliver = w.add_triangles("Sliver", [(0, 0.5, 0), (1, 0.5, 0), (1, 0.5, 0)], material=1)
    roots.append(w.add_node("Sliver", mesh=sliver))
    write("zero-area-emitter.gltf", w, roots)

    # The only emitter has zero area (two triangles, both collinear).
    w, roots = scene(light_points=[(0, 1, 0), (1, 1, 0), (2, 1, 0), (0, 1, 0)])
    write("zero-area-only-emitter.gltf", w, roots)

    # The only mesh, 0 ("Cube"), is drawn as LINES: no triangle is left.
    # (Lines next to triangles are skipped with a warning: tests/data/geometry.)
    w = GltfWriter("strata tests/data/make_broken.py")
    pos = w.add_vec3([(0, 0, 0), (1, 0, 0)])
    cube = w.add_mesh("Cube", [w.primitive(pos, mode=1)])
    cam = w.add_perspective("Camera", 0.7)
    write("lines-mode.gltf", w, [w.add_node("Cube", mesh=cube),
                                 w.add_node("Camera", camera=cam, translation=[0, 0.5, 3])])

    # Node 1 ("Light") is a root and also the child of a "Group" root: two
    # parents (chains of such nodes multiply the instances exponentially).
    w, roots = scene()
    roots.append(w.add_node("Group", children=[roots[1]]))
    write("node-two-parents.gltf", w, roots)

    w, roots = scene(camera=False)
    cam = w.add_orthographic("Ortho")
    roots.append(w.add_node("Ortho", camera=cam, translation=[0, 0.5, 3]))
    write("orthographic-camera.gltf", w, roots)

    w, _ = scene()
    write("no-scenes.gltf", w)

    print("wrote", OUT)


if __name__ == "__main__":
    main()
