#!/usr/bin/env python3
"""Writes tests/data/deform/: morph targets and skins, each posed mesh next
to its twin authored already posed, and deform/broken/ with one defect per
file (tests/test_gltf_deform.cpp). Uses make_geometry.py's File. Run from
anywhere:
    python3 tests/data/make_deform.py
"""

import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
sys.path.insert(0, HERE)

from make_geometry import (File, QUAD, TRIANGLE, data_uri, png)  # noqa: E402
from gltf_writer import (FLOAT, SHORT, UNSIGNED_BYTE, UNSIGNED_SHORT, f32, pack_vec3)  # noqa: E402

DEFORM = os.path.join(HERE, "deform")
DEFORM_BROKEN = os.path.join(DEFORM, "broken")


# morph.gltf: a quad with NORMAL, TANGENT and TEXCOORD_0 (for its normal
# map) and two targets; MORPH_WEIGHTS: the mesh's, then a node's own.
MORPH_NORMALS = [(0, 0, 1), (0.6, 0, 0.8), (0, 0.6, 0.8), (0, 0, 1)]
MORPH_TANGENTS = [(1, 0, 0, 1), (0.8, 0, -0.6, 1), (1, 0, 0, -1), (1, 0, 0, 1)]
MORPH_TARGETS = [
    {"POSITION": [(0, 0, 0.5), (0.25, 0, 0), (0, -0.5, 1), (0.125, 0.125, 0)],
     "NORMAL": [(0.5, 0, 0), (0, 0, 0), (0, 0.25, 0), (-0.5, 0, 0)],
     "TANGENT": [(0, 0.5, 0), (0, 0, 0), (0.25, 0, 0), (0, 0, 0.5)]},
    # POSITION only, sparse over zeros: vertex 2 moves by (1, 1, -1).
    {"POSITION": [(0, 0, 0), (0, 0, 0), (1, 1, -1), (0, 0, 0)]},
]
MORPH_WEIGHTS = [(0.5, 0.25), (1.0, -0.5)]


def morphed(base, weights, key):
    """base (3 or 4 numbers per vertex) plus sum_i weights[i] *
    MORPH_TARGETS[i]'s `key` displacement (xyz), in double, as the loader
    adds them."""
    out = []
    for v, b in enumerate(base):
        x = [f32(c) for c in b]
        for w, t in zip(weights, MORPH_TARGETS):
            if key in t:
                for c in range(3):
                    x[c] += w * f32(t[key][v][c])
        out.append(tuple(x))
    return out


def morph():
    # Mesh "Morphed" (weights MORPH_WEIGHTS[0]) on node "Mesh weights" and, at
    # x + 3, on node "Own weights" (MORPH_WEIGHTS[1]); mesh "Posed0" and
    # "Posed1": the same quad authored already posed by each, at x + 10 and
    # x + 13. Target 1's POSITION is a sparse accessor without bufferView.
    f = File()
    w = f.w
    image = w._add("images", {"uri": data_uri(png([[(128, 128, 255)]]))})
    mapped = w._add("materials", {"name": "Mapped", "emissiveFactor": [1, 1, 1],
                                  "normalTexture": {"index": w._add("textures", {"source": image})}})
    uv = f.values([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)], FLOAT, "VEC2")
    indices = w.add_indices([0, 1, 2, 0, 2, 3])

    def quad(positions, normals, tangents, targets=None):
        prim = w.primitive(w.add_vec3(positions), w.add_vec3(normals, with_bounds=False), indices, mapped,
                           attributes={"TEXCOORD_0": uv, "TANGENT": f.values(tangents, FLOAT, "VEC4")})
        if targets:
            prim["targets"] = targets
        return prim

    t0 = MORPH_TARGETS[0]
    targets = [{key: w.add_vec3(t0[key], with_bounds=key == "POSITION") for key in t0},
               {"POSITION": w.add_accessor(None, FLOAT, 4, "VEC3", 0, [0, 0, 0], [1, 1, 0],
                                           sparse=w.sparse([2], pack_vec3([(1, 1, -1)])))}]
    mesh = w._add("meshes", {"name": "Morphed", "weights": list(MORPH_WEIGHTS[0]),
                             "primitives": [quad(QUAD, MORPH_NORMALS, MORPH_TANGENTS, targets)]})
    f.roots.append(w.add_node("Mesh weights", mesh=mesh))
    f.roots.append(w.add_node("Own weights", mesh=mesh, weights=list(MORPH_WEIGHTS[1]), translation=[3, 0, 0]))
    for i, weights in enumerate(MORPH_WEIGHTS):
        posed = quad(morphed(QUAD, weights, "POSITION"), morphed(MORPH_NORMALS, weights, "NORMAL"),
                     morphed(MORPH_TANGENTS, weights, "TANGENT"))
        f.mesh(f"Posed{i}", [posed], translation=[10 + 3 * i, 0, 0])
    f.write("morph.gltf", DEFORM)


# Small 4 x 4 matrix helpers (row-major lists) for the skin's twin.
def mat_mul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


def trs(t=(0, 0, 0), angle_z=0.0, s=(1, 1, 1)):
    """T * R_z(angle_z degrees) * S, as the loader builds a node's matrix."""
    c, n = math.cos(math.radians(angle_z)), math.sin(math.radians(angle_z))
    return [[c * s[0], -n * s[1], 0, t[0]], [n * s[0], c * s[1], 0, t[1]], [0, 0, s[2], t[2]], [0, 0, 0, 1]]


def z_quaternion(angle_z):
    h = math.radians(angle_z) / 2
    return [0, 0, math.sin(h), math.cos(h)]


def inverse3(m):
    """Inverse of the upper-left 3 x 3 of m."""
    a = [row[:3] for row in m[:3]]
    cof = [[a[(r + 1) % 3][(c + 1) % 3] * a[(r + 2) % 3][(c + 2) % 3] -
            a[(r + 1) % 3][(c + 2) % 3] * a[(r + 2) % 3][(c + 1) % 3] for c in range(3)] for r in range(3)]
    det = sum(a[0][c] * cof[0][c] for c in range(3))
    return [[cof[c][r] / det for c in range(3)] for r in range(3)]


def apply(m, v, w):
    """m (4 x 4) times (v, w), xyz."""
    return [sum(m[r][c] * v[c] for c in range(3)) + m[r][3] * w for r in range(3)]


# skin.gltf: a bar of 8 vertices at x = +-0.25, y = 0..3, on three joints
# (Hip, Knee, Foot under a node "Rig" at x + 0.5); bound at the joints'
# translations only (inverseBindMatrices: their inverses), posed with Hip
# turned 20 degrees, Knee -40 degrees and scaled 1.5 along x.
SKIN_BAR = [(x, y, 0) for y in range(4) for x in (-0.25, 0.25)]
SKIN_NODES = {"Rig": trs((0.5, 0, 0)), "Hip": trs(angle_z=20), "Knee": trs((0, 1.5, 0), -40, (1.5, 1, 1)),
              "Foot": trs((0, 1.5, 0))}
SKIN_BIND = [(0.5, 0, 0), (0.5, 1.5, 0), (0.5, 3, 0)]
# Tilted normals (a scaled joint maps them otherwise than its tangents).
SKIN_NORMALS = [(0.6 * x * 4, 0, 0.8) for x, _, _ in SKIN_BAR]
# Per row y = 0..3: set 0 (joints, float weights), set 1 (joints, u16
# weights). Row 3's weights sum to 0.98 (renormalized with a warning).
SKIN_ROWS = [
    ((0, 0, 0, 0), (1.0, 0, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0)),
    ((0, 1, 0, 0), (0.75, 0.25, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0)),
    ((0, 1, 0, 0), (0.2, 0.6, 0, 0), (2, 0, 0, 0), (13107, 0, 0, 0)),
    ((1, 2, 0, 0), (0.49, 0.49, 0, 0), (0, 0, 0, 0), (0, 0, 0, 0)),
]


def skin_file(name, folder, edit=None):
    """skin.gltf's scene; `edit(f, accessors)` changes it for a broken file."""
    f = File()
    w = f.w
    image = w._add("images", {"uri": data_uri(png([[(128, 128, 255)]]))})
    mapped = w._add("materials", {"name": "Mapped", "emissiveFactor": [1, 1, 1],
                                  "normalTexture": {"index": w._add("textures", {"source": image})}})
    uv = f.values([((x + 0.25) * 2, y / 3) for x, y, _ in SKIN_BAR], FLOAT, "VEC2")
    indices = w.add_indices([i for r in range(3) for i in (2 * r, 2 * r + 1, 2 * r + 3, 2 * r, 2 * r + 3, 2 * r + 2)])
    rows = [SKIN_ROWS[v // 2] for v in range(8)]
    acc = {"joints0": f.values([r[0] for r in rows], UNSIGNED_BYTE, "VEC4"),
           "weights0": f.values([r[1] for r in rows], FLOAT, "VEC4"),
           "joints1": f.values([r[2] for r in rows], UNSIGNED_SHORT, "VEC4"),
           "weights1": f.values([r[3] for r in rows], UNSIGNED_SHORT, "VEC4", normalized=True)}
    ibm = b"".join(struct.pack("<16f", *[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -t[0], -t[1], -t[2], 1])
                   for t in SKIN_BIND)
    acc["ibm"] = w.add_accessor(w.add_view(ibm), FLOAT, 3, "MAT4")
    attributes = {"TEXCOORD_0": uv, "TANGENT": f.values([(1, 0, 0, 1)] * 8, FLOAT, "VEC4"),
                  "JOINTS_0": acc["joints0"], "WEIGHTS_0": acc["weights0"],
                  "JOINTS_1": acc["joints1"], "WEIGHTS_1": acc["weights1"]}
    normals = w.add_vec3(SKIN_NORMALS, with_bounds=False)
    mesh = w.add_mesh("Bar", [w.primitive(w.add_vec3(SKIN_BAR), normals, indices, mapped, attributes=attributes)])
    foot = w.add_node("Foot", translation=[0, 1.5, 0])
    knee = w.add_node("Knee", translation=[0, 1.5, 0], rotation=z_quaternion(-40), scale=[1.5, 1, 1], children=[foot])
    hip = w.add_node("Hip", rotation=z_quaternion(20), children=[knee])
    f.roots.append(w.add_node("Rig", translation=[0.5, 0, 0], children=[hip]))
    w.doc["skins"] = [{"name": "Legs", "joints": [hip, knee, foot], "inverseBindMatrices": acc["ibm"]}]
    skinned = w.add_node("Skinned", mesh=mesh, skin=0, translation=[100, 0, 0])
    f.roots.append(w.add_node("Ignored", translation=[50, 0, 0], scale=[2, 2, 2], children=[skinned]))
    if edit:
        edit(f, w.doc["meshes"][mesh]["primitives"][0]["attributes"], w.doc["skins"][0])
        f.write(name, folder)
    return f, mesh, normals, indices, mapped, uv


def skin():
    # skin.gltf: the skinned bar, then its twin authored posed at x + 10.
    f, mesh, normals, indices, mapped, uv = skin_file("skin.gltf", DEFORM)
    w = f.w
    world = {}
    world["Rig"] = SKIN_NODES["Rig"]
    world["Hip"] = mat_mul(world["Rig"], SKIN_NODES["Hip"])
    world["Knee"] = mat_mul(world["Hip"], SKIN_NODES["Knee"])
    world["Foot"] = mat_mul(world["Knee"], SKIN_NODES["Foot"])
    joints = []
    for name, t in zip(("Hip", "Knee", "Foot"), SKIN_BIND):
        ibm = trs((f32(-t[0]), f32(-t[1]), f32(-t[2])))
        joints.append(mat_mul(world[name], ibm))
    posed = {"p": [], "n": [], "t": []}
    for v, p in enumerate(SKIN_BAR):
        j0, w0, j1, w1 = SKIN_ROWS[v // 2]
        influences = [(j, f32(x)) for j, x in zip(j0, w0) if x] + [(j, f32(c / 65535)) for j, c in zip(j1, w1) if c]
        total = sum(x for _, x in influences)
        sums = {"p": [0, 0, 0], "n": [0, 0, 0], "t": [0, 0, 0]}
        for j, x in influences:
            m = joints[j]
            inv = inverse3(m)
            n = [f32(c) for c in SKIN_NORMALS[v]]
            normal = [sum(inv[c][r] * n[c] for c in range(3)) for r in range(3)]  # inverse transpose
            for key, value in (("p", apply(m, p, 1)), ("n", normal), ("t", apply(m, (1, 0, 0), 0))):
                for c in range(3):
                    sums[key][c] += x * value[c]
        for key in sums:
            posed[key].append(tuple(c / total for c in sums[key]))
    twin = w.add_mesh("Posed", [w.primitive(
        w.add_vec3(posed["p"]), w.add_vec3(posed["n"], with_bounds=False), indices, mapped,
        attributes={"TEXCOORD_0": uv, "TANGENT": f.values([t + (1,) for t in posed["t"]], FLOAT, "VEC4")})])
    f.roots.append(w.add_node("Posed", mesh=twin, translation=[10, 0, 0]))
    f.write("skin.gltf", DEFORM)


def broken():
    """One defect each (tests/test_gltf_deform.cpp lists the errors)."""
    def morph_bad(name, targets, weights=None, second=None):
        """mesh 0 "Bad": TRIANGLE with `targets` (lists of POSITION
        displacements, one per target), `weights`, and a `second` primitive
        with that many targets."""
        f = File()
        w = f.w
        pos = w.add_vec3(TRIANGLE)

        def prim(ts):
            p = w.primitive(pos, material=f.glow)
            p["targets"] = [{"POSITION": w.add_vec3(t, with_bounds=False)} for t in ts]
            return p
        mesh = {"name": "Bad", "primitives": [prim(targets)]}
        if second is not None:
            mesh["primitives"].append(prim([[(0, 0, 1)] * 3] * second))
        if weights is not None:
            mesh["weights"] = weights
        f.roots.append(w.add_node("Bad", mesh=w._add("meshes", mesh)))
        f.write(name, DEFORM_BROKEN)

    morph_bad("morph-weights-count.gltf", [[(0, 0, 1)] * 3] * 2, weights=[0.5, 0.5, 0.5])
    morph_bad("morph-target-count.gltf", [[(0, 0, 1)] * 2], weights=[1])
    morph_bad("morph-primitives-differ.gltf", [[(0, 0, 1)] * 3], weights=[1], second=2)

    def skin_bad(name, edit):
        skin_file(name, DEFORM_BROKEN, edit)

    def ibm(matrices):
        def edit(f, attributes, skin):
            data = b"".join(struct.pack("<16f", *m) for m in matrices)
            skin["inverseBindMatrices"] = f.w.add_accessor(f.w.add_view(data), FLOAT, len(matrices), "MAT4")
        return edit
    identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    skin_bad("skin-joint-range.gltf", lambda f, a, s: a.update(
        {"JOINTS_0": f.values([(5, 0, 0, 0)] * 8, UNSIGNED_BYTE, "VEC4")}))
    skin_bad("skin-weights-type.gltf", lambda f, a, s: a.update(
        {"WEIGHTS_0": f.values([(32767, 0, 0, 0)] * 8, SHORT, "VEC4", normalized=True)}))
    skin_bad("skin-negative-weight.gltf", lambda f, a, s: a.update(
        {"WEIGHTS_0": f.values([(-0.5, 1.5, 0, 0)] * 8, FLOAT, "VEC4")}))
    skin_bad("skin-missing-weights.gltf", lambda f, a, s: [a.pop(k) for k in
                                                           ("JOINTS_0", "WEIGHTS_0", "JOINTS_1", "WEIGHTS_1")])
    skin_bad("skin-joints-alone.gltf", lambda f, a, s: a.pop("WEIGHTS_1"))
    skin_bad("skin-ibm-singular.gltf", ibm([identity, [0] * 16, identity]))
    skin_bad("skin-ibm-count.gltf", ibm([identity, identity]))


def main():
    os.makedirs(DEFORM_BROKEN, exist_ok=True)
    morph()
    skin()
    broken()
    print("wrote", DEFORM)


if __name__ == "__main__":
    main()
