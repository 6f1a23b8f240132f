"""Minimal glTF 2.0 writer (Python 3 stdlib only), used by scripts/make_scenes.py
and by tests/data/make_features.py, make_broken.py and make_geometry.py.

One GltfWriter collects JSON objects and a single binary buffer; write_gltf
embeds the buffer as a base64 data URI (or writes a sibling .bin), write_glb
writes a binary glTF. Output is deterministic: same calls, same bytes.
"""

import base64
import json
import os
import struct

BYTE = 5120
UNSIGNED_BYTE = 5121
SHORT = 5122
UNSIGNED_SHORT = 5123
UNSIGNED_INT = 5125
FLOAT = 5126

# bufferView.target values (glTF 2.0, 5.11.4): vertex attributes, indices.
ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963

INDEX_FORMAT = {UNSIGNED_BYTE: "<B", UNSIGNED_SHORT: "<H", UNSIGNED_INT: "<I"}


def f32(x):
    """x rounded to float32 (round to nearest even), as the loader will read it."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def pack_vec3(points):
    return b"".join(struct.pack("<3f", *p) for p in points)


def to_json(value, level=0):
    """JSON with one-space indents; arrays of numbers stay on one line."""
    pad = " " * level
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f'{pad} {json.dumps(k)}: {to_json(v, level + 1)}' for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if all(not isinstance(v, (dict, list)) for v in value):
            return "[" + ", ".join(json.dumps(v) for v in value) + "]"
        items = [pad + " " + to_json(v, level + 1) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(value)


class GltfWriter:
    def __init__(self, generator, copyright=None):
        asset = {"version": "2.0", "generator": generator}
        if copyright is not None:
            asset["copyright"] = copyright
        self.doc = {"asset": asset}
        self.blob = bytearray()

    def _add(self, key, obj):
        items = self.doc.setdefault(key, [])
        items.append(obj)
        return len(items) - 1

    # Buffer data -------------------------------------------------------
    def add_view(self, data, stride=None, target=None):
        """Appends data (4-byte aligned) as a new bufferView; returns its index."""
        while len(self.blob) % 4:
            self.blob.append(0)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if stride is not None:
            view["byteStride"] = stride
        if target is not None:
            view["target"] = target
        self.blob += data
        return self._add("bufferViews", view)

    def add_accessor(self, view, component_type, count, type_, byte_offset=0,
                     min_=None, max_=None, normalized=False, sparse=None):
        """view None: an accessor without bufferView (zeros); sparse: a dict
        from sparse()."""
        acc = {} if view is None else {"bufferView": view}
        acc.update({"componentType": component_type, "count": count, "type": type_})
        if byte_offset:
            acc["byteOffset"] = byte_offset
        if min_ is not None:
            acc["min"] = min_
            acc["max"] = max_
        if normalized:
            acc["normalized"] = True
        if sparse is not None:
            acc["sparse"] = sparse
        return self._add("accessors", acc)

    def sparse(self, indices, values, index_type=UNSIGNED_BYTE):
        """An accessor's sparse object: indices (packed as index_type) and the
        packed bytes of the values that replace those elements."""
        fmt = INDEX_FORMAT[index_type]
        index_view = self.add_view(b"".join(struct.pack(fmt, i) for i in indices))
        return {"count": len(indices),
                "indices": {"bufferView": index_view, "componentType": index_type},
                "values": {"bufferView": self.add_view(values)}}

    def add_vec3(self, points, with_bounds=True):
        """Tightly packed float VEC3 accessor (POSITION bounds when with_bounds)."""
        view = self.add_view(pack_vec3(points), target=ARRAY_BUFFER)
        lo = hi = None
        if with_bounds:
            lo = [min(f32(p[i]) for p in points) for i in range(3)]
            hi = [max(f32(p[i]) for p in points) for i in range(3)]
        return self.add_accessor(view, FLOAT, len(points), "VEC3", 0, lo, hi)

    def add_indices(self, indices, component_type=UNSIGNED_SHORT):
        fmt = INDEX_FORMAT[component_type]
        view = self.add_view(b"".join(struct.pack(fmt, i) for i in indices),
                             target=ELEMENT_ARRAY_BUFFER)
        return self.add_accessor(view, component_type, len(indices), "SCALAR")

    # Scene objects -------------------------------------------------------
    def add_material(self, name, base_color=None, metallic=None, roughness=None,
                     emissive=None, strength=None, ior=None, double_sided=False,
                     alpha_mode=None, alpha_cutoff=None, specular=None, transmission=None, unlit=False,
                     volume=None, extensions=None):
        """base_color is RGBA; factors left as None are omitted (glTF defaults);
        extensions: more {name: object} in the material's extensions."""
        mat = {"name": name}
        pbr = {}
        if base_color is not None:
            pbr["baseColorFactor"] = list(base_color)
        if metallic is not None:
            pbr["metallicFactor"] = metallic
        if roughness is not None:
            pbr["roughnessFactor"] = roughness
        if pbr:
            mat["pbrMetallicRoughness"] = pbr
        if emissive is not None:
            mat["emissiveFactor"] = list(emissive)
        ext = {}
        if strength is not None:
            ext["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
        if ior is not None:
            ext["KHR_materials_ior"] = {"ior": ior}
        if specular is not None:
            ext["KHR_materials_specular"] = {"specularFactor": specular}
        if transmission is not None:
            ext["KHR_materials_transmission"] = {"transmissionFactor": transmission}
        if unlit:
            ext["KHR_materials_unlit"] = {}
        if volume is not None:  # (thicknessFactor, attenuationDistance, attenuationColor)
            ext["KHR_materials_volume"] = {"thicknessFactor": volume[0], "attenuationDistance": volume[1],
                                           "attenuationColor": list(volume[2])}
        ext.update(extensions or {})
        if ext:
            mat["extensions"] = ext
        if double_sided:
            mat["doubleSided"] = True
        if alpha_mode is not None:
            mat["alphaMode"] = alpha_mode
        if alpha_cutoff is not None:
            mat["alphaCutoff"] = alpha_cutoff
        return self._add("materials", mat)

    def primitive(self, position, normal=None, indices=None, material=None, mode=None,
                  attributes=None):
        """attributes: more {semantic: accessor}, after POSITION and NORMAL."""
        prim = {"attributes": {"POSITION": position}}
        if normal is not None:
            prim["attributes"]["NORMAL"] = normal
        if attributes:
            prim["attributes"].update(attributes)
        if indices is not None:
            prim["indices"] = indices
        if material is not None:
            prim["material"] = material
        if mode is not None:
            prim["mode"] = mode
        return prim

    def add_mesh(self, name, primitives):
        return self._add("meshes", {"name": name, "primitives": primitives})

    def add_triangles(self, name, points, normals=None, indices=None, material=None,
                      index_type=UNSIGNED_SHORT):
        """One mesh with one TRIANGLES primitive; returns the mesh index."""
        pos = self.add_vec3(points)
        nrm = self.add_vec3(normals, with_bounds=False) if normals is not None else None
        idx = self.add_indices(indices, index_type) if indices is not None else None
        return self.add_mesh(name, [self.primitive(pos, nrm, idx, material)])

    def add_perspective(self, name, yfov, znear=0.01, zfar=None, aspect_ratio=None):
        """yfov in radians; znear, zfar in scene units."""
        persp = {"yfov": yfov, "znear": znear}
        if zfar is not None:
            persp["zfar"] = zfar
        if aspect_ratio is not None:
            persp["aspectRatio"] = aspect_ratio
        return self._add("cameras", {"name": name, "type": "perspective",
                                     "perspective": persp})

    def add_orthographic(self, name, xmag=1.0, ymag=1.0, znear=0.01, zfar=100.0):
        return self._add("cameras", {"name": name, "type": "orthographic",
                                     "orthographic": {"xmag": xmag, "ymag": ymag,
                                                      "znear": znear, "zfar": zfar}})

    def add_light(self, name, type_, color=None, intensity=None, spot=None, range_=None):
        """KHR_lights_punctual light; spot = (innerConeAngle, outerConeAngle) in
        radians. Returns its index; a node refers to it with light=index."""
        light = {"name": name, "type": type_}
        if color is not None:
            light["color"] = list(color)
        if intensity is not None:
            light["intensity"] = intensity
        if spot is not None:
            light["spot"] = {"innerConeAngle": spot[0], "outerConeAngle": spot[1]}
        if range_ is not None:
            light["range"] = range_
        ext = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})
        ext["lights"].append(light)
        return len(ext["lights"]) - 1

    def add_node(self, name, light=None, **fields):
        """fields: mesh, camera, children, translation, rotation, scale, matrix;
        light: a KHR_lights_punctual light index."""
        node = {"name": name}
        node.update(fields)
        if light is not None:
            node["extensions"] = {"KHR_lights_punctual": {"light": light}}
        return self._add("nodes", node)

    def add_animation(self, name, channels):
        """channels: (node, path, interpolation, times, values) tuples; path is
        translation, rotation or scale, values one tuple per output element
        (three per key for CUBICSPLINE: in-tangent, value, out-tangent)."""
        samplers, targets = [], []
        for node, path, interpolation, times, values in channels:
            width = len(values[0])
            inp = self.add_accessor(self.add_view(struct.pack("<%df" % len(times), *times)), FLOAT,
                                    len(times), "SCALAR", 0, [f32(min(times))], [f32(max(times))])
            flat = [float(c) for v in values for c in v]
            out = self.add_accessor(self.add_view(struct.pack("<%df" % len(flat), *flat)), FLOAT,
                                    len(values), {3: "VEC3", 4: "VEC4"}[width])
            samplers.append({"input": inp, "output": out, "interpolation": interpolation})
            targets.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})
        return self._add("animations", {"name": name, "channels": targets, "samplers": samplers})

    def set_scene(self, nodes, name=None):
        scene = {} if name is None else {"name": name}
        scene["nodes"] = list(nodes)
        self.doc["scene"] = 0
        self.doc["scenes"] = [scene]

    def use_extensions(self, used, required=()):
        self.doc["extensionsUsed"] = list(used)
        if required:
            self.doc["extensionsRequired"] = list(required)

    # Output ------------------------------------------------------------
    def _json(self, buffer):
        doc = dict(self.doc)
        if self.blob:
            doc["buffers"] = [buffer]
        return to_json(doc) + "\n"

    def gltf_text(self, bin_uri=None):
        """glTF JSON; the buffer is a data URI unless bin_uri names a file."""
        uri = bin_uri or ("data:application/octet-stream;base64," +
                          base64.b64encode(bytes(self.blob)).decode("ascii"))
        return self._json({"byteLength": len(self.blob), "uri": uri})

    def write_gltf(self, path, bin_name=None):
        """Writes path; with bin_name the buffer goes to a sibling file."""
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(self.gltf_text(bin_name))
        if bin_name:
            with open(os.path.join(os.path.dirname(path), bin_name), "wb") as f:
                f.write(bytes(self.blob))

    def glb_bytes(self):
        text = self._json({"byteLength": len(self.blob)}).encode("utf-8")
        text += b" " * (-len(text) % 4)
        blob = bytes(self.blob) + b"\0" * (-len(self.blob) % 4)
        chunks = struct.pack("<I4s", len(text), b"JSON") + text
        if blob:
            chunks += struct.pack("<I4s", len(blob), b"BIN\0") + blob
        return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks

    def write_glb(self, path):
        with open(path, "wb") as f:
            f.write(self.glb_bytes())


def write_texts(folder, files):
    """Writes each {relative path: text} of `files` under `folder`, making
    sub-folders, and prints each path written."""
    for name, text in files.items():
        path = os.path.normpath(os.path.join(folder, name))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
        print("wrote", path)
