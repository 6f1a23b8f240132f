#!/usr/bin/env python3
"""Writes tests/data/geometry/: primitive modes, sparse accessors,
KHR_mesh_quantization, TEXCOORD_n, COLOR_0, KHR_materials_variants and
KHR_texture_basisu for the loader (tests/test_gltf_geometry.cpp,
test_vertex_colors.cpp, test_variants.cpp, test_texture_formats.cpp).
tests/data/make_deform.py writes the morph targets and skins.

The valid files each have a camera and an emissive material, so `strata
render` draws them; geometry/broken/ holds one defect per file. The numbers
below are mirrored in tests/test_gltf_geometry.cpp; change both. Run from
anywhere:
    python3 tests/data/make_geometry.py
"""

import base64
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts")
sys.path.insert(0, SCRIPTS)

from gltf_writer import (BYTE, FLOAT, SHORT, UNSIGNED_BYTE, UNSIGNED_INT,  # noqa: E402
                         UNSIGNED_SHORT, GltfWriter, pack_vec3)
from make_texture_scenes import data_uri, png  # noqa: E402

OUT = os.path.join(HERE, "geometry")
BROKEN = os.path.join(OUT, "broken")

POINTS, LINES, LINE_LOOP, LINE_STRIP, TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN = range(7)
QUANTIZATION = "KHR_mesh_quantization"

# struct format and size of one component.
COMPONENT = {BYTE: ("b", 1), UNSIGNED_BYTE: ("B", 1), SHORT: ("h", 2),
             UNSIGNED_SHORT: ("H", 2), FLOAT: ("f", 4)}

# Non-indexed strip, front face +Z: triangles (0,1,2) (1,3,2) (2,3,4) (3,5,4).
STRIP = [(0, 1, 0), (0, 0, 0), (1, 1, 0), (1, 0, 0), (2, 1, 0), (2, 0, 0)]
# Non-indexed fan around FAN[0], front face +Z: (1,2,0) (2,3,0) (3,4,0).
FAN = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0)]
UP3 = (0, 3, 0)  # the indexed copy of a strip or fan is moved by this
TRIANGLE = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
# The most elements an accessor without bufferView may have in a file whose
# buffers hold fewer bytes (gltf_internal.h, kZeroAccessorFloor).
ZERO_LIMIT = 1 << 20

# POSITION values per component type (each triangle counter-clockwise in xy).
QUANTIZED_POSITIONS = {
    BYTE: [(-128, 0, 0), (127, 0, -127), (0, 64, 1)],
    UNSIGNED_BYTE: [(0, 0, 0), (255, 0, 0), (0, 128, 1)],
    SHORT: [(-32768, 0, 0), (32767, 0, -32767), (0, 16384, 1)],
    UNSIGNED_SHORT: [(0, 0, 0), (65535, 0, 0), (0, 32768, 1)],
}
# TEXCOORD_0 values per component type.
QUANTIZED_UVS = {
    BYTE: [(-128, 127), (0, 64), (-1, 1)],
    UNSIGNED_BYTE: [(0, 255), (128, 1), (255, 0)],
    SHORT: [(-32768, 32767), (16384, 0), (-1, 1)],
    UNSIGNED_SHORT: [(0, 65535), (32768, 1), (65535, 0)],
}
# NORMAL and TANGENT xyz (normalized); -128 and -32768 decode to -1 exactly.
QUANTIZED_NORMALS = {
    BYTE: [(-128, 0, 127), (0, 0, 127), (127, 0, 127)],
    SHORT: [(-32768, 0, 32767), (0, 0, 32767), (32767, 0, 32767)],
}
QUANTIZED_TANGENT_W = {BYTE: (127, -128, 127), SHORT: (32767, -32768, 32767)}


def moved(points, by):
    return [tuple(p[i] + by[i] for i in range(3)) for p in points]


def packed(values, component, per_element):
    """Elements of per_element components, each padded to 4 bytes (glTF 2.0
    3.6.2.4); returns (bytes, stride)."""
    fmt, size = COMPONENT[component]
    stride = -(-size * per_element // 4) * 4
    pad = stride - size * per_element
    data = b"".join(struct.pack("<" + fmt * per_element, *v) + b"\0" * pad for v in values)
    return data, stride


class File:
    """One output file: a writer, its root nodes (a camera first), an
    emissive material."""

    def __init__(self):
        self.w = GltfWriter("strata tests/data/make_geometry.py")
        self.roots = []
        self.glow = self.w.add_material("Glow", base_color=(0.5, 0.5, 0.5, 1), metallic=0,
                                        roughness=1, emissive=(1, 1, 1))
        cam = self.w.add_perspective("Camera", 0.9)
        self.roots.append(self.w.add_node("Camera", camera=cam, translation=[0.5, 1, 6]))

    def values(self, values, component, type_, normalized=False, with_bounds=False):
        """An accessor of the given integer or float values (4-byte aligned)."""
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[type_]
        rows = [v if isinstance(v, tuple) else (v,) for v in values]
        data, stride = packed(rows, component, n)
        view = self.w.add_view(data, stride=stride if stride != COMPONENT[component][1] * n
                               else None)
        lo = hi = None
        if with_bounds:
            lo = [min(r[i] for r in rows) for i in range(n)]
            hi = [max(r[i] for r in rows) for i in range(n)]
        return self.w.add_accessor(view, component, len(rows), type_, 0, lo, hi, normalized)

    def mesh(self, name, primitives, **node):
        mesh = self.w.add_mesh(name, primitives)
        self.roots.append(self.w.add_node(name, mesh=mesh, **node))
        return mesh

    def write(self, name, folder=OUT, extensions=()):
        if extensions:
            self.w.use_extensions(list(extensions), required=list(extensions))
        self.w.set_scene(self.roots)
        self.w.write_gltf(os.path.join(folder, name))


def modes():
    # strip.gltf: the strip non-indexed, then indexed (u8) over its vertices
    # stored in reverse order and moved by UP3, with one more index repeating
    # the last vertex: the fifth triangle (4, 5, 5) is degenerate and dropped.
    f = File()
    w = f.w
    reverse = list(reversed(moved(STRIP, UP3)))
    f.mesh("Strip", [
        w.primitive(w.add_vec3(STRIP), material=f.glow, mode=TRIANGLE_STRIP),
        w.primitive(w.add_vec3(reverse), indices=w.add_indices([5, 4, 3, 2, 1, 0, 0], UNSIGNED_BYTE),
                    material=f.glow, mode=TRIANGLE_STRIP)])
    f.write("strip.gltf")

    # fan.gltf: the fan non-indexed, then indexed (u16) over its vertices
    # stored as FAN[1], FAN[3], FAN[0], FAN[4], FAN[2] moved by UP3, with the
    # last index repeated: the fourth triangle (FAN[4], FAN[4], FAN[0]) is dropped.
    f = File()
    w = f.w
    order = [1, 3, 0, 4, 2]
    stored = [moved(FAN, UP3)[k] for k in order]
    indices = [order.index(k) for k in range(5)] + [order.index(4)]
    f.mesh("Fan", [
        w.primitive(w.add_vec3(FAN), material=f.glow, mode=TRIANGLE_FAN),
        w.primitive(w.add_vec3(stored), indices=w.add_indices(indices, UNSIGNED_SHORT),
                    material=f.glow, mode=TRIANGLE_FAN)])
    f.write("fan.gltf")

    # lines-and-triangles.gltf: mesh 0 "Tri" (one triangle); mesh 1 "Wire":
    # LINES, TRIANGLES (TRIANGLE at z = 1), POINTS, on two nodes (the second
    # moved by (3, 0, 0)); mesh 2 "Loop": LINE_LOOP, LINE_STRIP. 3 triangles,
    # 4 primitives skipped.
    f = File()
    w = f.w
    line = w.add_vec3([(0, 0, 0), (1, 1, 0), (1, 0, 0)])
    f.mesh("Tri", [w.primitive(w.add_vec3(TRIANGLE), material=f.glow)])
    wire = f.mesh("Wire", [
        w.primitive(line, indices=w.add_indices([0, 1, 1, 2]), mode=LINES),
        w.primitive(w.add_vec3(moved(TRIANGLE, (0, 0, 1))), material=f.glow),
        w.primitive(line, mode=POINTS)])
    f.roots.append(w.add_node("Wire again", mesh=wire, translation=[3, 0, 0]))
    f.mesh("Loop", [w.primitive(line, mode=LINE_LOOP), w.primitive(line, mode=LINE_STRIP)])
    f.write("lines-and-triangles.gltf")


def sparse():
    # sparse.gltf, three meshes:
    # "Base": QUAD with a bufferView, sparse u8 indices [1, 3] -> (2, 0, 0),
    #   (0, 3, 0); NORMAL (0, 0, 1) everywhere, sparse u16 index [2] -> (0, 1, 1);
    #   indices 0 1 2 0 2 3.
    # "Zeros": POSITION without bufferView, count 3, sparse u32 indices [1, 2]
    #   -> (1, 0, 0), (0, 1, 0); non-indexed; node moved by (5, 0, 0).
    # "Indices": QUAD moved by (10, 0, 0); u16 indices 0 1 2 0 1 2 with sparse
    #   u8 indices [4, 5] -> u16 2, 3: the triangles 0 1 2 and 0 2 3.
    # "IndexZeros": QUAD moved by (15, 0, 0); u16 indices without bufferView,
    #   count 3, sparse [1, 2] -> 1, 2: the triangle 0 1 2.
    f = File()
    w = f.w
    pos = w.add_accessor(w.add_view(pack_vec3(QUAD)), FLOAT, 4, "VEC3", 0, [0, 0, 0], [2, 3, 0],
                         sparse=w.sparse([1, 3], pack_vec3([(2, 0, 0), (0, 3, 0)])))
    nrm = w.add_accessor(w.add_view(pack_vec3([(0, 0, 1)] * 4)), FLOAT, 4, "VEC3",
                         sparse=w.sparse([2], pack_vec3([(0, 1, 1)]), UNSIGNED_SHORT))
    f.mesh("Base", [w.primitive(pos, nrm, w.add_indices([0, 1, 2, 0, 2, 3]), f.glow)])
    zeros = w.add_accessor(None, FLOAT, 3, "VEC3", 0, [0, 0, 0], [1, 1, 0],
                           sparse=w.sparse([1, 2], pack_vec3([(1, 0, 0), (0, 1, 0)]),
                                           UNSIGNED_INT))
    f.mesh("Zeros", [w.primitive(zeros, material=f.glow)], translation=[5, 0, 0])
    idx_view = w.add_view(struct.pack("<6H", 0, 1, 2, 0, 1, 2))
    idx = w.add_accessor(idx_view, UNSIGNED_SHORT, 6, "SCALAR",
                         sparse=w.sparse([4, 5], struct.pack("<2H", 2, 3)))
    f.mesh("Indices", [w.primitive(w.add_vec3(moved(QUAD, (10, 0, 0))), indices=idx,
                                   material=f.glow)])
    zero_idx = w.add_accessor(None, UNSIGNED_SHORT, 3, "SCALAR", sparse=w.sparse([1, 2], struct.pack("<2H", 1, 2)))
    f.mesh("IndexZeros", [w.primitive(w.add_vec3(moved(QUAD, (15, 0, 0))), indices=zero_idx,
                                      material=f.glow)])
    f.write("sparse.gltf")

    # zeros-limit.gltf: POSITION without bufferView of count ZERO_LIMIT (the
    # most a file with under ZERO_LIMIT buffer bytes may have), sparse u32
    # [1, 2] -> (1, 0, 0), (0, 1, 0); indices 0 1 2: one triangle.
    f = File()
    w = f.w
    zeros = w.add_accessor(None, FLOAT, ZERO_LIMIT, "VEC3", 0, [0, 0, 0], [1, 1, 0],
                           sparse=w.sparse([1, 2], pack_vec3([(1, 0, 0), (0, 1, 0)]), UNSIGNED_INT))
    f.mesh("Zeros", [w.primitive(zeros, indices=w.add_indices([0, 1, 2]), material=f.glow)])
    f.write("zeros-limit.gltf")


def quantized():
    # quantized-positions.gltf: one triangle per mesh with QUANTIZED_POSITIONS,
    # in the order BYTE, BYTE normalized, UNSIGNED_BYTE, ..., UNSIGNED_SHORT
    # normalized; a last node "Dequantized" draws the UNSIGNED_SHORT mesh
    # (not normalized) scaled by 0.5 and moved by (1, 2, 3).
    f = File()
    meshes = {}
    for component in (BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT):
        for normalized in (False, True):
            pos = f.values(QUANTIZED_POSITIONS[component], component, "VEC3", normalized, True)
            name = COMPONENT_NAME[component] + (" normalized" if normalized else "")
            meshes[(component, normalized)] = f.mesh(
                name, [f.w.primitive(pos, material=f.glow)])
    f.roots.append(f.w.add_node("Dequantized", mesh=meshes[(UNSIGNED_SHORT, False)],
                                scale=[0.5, 0.5, 0.5], translation=[1, 2, 3]))
    f.write("quantized-positions.gltf", extensions=[QUANTIZATION])

    # quantized-texcoords.gltf: TRIANGLE with TEXCOORD_0 of QUANTIZED_UVS, one
    # mesh per component type and normalized flag in the same order.
    f = File()
    pos = f.w.add_vec3(TRIANGLE)
    for component in (BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT):
        for normalized in (False, True):
            uv = f.values(QUANTIZED_UVS[component], component, "VEC2", normalized)
            name = COMPONENT_NAME[component] + (" normalized" if normalized else "")
            f.mesh(name, [f.w.primitive(pos, material=f.glow, attributes={"TEXCOORD_0": uv})])
    f.write("quantized-texcoords.gltf", extensions=[QUANTIZATION])

    # quantized-normals.gltf: TRIANGLE with NORMAL and TANGENT (xyz
    # QUANTIZED_NORMALS, w QUANTIZED_TANGENT_W), normalized BYTE, then
    # normalized SHORT; the material has a normal map (so tangents are kept)
    # and float TEXCOORD_0.
    f = File()
    w = f.w
    image = w._add("images", {"uri": data_uri(png([[(128, 128, 255)]]))})
    texture = w._add("textures", {"source": image})
    mapped = w._add("materials", {"name": "Mapped", "normalTexture": {"index": texture},
                                  "emissiveFactor": [1, 1, 1]})
    pos = w.add_vec3(TRIANGLE)
    uv = f.values([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)], FLOAT, "VEC2")
    for component in (BYTE, SHORT):
        nrm = f.values(QUANTIZED_NORMALS[component], component, "VEC3", True)
        tangents = [n + (t,) for n, t in zip(QUANTIZED_NORMALS[component],
                                               QUANTIZED_TANGENT_W[component])]
        tan = f.values(tangents, component, "VEC4", True)
        f.mesh(COMPONENT_NAME[component], [w.primitive(
            pos, nrm, material=mapped, attributes={"TEXCOORD_0": uv, "TANGENT": tan})])
    f.write("quantized-normals.gltf", extensions=[QUANTIZATION])


# TEXCOORD_0-3 of the triangles of texcoord-sets.gltf: set n of vertex k is
# (n + k / 4, 10 * n + k / 8), exact in float.
def set_uvs(n):
    return [(n + k / 4, 10 * n + k / 8) for k in range(3)]


def texture_material(w, name, slots, texture):
    """A material with an emissive factor of 1 and `slots`: {slot name:
    texCoord} (baseColorTexture, emissiveTexture) reading `texture`."""
    mat = {"name": name, "emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {}}
    for slot, tex_coord in slots.items():
        info = {"index": texture, "texCoord": tex_coord}
        if slot == "baseColorTexture":
            mat["pbrMetallicRoughness"][slot] = info
        else:
            mat[slot] = info
    return w._add("materials", mat)


def checker_texture(w):
    """A 2 x 2 RGB checker, NEAREST; returns the texture index."""
    image = w._add("images", {"uri": data_uri(png([[(255, 32, 0), (0, 128, 255)],
                                                    [(16, 255, 64), (255, 255, 255)]]))})
    sampler = w._add("samplers", {"magFilter": 9728, "minFilter": 9728})
    return w._add("textures", {"source": image, "sampler": sampler})


def texcoord_sets():
    # texcoord-sets.gltf: one TRIANGLE with TEXCOORD_0..3 (set_uvs) per
    # material: "Sets23" (baseColor reads 3, emissive 2), "Set3" (both 3),
    # "Sets01" (baseColor 1, emissive 0).
    f = File()
    w = f.w
    texture = checker_texture(w)
    pos = w.add_vec3(TRIANGLE)
    uvs = {f"TEXCOORD_{n}": f.values(set_uvs(n), FLOAT, "VEC2") for n in range(4)}
    for name, slots in (("Sets23", {"baseColorTexture": 3, "emissiveTexture": 2}),
                        ("Set3", {"baseColorTexture": 3, "emissiveTexture": 3}),
                        ("Sets01", {"baseColorTexture": 1, "emissiveTexture": 0})):
        material = texture_material(w, name, slots, texture)
        f.mesh(name, [w.primitive(pos, material=material, attributes=uvs)])
    f.write("texcoord-sets.gltf")

    # texcoord-2.gltf and its twin texcoord-0.gltf: a quad filling the view
    # with the checker as emissive texture, read through TEXCOORD_2 (TEXCOORD_0
    # holding other values) and through TEXCOORD_0: the same image.
    quad = [(-3, -2, 0), (4, -2, 0), (4, 4, 0), (-3, 4, 0)]
    uv = [(0, 1), (1, 1), (1, 0), (0, 0)]
    for name, set_ in (("texcoord-2.gltf", 2), ("texcoord-0.gltf", 0)):
        f = File()
        w = f.w
        material = texture_material(w, "Checker", {"emissiveTexture": set_}, checker_texture(w))
        attributes = {f"TEXCOORD_{set_}": f.values(uv, FLOAT, "VEC2")}
        if set_ != 0:
            attributes["TEXCOORD_0"] = f.values([(0.5, 0.5)] * 4, FLOAT, "VEC2")
        f.mesh("Quad", [w.primitive(w.add_vec3(quad), indices=w.add_indices([0, 1, 2, 0, 2, 3]),
                                    material=material, attributes=attributes)])
        f.write(name)


# COLOR_0 of colors.gltf's triangles (vertex k = 0, 1, 2), one per storage.
COLORS = [
    ("FLOAT VEC3", FLOAT, "VEC3", [(0.25, 0.5, 1.0), (0.0, 0.125, 0.75), (1.0, 1.0, 0.5)]),
    ("FLOAT VEC4", FLOAT, "VEC4", [(0.25, 0.5, 1.0, 0.5), (0.0, 0.125, 0.75, 0.0), (1.0, 1.0, 0.5, 1.0)]),
    ("UNSIGNED_BYTE VEC3", UNSIGNED_BYTE, "VEC3", [(0, 128, 255), (51, 102, 204), (255, 0, 1)]),
    ("UNSIGNED_BYTE VEC4", UNSIGNED_BYTE, "VEC4", [(0, 128, 255, 64), (51, 102, 204, 0), (255, 0, 1, 255)]),
    ("UNSIGNED_SHORT VEC4", UNSIGNED_SHORT, "VEC4",
     [(0, 32768, 65535, 16384), (13107, 26214, 52428, 0), (65535, 0, 1, 65535)]),
]

# The vertex colour quad of colors-unlit.gltf and colors-mask.gltf at z = 0,
# covering the camera's view: COLOR_0 of a point (x, y) is the affine
# QUAD_COLOR(x, y) (tests/test_vertex_colors.cpp mirrors it), so any
# interpolation over the two triangles gives it back.
COLOR_QUAD = [(-4, -3, 0), (5, -3, 0), (5, 5, 0), (-4, 5, 0)]


def quad_color(x, y):
    return (0.2 + 0.05 * (x + 4), 0.3 + 0.06 * (y + 3), 0.9 - 0.04 * (x + 4) - 0.03 * (y + 3), (x + 4) / 9)


def vertex_colors():
    # colors.gltf: TRIANGLE once per COLORS entry (normalized integers), then
    # once without COLOR_0.
    f = File()
    w = f.w
    pos = w.add_vec3(TRIANGLE)
    for name, component, type_, values in COLORS:
        color = f.values(values, component, type_, normalized=component != FLOAT)
        f.mesh(name, [w.primitive(pos, material=f.glow, attributes={"COLOR_0": color})])
    f.mesh("White", [w.primitive(pos, material=f.glow)])
    f.write("colors.gltf")

    # colors-unlit.gltf: the quad, unlit, baseColorFactor (0.5, 1, 0.8, 1);
    # colors-mask.gltf: the same, alphaMode MASK with cutoff 0.5 (COLOR_0's
    # alpha runs from 0 at x = -4 to 1 at x = 5).
    for name, mask in (("colors-unlit.gltf", False), ("colors-mask.gltf", True)):
        f = File()
        w = f.w
        material = w.add_material("Coloured", base_color=(0.5, 1, 0.8, 1), unlit=True,
                                  alpha_mode="MASK" if mask else None, alpha_cutoff=0.5 if mask else None)
        color = f.values([quad_color(x, y) for x, y, _ in COLOR_QUAD], FLOAT, "VEC4")
        f.mesh("Quad", [w.primitive(w.add_vec3(COLOR_QUAD), indices=w.add_indices([0, 1, 2, 0, 2, 3]),
                                    material=material, attributes={"COLOR_0": color})])
        f.write(name, extensions=["KHR_materials_unlit"])


# A KTX2 file's 12-byte identifier and zeros: never decoded (strata has no
# Basis Universal decoder), so its contents do not matter.
KTX2 = bytes([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A]) + bytes(68)


def basisu_file(name, folder, fallback, used, required=False):
    """A triangle with TEXCOORD_0 and a texture whose KHR_texture_basisu
    source is KTX2 (image 0), with the checker PNG as its `source`
    (image 1) when `fallback`; material 1 "Textured" reads it as
    emissiveTexture when `used`."""
    f = File()
    w = f.w
    ktx2 = w._add("images", {"uri": "data:application/octet-stream;base64," + base64.b64encode(KTX2).decode()})
    texture = {"extensions": {"KHR_texture_basisu": {"source": ktx2}}}
    if fallback:
        texture["source"] = w._add("images", {"uri": data_uri(png([[(255, 32, 0), (0, 128, 255)]]))})
    index = w._add("textures", texture)
    material = texture_material(w, "Textured", {"emissiveTexture": 0} if used else {}, index)
    f.mesh("Tri", [w.primitive(w.add_vec3(TRIANGLE), material=material,
                               attributes={"TEXCOORD_0": f.values(set_uvs(0), FLOAT, "VEC2")})])
    w.use_extensions(["KHR_texture_basisu"], required=["KHR_texture_basisu"] if required else ())
    f.write(name, folder)


VARIANTS = ["Christmas", "Ocean", "Plain"]


def variants_file(name, folder, edit=None):
    """KHR_materials_variants: unlit materials 1 "Red", 2 "Green", 3 "Blue";
    mesh "A" (Red) maps Christmas -> Green, Ocean -> Blue; mesh "B" (Green)
    maps Christmas and Ocean -> Red; Plain maps nothing."""
    f = File()
    w = f.w
    red, green, blue = (w.add_material(n, base_color=c, unlit=True)
                        for n, c in (("Red", (1, 0, 0, 1)), ("Green", (0, 1, 0, 1)), ("Blue", (0, 0, 1, 1))))
    pos = w.add_vec3(TRIANGLE)
    for mesh, material, mappings, x in (("A", red, [(green, [0]), (blue, [1])], 0),
                                        ("B", green, [(red, [0, 1])], 2)):
        prim = w.primitive(pos, material=material)
        prim["extensions"] = {"KHR_materials_variants": {
            "mappings": [{"material": m, "variants": v} for m, v in mappings]}}
        f.mesh(mesh, [prim], translation=[x, 0, 0])
    w.doc["extensions"] = {"KHR_materials_variants": {"variants": [{"name": n} for n in VARIANTS]}}
    if edit:
        edit(w.doc)
    w.use_extensions(["KHR_materials_unlit", "KHR_materials_variants"])
    w.set_scene(f.roots)
    w.write_gltf(os.path.join(folder, name))


COMPONENT_NAME = {BYTE: "BYTE", UNSIGNED_BYTE: "UNSIGNED_BYTE", SHORT: "SHORT",
                  UNSIGNED_SHORT: "UNSIGNED_SHORT", FLOAT: "FLOAT"}


def broken():
    """One defect each, in mesh 0 "Bad" (the scene has a camera and an
    emitter, so only the defect stops a render); tests/test_gltf_geometry.cpp
    lists the error each must give."""

    def bad(name, attributes=None, extensions=(), mode=None, indices=None, position=None):
        f = File()
        w = f.w
        pos = position(f) if position else w.add_vec3(TRIANGLE)
        idx = indices(f) if indices else None
        f.mesh("Bad", [w.primitive(pos, indices=idx, material=f.glow, mode=mode,
                                   attributes=attributes(f) if attributes else None)])
        f.write(name, BROKEN, extensions)

    def sparse_position(indices, count=None, index_type=UNSIGNED_BYTE, values=2, edit=None):
        def make(f):
            s = f.w.sparse(indices, pack_vec3([(1, 1, 1)] * values), index_type)
            if count is not None:
                s["count"] = count
            if edit:
                edit(f.w, s)
            return f.w.add_accessor(f.w.add_view(pack_vec3(TRIANGLE)), FLOAT, 3, "VEC3",
                                    sparse=s)
        return make

    bad("sparse-index-out-of-range.gltf", position=sparse_position([1, 3]))
    bad("sparse-not-increasing.gltf", position=sparse_position([1, 1]))
    bad("sparse-count.gltf", position=sparse_position([0, 1, 2, 2], values=4, count=4))

    def past_end(w, s):  # the two u8 indices start at the view's last byte
        s["indices"]["byteOffset"] = 1
    bad("sparse-indices-out-of-view.gltf", position=sparse_position([0, 1], edit=past_end))
    bad("sparse-values-out-of-view.gltf", position=sparse_position([0, 1], values=1))

    def float_indices(w, s):
        s["indices"]["componentType"] = FLOAT
    bad("sparse-index-type.gltf", position=sparse_position([0, 1], edit=float_indices))

    def missing_view(w, s):
        s["values"]["bufferView"] = 99
    bad("sparse-missing-view.gltf", position=sparse_position([0, 1], edit=missing_view))

    def negative_offset(w, s):
        s["indices"]["byteOffset"] = -4
    bad("sparse-negative-offset.gltf", position=sparse_position([0, 1], edit=negative_offset))

    bad("no-bufferview-count.gltf",
        position=lambda f: f.w.add_accessor(None, FLOAT, 1 << 32, "VEC3"))
    bad("sparse-zeros-count.gltf",
        position=lambda f: f.w.add_accessor(
            None, FLOAT, ZERO_LIMIT + 1, "VEC3",
            sparse=f.w.sparse([1, 2], pack_vec3([(1, 0, 0), (0, 1, 0)]), UNSIGNED_INT)))

    short_triangle = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    bad("quantized-undeclared.gltf",
        position=lambda f: f.values(short_triangle, SHORT, "VEC3", with_bounds=True))
    bad("quantized-position-vec2.gltf", extensions=[QUANTIZATION],
        position=lambda f: f.values([(0, 0), (1, 0), (0, 1)], SHORT, "VEC2"))
    bad("quantized-normal-ubyte.gltf", extensions=[QUANTIZATION],
        attributes=lambda f: {"NORMAL": f.values([(0, 0, 1)] * 3, UNSIGNED_BYTE, "VEC3")})
    bad("quantized-normal-unnormalized.gltf", extensions=[QUANTIZATION],
        attributes=lambda f: {"NORMAL": f.values([(0, 0, 127)] * 3, BYTE, "VEC3")})
    bad("quantized-texcoord-undeclared.gltf",
        attributes=lambda f: {"TEXCOORD_0": f.values([(0, 0), (1, 0), (0, 1)],
                                                     UNSIGNED_BYTE, "VEC2")})

    bad("strip-too-short.gltf", mode=TRIANGLE_STRIP,
        indices=lambda f: f.w.add_indices([0, 1], UNSIGNED_BYTE))
    bad("fan-index-out-of-range.gltf", mode=TRIANGLE_FAN,
        indices=lambda f: f.w.add_indices([0, 1, 2, 9], UNSIGNED_BYTE))
    bad("unknown-mode.gltf", mode=7)

    def textured(name, slots, sets):
        """mesh 0 "Bad": TRIANGLE with TEXCOORD_n for n in `sets`, its
        material 1 "Textured" reading `slots`."""
        f = File()
        w = f.w
        material = texture_material(w, "Textured", slots, checker_texture(w))
        uvs = {f"TEXCOORD_{n}": f.values(set_uvs(n), FLOAT, "VEC2") for n in sets}
        f.mesh("Bad", [w.primitive(w.add_vec3(TRIANGLE), material=material, attributes=uvs)])
        f.write(name, BROKEN)

    bad("color-unnormalized.gltf",
        attributes=lambda f: {"COLOR_0": f.values([(0, 0, 255)] * 3, UNSIGNED_BYTE, "VEC3")})
    bad("color-vec2.gltf", attributes=lambda f: {"COLOR_0": f.values([(0.5, 0.5)] * 3, FLOAT, "VEC2")})
    bad("color-count.gltf", attributes=lambda f: {"COLOR_0": f.values([(1.0, 1.0, 1.0)] * 2, FLOAT, "VEC3")})

    def mapping(key, value):
        def edit(doc):
            doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"][0][key] = value
        return edit
    variants_file("variants-bad-material.gltf", BROKEN, mapping("material", 9))
    variants_file("variants-bad-index.gltf", BROKEN, mapping("variants", [0, 5]))

    basisu_file("basisu-no-fallback.gltf", BROKEN, fallback=False, used=True)
    basisu_file("basisu-required.gltf", BROKEN, fallback=True, used=True, required=True)

    textured("texcoord-three-sets.gltf", {"baseColorTexture": 0, "emissiveTexture": 2,
                                          "normalTexture": 3}, range(4))
    textured("texcoord-negative.gltf", {"emissiveTexture": -1}, range(1))
    textured("texcoord-missing-set.gltf", {"emissiveTexture": 2}, range(2))


def main():
    os.makedirs(BROKEN, exist_ok=True)
    modes()
    sparse()
    quantized()
    texcoord_sets()
    vertex_colors()
    variants_file("variants.gltf", OUT)
    basisu_file("basisu-fallback.gltf", OUT, fallback=True, used=True)
    basisu_file("basisu-unused.gltf", OUT, fallback=False, used=False)
    broken()
    print("wrote", OUT)


if __name__ == "__main__":
    main()
