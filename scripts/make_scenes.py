#!/usr/bin/env python3
"""Writes the scenes strata ships (scenes/*.gltf); Python 3 stdlib only.

Each scene is one .gltf with its buffer embedded as a base64 data URI. The
output is deterministic: running this again rewrites identical bytes. All
geometry and numbers are our own (CC0). Front faces are counter-clockwise;
the renderer emits light from the front face only unless doubleSided.

    python3 scripts/make_scenes.py [OUTDIR]     (default: scenes/)
"""

import base64
import json
import math
import os
import struct
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FLOAT = 5126
UNSIGNED_SHORT = 5123


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def normalize(a):
    n = math.sqrt(dot(a, a))
    return tuple(x / n for x in a)


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


class Quads:
    """Flat-shaded quads collected into one indexed TRIANGLES primitive."""

    def __init__(self):
        self.positions = []
        self.normals = []
        self.indices = []

    def add(self, origin, u, v, facing):
        """Quad origin, origin+u, origin+u+v, origin+v; its front face
        (normal cross(u, v)) must point along `facing`."""
        normal = normalize(cross(u, v))
        assert dot(normal, facing) > 0, "quad faces the wrong way"
        base = len(self.positions)
        self.positions += [origin, add(origin, u), add(add(origin, u), v), add(origin, v)]
        self.normals += [normal] * 4
        self.indices += [base, base + 1, base + 2, base, base + 2, base + 3]
        return self


def box_faces(inward):
    """Faces of the cube [-1, 1]^3, front faces outward or inward."""
    q = Quads()
    for axis in range(3):
        for sign in (-1.0, 1.0):
            a, b = (axis + 1) % 3, (axis + 2) % 3
            origin = [0.0, 0.0, 0.0]
            origin[axis] = sign
            origin[a] = origin[b] = -1.0
            u = [0.0, 0.0, 0.0]
            v = [0.0, 0.0, 0.0]
            u[a] = 2.0
            v[b] = 2.0
            outward = [0.0, 0.0, 0.0]
            outward[axis] = sign
            facing = tuple(-x for x in outward) if inward else tuple(outward)
            # cross(u, v) points along +axis; swap the edges to flip it.
            if dot(cross(u, v), facing) < 0:
                u, v = v, u
            q.add(tuple(origin), tuple(u), tuple(v), facing)
    return q


class Writer:
    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "strata scripts/make_scenes.py",
                              "copyright": "CC0 1.0 (public domain), the strata authors"}}
        self.blob = bytearray()

    def _add(self, key, obj):
        items = self.doc.setdefault(key, [])
        items.append(obj)
        return len(items) - 1

    def _accessor(self, data, component_type, count, type_, target, bounds=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        view = self._add("bufferViews", {"buffer": 0, "byteOffset": len(self.blob),
                                         "byteLength": len(data), "target": target})
        self.blob += data
        acc = {"bufferView": view, "componentType": component_type, "count": count,
               "type": type_}
        if bounds:
            acc["min"], acc["max"] = bounds
        return self._add("accessors", acc)

    def mesh(self, name, quads, material):
        pts = quads.positions
        bounds = ([min(f32(p[i]) for p in pts) for i in range(3)],
                  [max(f32(p[i]) for p in pts) for i in range(3)])
        pos = self._accessor(b"".join(struct.pack("<3f", *p) for p in pts), FLOAT, len(pts),
                             "VEC3", 34962, bounds)
        nrm = self._accessor(b"".join(struct.pack("<3f", *n) for n in quads.normals), FLOAT,
                             len(pts), "VEC3", 34962)
        ind = self._accessor(b"".join(struct.pack("<H", i) for i in quads.indices),
                             UNSIGNED_SHORT, len(quads.indices), "SCALAR", 34963)
        prim = {"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": ind,
                "material": material}
        return self._add("meshes", {"name": name, "primitives": [prim]})

    def material(self, name, base_color, emissive=None, strength=None):
        mat = {"name": name,
               "pbrMetallicRoughness": {"baseColorFactor": list(base_color) + [1.0],
                                        "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if emissive is not None:
            mat["emissiveFactor"] = list(emissive)
        if strength is not None:
            mat["extensions"] = {"KHR_materials_emissive_strength":
                                 {"emissiveStrength": strength}}
        return self._add("materials", mat)

    def camera(self, name, yfov_degrees):
        return self._add("cameras", {"name": name, "type": "perspective",
                                     "perspective": {"yfov": math.radians(yfov_degrees),
                                                     "znear": 0.01, "aspectRatio": 1.0}})

    def node(self, name, **fields):
        node = {"name": name}
        node.update(fields)
        return self._add("nodes", node)

    def text(self, roots):
        self.doc["scene"] = 0
        self.doc["scenes"] = [{"name": "Scene", "nodes": roots}]
        uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.blob)).decode()
        self.doc["buffers"] = [{"byteLength": len(self.blob), "uri": uri}]
        return to_json(self.doc) + "\n"


def to_json(value, level=0):
    """JSON with one-space indents; arrays of numbers stay on one line."""
    pad = " " * level
    if isinstance(value, dict):
        items = [f"{pad} {json.dumps(k)}: {to_json(v, level + 1)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if all(not isinstance(v, (dict, list)) for v in value):
            return "[" + ", ".join(json.dumps(v) for v in value) + "]"
        items = [pad + " " + to_json(v, level + 1) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(value)


def rotation_y(degrees):
    """Quaternion (x, y, z, w) for a rotation about +Y."""
    h = math.radians(degrees) / 2
    return [0.0, math.sin(h), 0.0, math.cos(h)]


def cornell_box():
    """Room x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +Z."""
    w = Writer()
    white = w.material("White", (0.73, 0.73, 0.73))
    red = w.material("Red", (0.63, 0.065, 0.05))
    green = w.material("Green", (0.14, 0.45, 0.09))
    light = w.material("Light", (0.73, 0.73, 0.73), emissive=(1.0, 1.0, 1.0), strength=15.0)
    w.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]

    up, down = (0, 1, 0), (0, -1, 0)
    floor = Quads().add((-1, 0, -1), (0, 0, 2), (2, 0, 0), up)
    ceiling = Quads().add((-1, 2, -1), (2, 0, 0), (0, 0, 2), down)
    back = Quads().add((-1, 0, -1), (2, 0, 0), (0, 2, 0), (0, 0, 1))
    left = Quads().add((-1, 0, -1), (0, 2, 0), (0, 0, 2), (1, 0, 0))
    right = Quads().add((1, 0, -1), (0, 0, 2), (0, 2, 0), (-1, 0, 0))
    # 0.46 x 0.46 (23% of the ceiling width), 0.02 below the ceiling, facing down.
    lamp = Quads().add((-0.23, 1.98, -0.23), (0.46, 0, 0), (0, 0, 0.46), down)
    # Unit box x, z in [-0.5, 0.5], y in [0, 1], no bottom face; front faces out.
    cube = box_faces(inward=False)
    box = Quads()
    for i in range(0, len(cube.positions), 4):
        n = cube.normals[i]
        if n[1] < -0.5:
            continue  # bottom
        p = [(x * 0.5, y * 0.5 + 0.5, z * 0.5) for x, y, z in cube.positions[i:i + 4]]
        box.add(p[0], sub(p[1], p[0]), sub(p[3], p[0]), n)

    roots = [
        w.node("Floor", mesh=w.mesh("Floor", floor, white)),
        w.node("Ceiling", mesh=w.mesh("Ceiling", ceiling, white)),
        w.node("BackWall", mesh=w.mesh("BackWall", back, white)),
        w.node("LeftWall", mesh=w.mesh("LeftWall", left, red)),
        w.node("RightWall", mesh=w.mesh("RightWall", right, green)),
    ]
    box_white = w.mesh("Box", box, white)
    roots += [
        w.node("ShortBox", mesh=box_white, translation=[0.4, 0.0, 0.4],
               rotation=rotation_y(-18.0), scale=[0.6, 0.6, 0.6]),
        w.node("TallBox", mesh=box_white, translation=[-0.4, 0.0, -0.35],
               rotation=rotation_y(17.0), scale=[0.6, 1.2, 0.6]),
        w.node("Light", mesh=w.mesh("Light", lamp, light)),
        # Looks down -Z (the glTF camera default) through the open front.
        w.node("Camera", camera=w.camera("Camera", 40.0), translation=[0.0, 1.0, 3.8]),
    ]
    return w.text(roots)


def furnace(albedo=0.5, le=0.5):
    """Closed cube [-1, 1]^3 facing inward, emissive and diffuse everywhere."""
    w = Writer()
    wall = w.material("Furnace", (albedo, albedo, albedo), emissive=(le, le, le))
    roots = [
        w.node("Cube", mesh=w.mesh("Cube", box_faces(inward=True), wall)),
        w.node("Camera", camera=w.camera("Camera", 60.0)),  # at the centre, looking at -Z
    ]
    return w.text(roots)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "scenes")
    os.makedirs(out, exist_ok=True)
    scenes = (
        ("cornell-box.gltf", cornell_box()),
        ("furnace.gltf", furnace()),
        # Le = 0.1 is not a float32 dyadic: sums of it drift in float32.
        ("furnace-a0.8-le0.1.gltf", furnace(albedo=0.8, le=0.1)),
    )
    for name, text in scenes:
        path = os.path.join(out, name)
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        print("wrote", path)


if __name__ == "__main__":
    main()
