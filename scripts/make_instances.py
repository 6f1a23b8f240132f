#!/usr/bin/env python3
"""Scenes with instanced meshes (Python 3 stdlib only; our own, CC0).

    python3 scripts/make_instances.py
        writes tests/data/instancing/: instances.gltf (a mesh placed by nine
        nodes, one of them mirrored and one scaled unevenly, and by a node
        with EXT_mesh_gpu_instancing; a glossy mesh placed twice; a floor and
        a lamp that are not instanced), normal-mapped.gltf (a normal-mapped
        quad placed three times) and broken/*.gltf (one defect each)
    python3 scripts/make_instances.py --grid N OUT.glb
        a floor, a lamp and N x N instances of a small sphere on one node's
        EXT_mesh_gpu_instancing (N = 1000: a million instances), for
        `strata render --stats` and `strata bench`
    python3 scripts/make_instances.py --showcase OUT.gltf
        the README picture: 45 spheres under thin films, by instancing
    python3 scripts/make_instances.py --nodes N OUT.glb
        the same N x N sphere placements, one node each (no extension), for
        the line between flattening and instancing (docs/benchmarks.md)
"""

import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
sys.path.insert(0, HERE)

sys.path.insert(0, os.path.join(ROOT, "tests", "data"))

from gltf_writer import FLOAT, GltfWriter  # noqa: E402
from make_lights import icosphere  # noqa: E402
from make_texture_scenes import data_uri, png  # noqa: E402

GENERATOR = "strata scripts/make_instances.py"
COPYRIGHT = "CC0 1.0 (public domain), the strata authors"
EXTENSION = "EXT_mesh_gpu_instancing"
OUT = os.path.join(ROOT, "tests", "data", "instancing")


def sphere_mesh(level):
    """Unit icosphere (tests/data/make_lights.py) as (positions, normals, indices)."""
    verts, faces = icosphere(level)
    return verts, list(verts), [i for f in faces for i in f]


def quad(w, name, corner, u, v, material):
    """A one-sided quad, front face along cross(u, v)."""
    p = [corner, tuple(corner[k] + u[k] for k in range(3)),
         tuple(corner[k] + u[k] + v[k] for k in range(3)), tuple(corner[k] + v[k] for k in range(3))]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    ln = math.sqrt(sum(x * x for x in n))
    n = tuple(x / ln for x in n)
    return w.add_triangles(name, p, normals=[n] * 4, indices=[0, 1, 2, 0, 2, 3], material=material)


def rotation(axis, degrees):
    h = math.radians(degrees) / 2
    s = math.sin(h)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(h)]


def base_scene(w, extent, lamp_height, camera_from, lamp_triangle=False):
    """Floor, lamp and camera; returns their nodes and the sphere's mesh.
    lamp_triangle: a lamp of one triangle, so that the emitter list has one
    order however the BVH orders the triangles (the instanced and the
    flattened scene then pick the same light for the same random numbers)."""
    floor_mat = w.add_material("Floor", base_color=[0.6, 0.6, 0.6, 1.0], metallic=0.0, roughness=1.0, specular=0.0)
    lamp_mat = w.add_material("Lamp", base_color=[0.0, 0.0, 0.0, 1.0], metallic=0.0, roughness=1.0, specular=0.0,
                              emissive=[1.0, 1.0, 1.0], strength=8.0)
    rock = w.add_material("Rock", base_color=[0.8, 0.45, 0.2, 1.0], metallic=0.0, roughness=0.5)
    floor = quad(w, "Floor", (-extent, 0.0, extent), (2 * extent, 0.0, 0.0), (0.0, 0.0, -2 * extent), floor_mat)
    half = extent / 4
    lamp = quad(w, "Lamp", (-half, lamp_height, -half), (2 * half, 0.0, 0.0), (0.0, 0.0, 2 * half), lamp_mat)
    if lamp_triangle:
        w.doc["accessors"][w.doc["meshes"][lamp]["primitives"][0]["indices"]]["count"] = 3
    pos, nrm, idx = sphere_mesh(1)
    sphere = w.add_triangles("Sphere", pos, normals=nrm, indices=idx, material=rock)
    cam = w.add_perspective("Camera", math.radians(40.0), znear=0.01, aspect_ratio=4.0 / 3.0)
    x, y, z = camera_from
    pitch = -math.atan2(y, math.hypot(x, z))
    nodes = [w.add_node("Floor", mesh=floor), w.add_node("Lamp", mesh=lamp),
             w.add_node("Camera", camera=cam, translation=[x, y, z], rotation=[math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)])]
    return nodes, sphere


def add_instances(w, translations, rotations=None, scales=None):
    """The extension object of N instances (float accessors)."""
    attrs = {}
    for name, values, type_ in (("TRANSLATION", translations, "VEC3"), ("ROTATION", rotations, "VEC4"),
                                ("SCALE", scales, "VEC3")):
        if values is None:
            continue
        data = b"".join(struct.pack("<%df" % len(v), *v) for v in values)
        attrs[name] = w.add_accessor(w.add_view(data), FLOAT, len(values), type_)
    return {EXTENSION: {"attributes": attrs}}


def instances_scene():
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    roots, sphere = base_scene(w, 4.0, 3.0, (0.0, 2.4, 5.5), lamp_triangle=True)
    # Clearcoated: the layered path tracer's instanced variant.
    gloss = w.add_material("Gloss", base_color=[0.2, 0.3, 0.8, 1.0], metallic=0.0, roughness=0.6,
                           extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0,
                                                                   "clearcoatRoughnessFactor": 0.1}})
    pos, nrm, idx = sphere_mesh(2)
    glossy = w.add_triangles("GlossySphere", pos, normals=nrm, indices=idx, material=gloss)
    # Nine nodes: a grid, turned and scaled; node 4 mirrored, node 7 uneven.
    for i in range(9):
        x, z = (i % 3 - 1) * 1.6, (i // 3 - 1) * 1.6
        scale = [0.5, 0.5, 0.5]
        if i == 4:
            scale = [-0.5, 0.5, 0.5]
        if i == 7:
            scale = [0.8, 0.3, 0.4]
        roots.append(w.add_node("Rock%d" % i, mesh=sphere, translation=[x, scale[1], z],
                                rotation=rotation((0.0, 1.0, 0.0), 20.0 * i), scale=scale))
    # One node with EXT_mesh_gpu_instancing: a row of small spheres at the back, under a parent turned about Y.
    t = [(-3.0 + 0.75 * k, 0.2, 0.0) for k in range(9)]
    r = [rotation((1.0, 0.0, 0.0), 30.0 * k) for k in range(9)]
    s = [(0.2, 0.2 + 0.02 * k, 0.2) for k in range(9)]
    row = w.add_node("Row", mesh=sphere, translation=[0.0, 0.0, -2.6])
    w.doc["nodes"][row]["extensions"] = add_instances(w, t, r, s)
    roots.append(w.add_node("RowParent", children=[row], rotation=rotation((0.0, 1.0, 0.0), 8.0)))
    for k, x in enumerate((-1.0, 1.0)):
        roots.append(w.add_node("Glossy%d" % k, mesh=glossy, translation=[x, 0.45, 2.4], scale=[0.45, 0.45, 0.45]))
    w.set_scene(roots, name="Instances")
    w.use_extensions(["KHR_materials_clearcoat", "KHR_materials_emissive_strength", "KHR_materials_specular",
                      EXTENSION])
    return w


def normal_map_scene():
    """A normal-mapped quad (a 4 x 4 map of four tilts, tangents generated)
    placed three times: turned, mirrored, scaled unevenly; no lamp, so the
    default white environment lights it (the light samples do not depend on
    how the triangles are ordered)."""
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    roots, _ = base_scene(w, 4.0, 3.0, (0.0, 2.4, 5.5))
    roots = [r for r in roots if w.doc["nodes"][r]["name"] != "Lamp"]
    tilts = [(191, 128, 221, 255), (64, 128, 221, 255), (128, 191, 221, 255), (128, 64, 221, 255)]
    rows = [[tilts[(x // 2 + 2 * (y // 2)) % 4] for x in range(4)] for y in range(4)]
    w.doc["images"] = [{"uri": data_uri(png(rows))}]
    w.doc["samplers"] = [{"magFilter": 9728, "minFilter": 9728}]
    w.doc["textures"] = [{"source": 0, "sampler": 0}]
    bumpy = w.add_material("Bumpy", base_color=[0.7, 0.7, 0.7, 1.0], metallic=0.0, roughness=0.4)
    w.doc["materials"][bumpy]["normalTexture"] = {"index": 0}
    p = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
    pos = w.add_vec3([(x, y + 0.01, z) for x, y, z in p])
    nrm = w.add_vec3([(0, 1, 0)] * 4, with_bounds=False)
    uv = w.add_accessor(w.add_view(struct.pack("<8f", 0, 0, 1, 0, 1, 1, 0, 1)), FLOAT, 4, "VEC2")
    idx = w.add_indices([0, 2, 1, 0, 3, 2])
    quad = w.add_mesh("BumpyQuad", [w.primitive(pos, nrm, idx, bumpy, attributes={"TEXCOORD_0": uv})])
    roots.append(w.add_node("Bumpy0", mesh=quad, translation=[-2.0, 0.0, 0.0],
                            rotation=rotation((0.0, 1.0, 0.0), 30.0)))
    roots.append(w.add_node("Bumpy1", mesh=quad, translation=[0.5, 1.0, -1.0], scale=[-1.0, 1.0, 1.0],
                            rotation=rotation((1.0, 0.0, 0.0), 50.0)))
    roots.append(w.add_node("Bumpy2", mesh=quad, translation=[2.2, 0.3, 0.5], scale=[0.7, 1.0, 1.4],
                            rotation=rotation((0.0, 0.0, 1.0), -20.0)))
    w.set_scene(roots, name="NormalMapped")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular"])
    return w


def showcase_scene():
    """The README picture: a 9 x 5 grid of spheres placed by one node's
    EXT_mesh_gpu_instancing, each a metal or a dark dielectric under a thin
    film whose thickness grows along the rows (two meshes, one material each
    thickness), over a floor; no lamp (render it with --env)."""
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    roots, _ = base_scene(w, 8.0, 5.0, (0.0, 2.6, 6.0))
    roots = [r for r in roots if w.doc["nodes"][r]["name"] != "Lamp"]
    pos, nrm, idx = sphere_mesh(3)
    for row, thickness in enumerate((200.0, 300.0, 400.0, 500.0, 650.0)):
        film = {"iridescenceFactor": 1.0, "iridescenceIor": 1.35, "iridescenceThicknessMaximum": thickness}
        metal = w.add_material("FilmMetal%d" % row, base_color=[0.3, 0.3, 0.3, 1.0], metallic=1.0, roughness=0.1,
                               extensions={"KHR_materials_iridescence": film})
        dark = w.add_material("FilmDark%d" % row, base_color=[0.02, 0.02, 0.03, 1.0], metallic=0.0,
                              roughness=0.05, extensions={"KHR_materials_iridescence": film})
        for kind, material in (("Metal", metal), ("Dark", dark)):
            mesh = w.add_triangles("%sSphere%d" % (kind, row), pos, normals=nrm, indices=idx, material=material)
            cols = [c for c in range(9) if (c % 2 == 0) == (kind == "Metal")]
            t = [(-4.4 + 1.1 * c, 0.45, -3.0 + 1.2 * row) for c in cols]
            node = w.add_node("%s%d" % (kind, row), mesh=mesh)
            w.doc["nodes"][node]["extensions"] = add_instances(w, t, scales=[(0.45, 0.45, 0.45)] * len(t))
            roots.append(node)
    w.set_scene(roots, name="Showcase")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_materials_iridescence",
                      EXTENSION])
    return w


def broken(defect):
    """instances_scene's Row node with one defect."""
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    roots, sphere = base_scene(w, 4.0, 3.0, (0.0, 2.4, 5.5))
    t = [(k * 0.5, 0.2, 0.0) for k in range(4)]
    if defect == "count-mismatch":
        ext = add_instances(w, t, scales=[(0.2, 0.2, 0.2)] * 3)
    elif defect == "nan-translation":
        ext = add_instances(w, t[:3] + [(float("nan"), 0.0, 0.0)])
    elif defect == "no-attributes":
        ext = {EXTENSION: {"attributes": {}}}
    elif defect == "no-mesh":
        ext = add_instances(w, t)
    else:
        raise ValueError(defect)
    row = w.add_node("Row", mesh=None if defect == "no-mesh" else sphere)
    w.doc["nodes"][row]["extensions"] = ext
    roots.append(row)
    w.set_scene(roots, name="Broken")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular", EXTENSION])
    return w


def grid_scene(n, extension):
    """n x n spheres of radius 0.4 on a unit grid, by one node's extension or n*n nodes."""
    extent = n / 2 + 1
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    roots, sphere = base_scene(w, extent, max(4.0, n / 4), (0.0, n * 0.45 + 2.0, n * 0.75 + 3.0))
    coords = [((i % n) - (n - 1) / 2, 0.4, (i // n) - (n - 1) / 2) for i in range(n * n)]
    if extension:
        node = w.add_node("Spheres", mesh=sphere)
        w.doc["nodes"][node]["extensions"] = add_instances(w, coords, scales=[(0.4, 0.4, 0.4)] * len(coords))
        roots.append(node)
    else:
        for i, c in enumerate(coords):
            roots.append(w.add_node("S%d" % i, mesh=sphere, translation=list(c), scale=[0.4, 0.4, 0.4]))
    w.set_scene(roots, name="Grid")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular"] + ([EXTENSION] if extension else []))
    return w


def write_glb(w, path):
    text = w._json({"byteLength": len(w.blob)}).encode("utf-8")
    text += b" " * (-len(text) % 4)
    blob = bytes(w.blob) + b"\0" * (-len(w.blob) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, total))
        f.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<II", len(blob), 0x004E4942) + blob)
    print("wrote", path)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--showcase":
        showcase_scene().write_gltf(sys.argv[2])
        return
    if len(sys.argv) == 4 and sys.argv[1] in ("--grid", "--nodes"):
        write_glb(grid_scene(int(sys.argv[2]), sys.argv[1] == "--grid"), sys.argv[3])
        return
    os.makedirs(os.path.join(OUT, "broken"), exist_ok=True)
    path = os.path.join(OUT, "instances.gltf")
    instances_scene().write_gltf(path)
    print("wrote", path)
    path = os.path.join(OUT, "normal-mapped.gltf")
    normal_map_scene().write_gltf(path)
    print("wrote", path)
    for defect in ("count-mismatch", "nan-translation", "no-attributes", "no-mesh"):
        path = os.path.join(OUT, "broken", defect + ".gltf")
        broken(defect).write_gltf(path)
        print("wrote", path)


if __name__ == "__main__":
    main()
