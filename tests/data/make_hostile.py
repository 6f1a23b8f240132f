#!/usr/bin/env python3
"""Writes tests/data/fuzz/gltf/hostile-*: hostile glTF inputs written by hand.

They go with the inputs the fuzzers found (tests/data/fuzz/TARGET/) through
the fuzz targets' bodies (tests/test_fuzz_regressions.cpp) and through the
real binary (tests/test_hostile.cpp): each must be refused in one line.
Python 3 standard library only:
    python3 tests/data/make_hostile.py
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "fuzz", "gltf")


def data_uri(raw):
    return "data:application/octet-stream;base64," + base64.b64encode(raw).decode()


def triangle(extra=None, buffer_uri=None):
    """One triangle; `extra` merged into the document."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    doc = {
        "asset": {"version": "2.0", "generator": "strata tests/data/make_hostile.py"},
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36, "uri": buffer_uri or data_uri(pos)}],
    }
    doc.update(extra or {})
    return doc


def png_header(width, height):
    """A PNG signature and IHDR chunk only (the CRC left 0): the size claimed."""
    ihdr = b"IHDR" + struct.pack(">II", width, height) + b"\x08\x06\x00\x00\x00"
    return b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + ihdr + b"\0\0\0\0"


def write(name, doc_or_bytes, prefix="hostile-"):
    os.makedirs(OUT, exist_ok=True)
    raw = doc_or_bytes if isinstance(doc_or_bytes, bytes) else json.dumps(doc_or_bytes, separators=(",", ":")).encode()
    with open(os.path.join(OUT, prefix + name), "wb") as f:
        f.write(raw)


def emitter_placements(n_tris, n_nodes):
    """An emissive mesh of n_tris triangles (u8 indices) placed by n_nodes
    nodes: emitters are never instanced, so n_tris x n_nodes world triangles."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    idx = bytes([0, 1, 2]) * n_tris
    nodes = [{"children": list(range(1, n_nodes + 1))}] + [{"mesh": 0}] * n_nodes
    return {
        "asset": {"version": "2.0", "generator": "strata tests/data/make_hostile.py"},
        "scenes": [{"nodes": [0]}], "nodes": nodes,
        "materials": [{"emissiveFactor": [1, 1, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5121, "count": 3 * n_tris, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": len(idx)}],
        "buffers": [{"byteLength": 36 + len(idx), "uri": data_uri(pos + idx)}],
    }


def main():
    write("absolute-uri.gltf", triangle(buffer_uri="/etc/passwd"))
    write("file-uri.gltf", triangle(buffer_uri="file:///etc/passwd"))
    write("encoded-absolute-uri.gltf", triangle(buffer_uri="%2Fetc%2Fpasswd"))
    write("http-uri.gltf", triangle(buffer_uri="http://example.com/tri.bin"))
    write("escape-uri.gltf", triangle(buffer_uri="../../../../../../../../etc/passwd"))
    write("image-absolute-uri.gltf", triangle({
        "images": [{"uri": "/etc/hostname"}], "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]}))
    # A texture whose header claims 60000 x 60000 (14 GB of RGBA).
    write("png-60000x60000.gltf", triangle({
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(png_header(60000, 60000)).decode()}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]}))
    # extras nested 100000 deep: a recursive converter's stack overflow.
    doc = json.dumps(triangle(), separators=(",", ":"))
    write("deep-json.gltf", (doc[:-1] + ',"extras":' + "[" * 100000 + "]" * 100000 + "}").encode())
    # An emissive mesh of 10^5 triangles placed by 2 x 10^4 nodes: 2 x 10^9
    # world triangles.
    write("flatten-bomb.gltf", emitter_placements(100000, 20000))
    # 8 x 10^6 emitting triangles: 0.95 GiB at kHostBytesPerTriangle, within
    # the fuzz target's 1 GiB, while their light tree took the fuzzer's
    # process past 4 GiB (a libFuzzer out-of-memory, 2026-12-06): the
    # emitters' own memory counts too (kHostBytesPerEmitter).
    write("oom-emitters-light-tree.gltf", emitter_placements(1000, 8000), prefix="")

    # EXT_mesh_gpu_instancing: nodes sharing one accessor of 2^20 zeros as
    # TRANSLATION and SCALE (no bufferView; 2^20 is what any file may have).
    # 257 of them place the triangle 269,484,032 times, past the 2^28
    # instances strata indexes; 200 of them 209,715,200 times, 50 GiB of
    # instances, whose transforms alone (5 GB) were once read before the
    # memory was checked.
    for name, nodes in (("instance-count.gltf", 257), ("instance-bomb.gltf", 200)):
        write(name, triangle({
            "extensionsUsed": ["EXT_mesh_gpu_instancing"],
            "scenes": [{"nodes": list(range(nodes))}],
            "nodes": [{"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {
                "attributes": {"TRANSLATION": 1, "SCALE": 1}}}}] * nodes,
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"componentType": 5126, "count": 1 << 20, "type": "VEC3"}]}))

if __name__ == "__main__":
    main()
