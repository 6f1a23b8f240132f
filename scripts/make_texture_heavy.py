#!/usr/bin/env python3
"""Writes a scene whose textures exceed what a device holds, for measuring
strata's texture memory (docs/benchmarks.md): N quads in a row, each with
its own SIZE x SIZE RGB PNG as its emissive texture (a gradient and a grid,
so the images compress), seen by one camera. N = 8 and SIZE = 8192 give
2 GiB of texels as strata packs them (4 bytes a texel).

    python3 scripts/make_texture_heavy.py OUT_DIR [N] [SIZE]

Python 3 standard library only; deterministic.
"""

import base64
import json
import os
import struct
import sys
import zlib


def png_file(path, size, k):
    """A size x size RGB PNG: red the column, green the row (both mod 256), blue k."""
    row = bytearray(size * 3)
    row[0::3] = bytes(x & 255 for x in range(size))
    row[2::3] = bytes([(40 * k) & 255]) * size
    comp = zlib.compressobj(1)
    idat = bytearray()
    for y in range(size):
        row[1::3] = bytes([y & 255]) * size
        idat += comp.compress(b"\0" + bytes(row))
    idat += comp.flush()

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", bytes(idat)) + chunk(b"IEND", b""))


def main():
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 8
    size = int(sys.argv[3]) if len(sys.argv) > 3 else 8192
    os.makedirs(out, exist_ok=True)
    positions, uvs, indices = [], [], []
    for k in range(n):
        x0 = 1.1 * k - 0.55 * n
        positions += [(x0, -0.5, 0), (x0 + 1, -0.5, 0), (x0 + 1, 0.5, 0), (x0, 0.5, 0)]
        uvs += [(0, 1), (1, 1), (1, 0), (0, 0)]
    blob = b"".join(struct.pack("<3f", *p) for p in positions) + b"".join(struct.pack("<2f", *t) for t in uvs)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3) * n  # each quad's accessor holds its own 4 vertices
    doc = {
        "asset": {"version": "2.0", "generator": "strata scripts/make_texture_heavy.py"},
        "buffers": [{"byteLength": len(blob) + len(idx),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob + idx).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * len(positions)},
                        {"buffer": 0, "byteOffset": 12 * len(positions), "byteLength": 8 * len(uvs)},
                        {"buffer": 0, "byteOffset": len(blob), "byteLength": len(idx)}],
        "accessors": [], "meshes": [], "materials": [], "textures": [], "images": [], "nodes": [],
        "samplers": [{"magFilter": 9729, "minFilter": 9729}],
    }
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    for k in range(n):
        name = "heavy-%d.png" % k
        png_file(os.path.join(out, name), size, k)
        doc["images"].append({"uri": name})
        doc["textures"].append({"source": k, "sampler": 0})
        doc["materials"].append({"name": "Glow %d" % k, "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": k},
                                 "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}})
        doc["accessors"] += [
            {"bufferView": 0, "byteOffset": 48 * k, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "byteOffset": 32 * k, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "byteOffset": 12 * k, "componentType": 5123, "count": 6, "type": "SCALAR"}]
        doc["meshes"].append({"primitives": [{"attributes": {"POSITION": 3 * k, "TEXCOORD_0": 3 * k + 1},
                                              "indices": 3 * k + 2, "material": k}]})
        doc["nodes"].append({"mesh": k})
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01}}]
    doc["nodes"].append({"camera": 0, "translation": [0, 0, 0.62 * n / 0.5]})
    doc["scenes"] = [{"nodes": list(range(n + 1))}]
    doc["scene"] = 0
    with open(os.path.join(out, "heavy.gltf"), "w") as f:
        json.dump(doc, f, indent=1)


if __name__ == "__main__":
    main()
