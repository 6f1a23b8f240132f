#!/usr/bin/env python3
"""Seed corpora for the fuzz targets (scripts/fuzz.sh): make_seeds.py OUT [GENERATED...]

OUT/gltf   every .gltf and .glb of tests/data and scenes (and of the GENERATED
           folders: the build's compressed and WebP test files), with the
           files their uris name put inline as data: URIs, so that a seed
           needs nothing beside it
OUT/image  the PNG, JPEG and WebP images among them, each after a 0 byte
           (fuzz/entries.h), and small environment maps after a 1 byte
OUT/state  the state files of fuzz/seeds/state
OUT/cli    the command lines of fuzz/seeds/cli.txt, one a line, as words
           separated by NUL bytes
"""
import base64
import hashlib
import json
import os
import shlex
import struct
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_SEED = 1 << 20  # bytes; larger files would slow every mutation


def put(folder, data):
    os.makedirs(folder, exist_ok=True)
    if len(data) > MAX_SEED:
        return
    name = hashlib.sha1(data).hexdigest()
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def inline(path):
    """The glTF at `path` with its external uris as data: URIs, or None."""
    with open(path, "rb") as f:
        raw = f.read()
    if raw[:4] == b"glTF":
        return raw
    try:
        doc = json.loads(raw)
    except (ValueError, UnicodeDecodeError, RecursionError):
        return raw  # a broken file is a seed as it is
    if not isinstance(doc, dict):
        return raw
    folder = os.path.dirname(path)
    for key in ("buffers", "images"):
        for item in doc.get(key, []) if isinstance(doc.get(key), list) else []:
            uri = item.get("uri") if isinstance(item, dict) else None
            if not isinstance(uri, str) or uri.startswith("data:"):
                continue
            file = os.path.join(folder, uri)
            if os.path.isfile(file) and os.path.getsize(file) <= MAX_SEED:
                with open(file, "rb") as f:
                    item["uri"] = "data:application/octet-stream;base64," + base64.b64encode(f.read()).decode()
    return json.dumps(doc, separators=(",", ":")).encode()


def images_in(folders):
    magic = (b"\x89PNG", b"\xff\xd8\xff", b"RIFF")
    for folder in folders:
        for dirpath, _, files in os.walk(folder):
            for name in sorted(files):
                file = os.path.join(dirpath, name)
                with open(file, "rb") as f:
                    head = f.read(4)
                if head.startswith(magic) and os.path.getsize(file) <= MAX_SEED:
                    with open(file, "rb") as f:
                        yield f.read()


def main():
    out = sys.argv[1]
    sources = [os.path.join(REPO, "tests", "data"), os.path.join(REPO, "scenes")] + sys.argv[2:]
    for folder in sources:
        for dirpath, _, files in os.walk(folder):
            for name in sorted(files):
                if name.endswith((".gltf", ".glb")):
                    put(os.path.join(out, "gltf"), inline(os.path.join(dirpath, name)))
    for image in images_in(sources):
        put(os.path.join(out, "image"), b"\x00" + image)
    for w, h, values in ((2, 1, [1.0] * 6), (4, 2, [0.5, 2.0, 0.0] * 8), (3, 3, [0.0] * 26 + [7.0])):
        put(os.path.join(out, "image"), b"\x01" + bytes([w - 1, h - 1]) + struct.pack("<%df" % len(values), *values))
    states = os.path.join(REPO, "fuzz", "seeds", "state")
    for name in sorted(os.listdir(states)):
        with open(os.path.join(states, name), "rb") as f:
            put(os.path.join(out, "state"), f.read())
    with open(os.path.join(REPO, "fuzz", "seeds", "cli.txt")) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                put(os.path.join(out, "cli"), b"\x00".join(w.encode() for w in shlex.split(line)))


if __name__ == "__main__":
    main()
