#!/usr/bin/env python3
"""Writes tests/data/validator/: one small glTF file per finding of running
strata on Khronos' glTF-Validator test corpus (issue 45): files glTF 2.0
calls valid that strata refused, each now read as the spec says (a part
skipped with one warning, a default used, a fallback taken).

    python3 tests/data/make_validator.py
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "validator")

# A 1x1 lossless WebP (opaque white).
WEBP_1X1 = "UklGRhoAAABXRUJQVlA4TA0AAAAvAAAAEAcQERGIiP4HAA=="


def data(b, mime="application/octet-stream"):
    return f"data:{mime};base64," + base64.b64encode(b).decode("ascii")


class File:
    """A triangle (0,0,0) (1,0,0) (0,1,0) emitting white, and a camera."""

    def __init__(self):
        self.bin = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "strata tests/data/make_validator.py"},
            "scene": 0, "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"name": "Triangle", "mesh": 0}, {"name": "Camera", "camera": 0, "translation": [0.3, 0.3, 2]}],
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
            "materials": [{"name": "Light", "emissiveFactor": [1, 1, 1]}],
            "meshes": [{"name": "Triangle", "primitives": [{"attributes": {}, "material": 0}]}],
            "bufferViews": [], "accessors": [],
        }
        pos = self.accessor(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0), 5126, 3, "VEC3",
                            min=[0, 0, 0], max=[1, 1, 0])
        self.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = pos

    def accessor(self, raw, component, count, type_, **extra):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(raw)})
        self.bin += raw
        self.doc["accessors"].append(dict(bufferView=len(self.doc["bufferViews"]) - 1, componentType=component,
                                          count=count, type=type_, **extra))
        return len(self.doc["accessors"]) - 1

    def write(self, name, uri=True):
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri": data(bytes(self.bin))}]
        if not uri:
            del self.doc["buffers"][0]["uri"]
        with open(os.path.join(OUT, name), "w", encoding="utf-8", newline="\n") as f:
            json.dump(self.doc, f, indent=1)
            f.write("\n")


def main():
    os.makedirs(OUT, exist_ok=True)

    # A skin without inverseBindMatrices (optional: identity), its one joint at the origin.
    f = File()
    prim = f.doc["meshes"][0]["primitives"][0]
    prim["attributes"]["JOINTS_0"] = f.accessor(bytes(12), 5121, 3, "VEC4")
    prim["attributes"]["WEIGHTS_0"] = f.accessor(struct.pack("<12f", 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0), 5126, 3,
                                                 "VEC4")
    f.doc["nodes"][0]["skin"] = 0
    f.doc["nodes"].append({"name": "Joint"})
    f.doc["scenes"][0]["nodes"].append(2)
    f.doc["skins"] = [{"joints": [2]}]
    f.write("skin-without-inverse-bind.gltf")

    # A second primitive whose indices accessor has no bufferView (zeros).
    f = File()
    pos = f.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
    f.doc["accessors"].append({"componentType": 5123, "count": 3, "type": "SCALAR"})
    f.doc["meshes"][0]["primitives"].append({"attributes": {"POSITION": pos}, "indices": 1})
    f.write("indices-without-view.gltf")

    # A node matrix whose last row is not (0, 0, 0, 1).
    f = File()
    f.doc["nodes"][0]["matrix"] = [1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    f.write("matrix-not-affine.gltf")

    # A primitive without POSITION, and a non-indexed one of 4 vertices.
    f = File()
    four = f.accessor(struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0), 5126, 4, "VEC3",
                      min=[0, 0, 0], max=[1, 1, 0])
    f.doc["meshes"][0]["primitives"] += [{"attributes": {}}, {"attributes": {"POSITION": four}}]
    f.write("primitives-to-skip.gltf")

    # A texture without a source, read as the emissive texture.
    f = File()
    f.doc["textures"] = [{}]
    f.doc["materials"][0]["emissiveTexture"] = {"index": 0}
    f.write("texture-without-source.gltf")

    # An image no texture uses, which cannot be decoded (3 bytes).
    f = File()
    f.doc["images"] = [{"uri": data(b"\0\0\0", "image/png")}]
    f.write("unused-undecodable-image.gltf")

    # KHR_animation_pointer: the triangle's node translated from (0, 0, 0)
    # at t = 0 to (2, 0, 0) at t = 1 through a pointer, and a material's
    # emissiveFactor animated (ignored with one warning).
    f = File()
    times = f.accessor(struct.pack("<2f", 0, 1), 5126, 2, "SCALAR", min=[0], max=[1])
    moves = f.accessor(struct.pack("<6f", 0, 0, 0, 2, 0, 0), 5126, 2, "VEC3")
    colours = f.accessor(struct.pack("<6f", 1, 1, 1, 0, 0, 0), 5126, 2, "VEC3")
    pointer = lambda p: {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": p}}}  # noqa: E731
    f.doc["animations"] = [{"name": "Slide",
                            "channels": [{"sampler": 0, "target": pointer("/nodes/0/translation")},
                                         {"sampler": 1, "target": pointer("/materials/0/emissiveFactor")}],
                            "samplers": [{"input": times, "output": moves}, {"input": times, "output": colours}]}]
    f.doc["extensionsUsed"] = ["KHR_animation_pointer"]
    f.write("animation-pointer.gltf")

    # An emissive texture whose image is a WebP data: URI.
    f = File()
    prim = f.doc["meshes"][0]["primitives"][0]
    prim["attributes"]["TEXCOORD_0"] = f.accessor(struct.pack("<6f", 0, 0, 1, 0, 0, 1), 5126, 3, "VEC2")
    f.doc["images"] = [{"uri": "data:image/webp;base64," + WEBP_1X1}]
    f.doc["textures"] = [{"source": 0}]
    f.doc["materials"][0]["emissiveTexture"] = {"index": 0}
    f.write("webp-data-uri.gltf")
    # KHR_node_visibility: a hidden node (visible: false) with a visible
    # child, both with a triangle, beside the visible one; the camera sits
    # under the hidden node.
    f = File()
    f.doc["nodes"][1]["name"] = "Camera"
    f.doc["nodes"] += [{"name": "Hidden", "mesh": 0, "translation": [5, 0, 0], "children": [1, 3],
                        "extensions": {"KHR_node_visibility": {"visible": False}}},
                       {"name": "Child", "mesh": 0, "translation": [0, 5, 0],
                        "extensions": {"KHR_node_visibility": {"visible": True}}}]
    f.doc["scenes"][0]["nodes"] = [0, 2]
    f.doc["extensionsUsed"] = ["KHR_node_visibility"]
    f.write("node-visibility.gltf")
    # A .gltf whose buffer has no uri: valid to the validator (which reads no
    # data), but the data is nowhere: one error line naming the buffer.
    File().write("buffer-without-uri.gltf", uri=False)
    print("wrote", OUT)


if __name__ == "__main__":
    main()
