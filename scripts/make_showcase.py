#!/usr/bin/env python3
"""Writes the material and light showcase scenes (issue 5) to scenes/;
Python 3 stdlib only. Our own work, CC0: every number below was chosen for
this project.

    materials-board.gltf  metal / plastic / glossy-black spheres of rising
                          roughness, and two glass spheres, on a studio sweep
    cornell-glass.gltf    the Cornell box of make_scenes.cornell_box() with a
                          glass sphere (caustic) and a mirror sphere
    veach-mis.gltf        after Veach 1997, fig. 9.4: four spherical emitters
                          of equal power over four metal plates of rising
                          roughness

Spheres are UV spheres with smooth vertex normals and TEXCOORD_0
(u = longitude / 2 pi, v = colatitude / pi, v = 0 at +Y). Each scene lists in
extensionsUsed exactly the extensions its materials use. Output is
deterministic.

    python3 scripts/make_showcase.py [OUTDIR]     default: scenes/
"""

import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "data"))  # make_lights

from gltf_writer import ARRAY_BUFFER, FLOAT  # noqa: E402
from make_texture_scenes import data_uri, png  # noqa: E402
from make_lights import rgbe  # noqa: E402
from make_scenes import (CORNELL_CAMERA, Quads, add, box_faces, camera,  # noqa: E402
                         cornell_materials, cornell_room, cross, dot, lambert, mesh,
                         normalize, sub, write, writer)


# Geometry -------------------------------------------------------------------

class Sphere:
    """Unit UV sphere: `segments` columns of longitude, `rings` rows of
    colatitude. The seam column and the poles are duplicated for the UVs but
    bit-identical in position, so the surface is closed (watertight for
    refraction). Pole rows are single triangles: 2 * segments * (rings - 1)
    triangles. Front faces (counter-clockwise) point outward."""

    def __init__(self, segments=32, rings=16):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []
        for i in range(rings + 1):
            theta = math.pi * i / rings
            st, ct = math.sin(theta), math.cos(theta)
            if i == 0 or i == rings:
                st, ct = 0.0, (1.0 if i == 0 else -1.0)
            for j in range(segments + 1):
                phi = 2.0 * math.pi * (j % segments) / segments
                # + 0.0 turns -0.0 (the poles) into +0.0: one bit pattern per point.
                p = (st * math.cos(phi) + 0.0, ct, -st * math.sin(phi) + 0.0)
                self.positions.append(p)
                self.normals.append(p)
                self.uvs.append((j / segments, i / rings))
        row = segments + 1
        for i in range(rings):
            for j in range(segments):
                a, b = i * row + j, i * row + j + 1          # upper edge
                c, d = (i + 1) * row + j, (i + 1) * row + j + 1  # lower edge
                if i != 0:
                    self.indices += [a, c, b]
                if i != rings - 1:
                    self.indices += [b, c, d]
        for t in range(0, len(self.indices), 3):  # every face points outward
            p0, p1, p2 = (self.positions[k] for k in self.indices[t:t + 3])
            centre = tuple(sum(x) / 3 for x in zip(p0, p1, p2))
            assert dot(cross(sub(p1, p0), sub(p2, p0)), centre) > 0

    def triangles(self):
        return len(self.indices) // 3


def add_sphere_accessors(w, sphere):
    """POSITION, NORMAL, TEXCOORD_0 and index accessors, shared by every mesh
    that draws this sphere; returns the attributes dict and the indices."""
    pos = w.add_vec3(sphere.positions)
    nrm = w.add_vec3(sphere.normals, with_bounds=False)
    uv_view = w.add_view(b"".join(struct.pack("<2f", *uv) for uv in sphere.uvs),
                         target=ARRAY_BUFFER)
    uv = w.add_accessor(uv_view, FLOAT, len(sphere.uvs), "VEC2")
    idx = w.add_indices(sphere.indices)
    return {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}, idx


def sphere_mesh(w, name, accessors, material):
    attributes, idx = accessors
    prim = w.primitive(attributes["POSITION"], attributes["NORMAL"], idx, material)
    prim["attributes"]["TEXCOORD_0"] = attributes["TEXCOORD_0"]
    return w.add_mesh(name, [prim])


def sphere_node(w, name, mesh_index, centre, radius):
    return w.add_node(name, mesh=mesh_index, translation=list(centre), scale=[radius] * 3)


def sweep(profile, x0, x1):
    """Studio backdrop: the (y, z) polyline `profile` extruded along x in
    [x0, x1], with smooth normals (the profile's vertex normals) facing up
    and towards +z (the side the scene is on). Returns (positions, normals,
    indices) of one indexed strip."""
    n = len(profile)
    normals2 = []
    for k in range(n):
        a, b = profile[max(k - 1, 0)], profile[min(k + 1, n - 1)]
        ty, tz = b[0] - a[0], b[1] - a[1]
        length = math.hypot(ty, tz)
        normals2.append((-tz / length, ty / length))  # tangent turned towards +y/+z
    positions, normals, indices = [], [], []
    for (y, z), (ny, nz) in zip(profile, normals2):
        positions += [(x0, y, z), (x1, y, z)]
        normals += [(0.0, ny, nz)] * 2
    for k in range(n - 1):
        a, b, c, d = 2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3
        indices += [a, b, d, a, d, c]
    p0, p1, p2 = positions[0], positions[1], positions[3]
    assert dot(cross(sub(p1, p0), sub(p2, p0)), normals[0]) > 0, "sweep faces the wrong way"
    return positions, normals, indices


def sweep_profile(front, floor_back, radius, top, bend_steps=8):
    """Floor y = 0 from z = front back to z = floor_back, a quarter-circle
    bend of `radius`, then a wall at z = floor_back - radius up to y = top,
    as (y, z) points from the front edge upwards."""
    pts = [(0.0, front), (0.0, floor_back)]
    for k in range(1, bend_steps + 1):
        a = 0.5 * math.pi * k / bend_steps
        pts.append((radius - radius * math.cos(a), floor_back - radius * math.sin(a)))
    pts.append((top, floor_back - radius))
    return pts


def rect(centre, right, up, half_w, half_h):
    """Quad centred at `centre` spanning +-half_w along `right` and +-half_h
    along `up` (unit vectors); its front face is cross(right, up)."""
    r = tuple(x * 2 * half_w for x in right)
    u = tuple(x * 2 * half_h for x in up)
    origin = tuple(c - x * half_w - y * half_h for c, x, y in zip(centre, right, up))
    return Quads().add(origin, r, u, cross(right, up))


def look_at_rotation(eye, target):
    """Quaternion (x, y, z, w) turning the glTF camera (looking down -Z, +Y
    up) to look from eye at target with no roll (yaw about Y, then pitch)."""
    d = normalize(sub(target, eye))
    yaw = math.atan2(-d[0], -d[2])
    pitch = math.asin(d[1])
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    # q = q_yaw(Y) * q_pitch(X)
    return [cy * sp, sy * cp, -sy * sp, cy * cp]


def emitter(w, name, strength, rgb=(1.0, 1.0, 1.0)):
    """Black, purely emissive: radiance rgb * strength from the front face."""
    return w.add_material(name, base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                          emissive=list(rgb), strength=strength, specular=0.0)


def glass(w, name, roughness):
    return w.add_material(name, base_color=(1, 1, 1, 1), metallic=0.0, roughness=roughness,
                          ior=1.5, transmission=1.0)


def finish(w, roots):
    """Sets the scene and lists in extensionsUsed what the materials use."""
    w.set_scene(roots, name="Scene")
    used = sorted({e for m in w.doc.get("materials", []) for e in m.get("extensions", {})})
    w.use_extensions(used)
    return w.gltf_text()


def count_triangles(w):
    """Triangles drawn by the scene's nodes (instances counted per node)."""
    tris = 0
    for node in w.doc["nodes"]:
        if "mesh" in node:
            for prim in w.doc["meshes"][node["mesh"]]["primitives"]:
                acc = prim.get("indices")
                tris += (w.doc["accessors"][acc]["count"] if acc is not None else
                         w.doc["accessors"][prim["attributes"]["POSITION"]]["count"]) // 3
    return tris


# 1. Materials board ---------------------------------------------------------

BOARD_ROUGHNESS = (0.0, 0.1, 0.25, 0.5, 0.75, 1.0)
BOARD_ROWS = (  # name, z of the row, material factors (roughness per column)
    ("Gold", -1.45, dict(base_color=(1.0, 0.71, 0.29, 1.0), metallic=1.0)),
    ("Plastic", 0.0, dict(base_color=(0.7, 0.08, 0.05, 1.0), metallic=0.0, specular=1.0)),
    ("Black", 1.45, dict(base_color=(0.02, 0.02, 0.02, 1.0), metallic=0.0, specular=1.0)),
)
BOARD_RADIUS = 0.4
BOARD_GLASS = (("GlassSmooth", -1.0, 0.0), ("GlassRough", 1.0, 0.3))  # name, x, roughness
BOARD_GLASS_Z, BOARD_GLASS_RADIUS = 2.95, 0.45
BOARD_TEXTURED_X = 2.4  # textured spheres at -x (checker plastic) and +x (bumpy brushed metal)
TEXTURE_SIZE = 64
LINEAR, REPEAT = 9729, 10497


def texture(w, rows):
    """A LINEAR / REPEAT texture of an embedded PNG."""
    image = w._add("images", {"uri": data_uri(png(rows))})
    sampler = w._add("samplers", {"magFilter": LINEAR, "minFilter": LINEAR, "wrapS": REPEAT, "wrapT": REPEAT})
    return w._add("textures", {"source": image, "sampler": sampler})


def checker_plastic(w):
    """Plastic whose baseColor is an 8 x 4 checker (sRGB) over the sphere's uv."""
    n = TEXTURE_SIZE
    rows = [[(230, 200, 60) if ((x * 8 // n) + (y * 4 // n)) % 2 else (30, 60, 160) for x in range(n)]
            for y in range(n)]
    m = w.add_material("CheckerPlastic", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.3)
    w.doc["materials"][m]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture(w, rows)}
    return m


def bumpy_metal(w):
    """Metal with a tangent-space normal map of round bumps (12 x 6 over the
    uv square) and a metallicRoughness texture of rough and polished bands."""
    n = TEXTURE_SIZE
    normals, mr = [], []
    for y in range(n):
        nrow, mrow = [], []
        for x in range(n):
            # Height h = sin(2 pi 12 u) sin(2 pi 6 v) * a; normal = (-dh/du, -dh/dv, 1).
            u, v = (x + 0.5) / n, (y + 0.5) / n
            a = 0.02
            dhdu = a * 2 * math.pi * 12 * math.cos(2 * math.pi * 12 * u) * math.sin(2 * math.pi * 6 * v)
            dhdv = a * 2 * math.pi * 6 * math.sin(2 * math.pi * 12 * u) * math.cos(2 * math.pi * 6 * v)
            nx, ny, nz = -dhdu, dhdv, 1.0  # glTF: +Y of the map points to decreasing v
            k = 1.0 / math.sqrt(nx * nx + ny * ny + nz * nz)
            nrow.append(tuple(int(round((c * k * 0.5 + 0.5) * 255)) for c in (nx, ny, nz)))
            rough = 0.15 if (y * 8 // n) % 2 else 0.55
            mrow.append((0, int(round(rough * 255)), 255))
        normals.append(nrow)
        mr.append(mrow)
    m = w.add_material("BumpyMetal", base_color=(0.95, 0.93, 0.88, 1), metallic=1.0, roughness=1.0)
    pbr = w.doc["materials"][m]["pbrMetallicRoughness"]
    pbr["metallicRoughnessTexture"] = {"index": texture(w, mr)}
    w.doc["materials"][m]["normalTexture"] = {"index": texture(w, normals)}
    return m
BOARD_EYE, BOARD_TARGET, BOARD_YFOV = (0.0, 4.8, 8.6), (0.0, 0.1, 0.6), 30.0
BOARD_KEY = ((0.0, 5.5, 4.0), 2.6, 1.1, 9.0)   # centre, half width, half height, strength
BOARD_RIM = ((-5.5, 2.2, -0.5), 0.6, 1.5, 6.0)


def materials_board(lamps=True):
    """The board; lamps=False leaves only the environment (--env) to light it."""
    w = writer()
    sphere = Sphere(32, 16)
    acc = add_sphere_accessors(w, sphere)
    roots = []
    for row, z, factors in BOARD_ROWS:
        for c, r in enumerate(BOARD_ROUGHNESS):
            name = f"{row}R{r:g}"
            m = w.add_material(name, roughness=r, **factors)
            x = (c - (len(BOARD_ROUGHNESS) - 1) / 2) * 1.0
            roots.append(sphere_node(w, name, sphere_mesh(w, name, acc, m),
                                     (x, BOARD_RADIUS, z), BOARD_RADIUS))
    for name, x, r in BOARD_GLASS:
        m = glass(w, name, r)
        roots.append(sphere_node(w, name, sphere_mesh(w, name, acc, m),
                                 (x, BOARD_GLASS_RADIUS, BOARD_GLASS_Z), BOARD_GLASS_RADIUS))
    for name, x, material in (("Checker", -BOARD_TEXTURED_X, checker_plastic(w)),
                              ("Bumpy", BOARD_TEXTURED_X, bumpy_metal(w))):
        roots.append(sphere_node(w, name, sphere_mesh(w, name, acc, material),
                                 (x, BOARD_GLASS_RADIUS, BOARD_GLASS_Z), BOARD_GLASS_RADIUS))
    ground = lambert(w, "Ground", (0.4, 0.4, 0.4))
    pos, nrm, idx = sweep(sweep_profile(front=9.0, floor_back=-2.5, radius=2.5, top=9.0), -12, 12)
    roots.append(w.add_node("Sweep", mesh=w.add_triangles("Sweep", pos, nrm, idx, ground)))
    if not lamps:
        return board_camera(w, roots)
    # Key: a wide softbox above the camera side, tilted down at the board.
    centre, hw, hh, le = BOARD_KEY
    facing = normalize(sub((0.0, 0.0, 0.3), centre))
    right = (1.0, 0.0, 0.0)
    up = normalize(cross(facing, right))       # cross(right, up) = facing
    key = rect(centre, right, up, hw, hh)
    roots.append(w.add_node("KeyLight", mesh=mesh(w, "KeyLight", key, emitter(w, "Key", le))))
    # Rim: a tall narrow strip on the left, facing the board.
    centre, hw, hh, le = BOARD_RIM
    facing = normalize(sub((0.0, 0.4, 0.0), centre))
    up = (0.0, 1.0, 0.0)
    right = normalize(cross(up, facing))       # cross(right, up) = facing
    up = cross(facing, right)
    rim = rect(centre, right, up, hw, hh)
    roots.append(w.add_node("RimLight", mesh=mesh(w, "RimLight", rim,
                                                  emitter(w, "Rim", le, (1.0, 0.9, 0.8)))))
    return board_camera(w, roots)


def board_camera(w, roots):
    cam = w.add_perspective("Camera", math.radians(BOARD_YFOV), znear=0.05, aspect_ratio=16 / 9)
    roots.append(w.add_node("Camera", camera=cam, translation=list(BOARD_EYE),
                            rotation=look_at_rotation(BOARD_EYE, BOARD_TARGET)))
    return w, finish(w, roots)


# 2. Cornell box with glass -------------------------------------------------

CORNELL_GLASS = ((0.42, 0.33, 0.3), 0.33)     # centre, radius: front right
CORNELL_MIRROR = ((-0.45, 0.36, -0.4), 0.36)  # back left


def cornell_glass():
    """make_scenes.cornell_box()'s room, lamp and camera; the boxes replaced
    by a smooth glass sphere and a mirror sphere."""
    w = writer()
    mats = cornell_materials(w)
    roots = [w.add_node(name, mesh=mesh(w, name, q, mats[m])) for name, q, m in cornell_room()]
    acc = add_sphere_accessors(w, Sphere(48, 24))
    g = glass(w, "Glass", 0.0)
    mirror = w.add_material("Mirror", base_color=(0.95, 0.95, 0.95, 1.0), metallic=1.0,
                            roughness=0.0)
    for name, m, (centre, radius) in (("GlassSphere", g, CORNELL_GLASS),
                                      ("MirrorSphere", mirror, CORNELL_MIRROR)):
        roots.append(sphere_node(w, name, sphere_mesh(w, name, acc, m), centre, radius))
    roots.append(w.add_node("Camera", camera=camera(w, "Camera", 40.0),
                            translation=list(CORNELL_CAMERA)))
    return w, finish(w, roots)


# 3. Veach MIS -------------------------------------------------------------

VEACH_EYE, VEACH_TARGET, VEACH_YFOV = (0.0, 2.0, 15.0), (0.0, -2.0, 2.5), 30.0
VEACH_LIGHT_X = (-3.75, -1.25, 1.25, 3.75)
VEACH_LIGHT_RADIUS = (0.03, 0.09, 0.27, 0.81)   # x3 each
VEACH_LIGHT_LE_BIG = 1.0                        # radiance of the largest light
VEACH_LIGHT_Y, VEACH_LIGHT_Z = 0.0, 0.0
# Plates back (top of the image) to front: roughest first, as in the figure.
VEACH_ROUGHNESS = (0.35, 0.2, 0.1, 0.05)
VEACH_PLATES = ((-2.3, 0.9), (-2.9, 2.05), (-3.4, 3.25), (-3.8, 4.5))  # (y, z) of the centres
VEACH_PLATE_HALF = (4.2, 0.02, 0.5)            # half width (x), thickness, depth


def veach_strengths():
    """Equal power: Le r^2 is the same for all four (power = Le pi 4 pi r^2)."""
    big = VEACH_LIGHT_RADIUS[-1]
    return tuple(round(VEACH_LIGHT_LE_BIG * (big / r) ** 2, 6) for r in VEACH_LIGHT_RADIUS)


def plate(centre, normal, half):
    """Thin box: half[0] along x, half[1] along `normal`, half[2] along
    cross(x, normal); front faces outward."""
    ex = (1.0, 0.0, 0.0)
    en = normalize(normal)
    et = cross(ex, en)

    def to_world(p):
        return tuple(c + ex[i] * p[0] * half[0] + en[i] * p[1] * half[1] + et[i] * p[2] * half[2]
                     for i, c in enumerate(centre))
    return box_faces(inward=False).mapped(to_world)


def veach_mis():
    w = writer()
    roots = []
    back = lambert(w, "Backdrop", (0.2, 0.2, 0.2))
    pos, nrm, idx = sweep(sweep_profile(front=12.0, floor_back=-4.0, radius=3.0, top=12.0), -20, 20)
    # The sweep's floor sits below the lowest plate.
    pos = [(x, y - 5.0, z) for x, y, z in pos]
    roots.append(w.add_node("Backdrop", mesh=w.add_triangles("Backdrop", pos, nrm, idx, back)))
    light_centre = (0.0, VEACH_LIGHT_Y, VEACH_LIGHT_Z)
    for k, ((y, z), r) in enumerate(zip(VEACH_PLATES, VEACH_ROUGHNESS)):
        centre = (0.0, y, z)
        n = normalize(add(normalize(sub(VEACH_EYE, centre)), normalize(sub(light_centre, centre))))
        m = w.add_material(f"Plate{k}R{r:g}", base_color=(0.8, 0.8, 0.8, 1.0), metallic=1.0,
                           roughness=r)
        name = f"Plate{k}"
        roots.append(w.add_node(name, mesh=mesh(w, name, plate(centre, n, VEACH_PLATE_HALF), m)))
    acc = add_sphere_accessors(w, Sphere(24, 12))
    for k, (x, r, le) in enumerate(zip(VEACH_LIGHT_X, VEACH_LIGHT_RADIUS, veach_strengths())):
        name = f"Light{k}"
        m = emitter(w, f"Light{k}Le{le:g}", le)
        roots.append(sphere_node(w, name, sphere_mesh(w, name, acc, m),
                                 (x, VEACH_LIGHT_Y, VEACH_LIGHT_Z), r))
    cam = w.add_perspective("Camera", math.radians(VEACH_YFOV), znear=0.05, aspect_ratio=16 / 9)
    roots.append(w.add_node("Camera", camera=cam, translation=list(VEACH_EYE),
                            rotation=look_at_rotation(VEACH_EYE, VEACH_TARGET)))
    return w, finish(w, roots)


# 4. An environment map --------------------------------------------------------

SKY_SIZE = (256, 128)
SKY_SUN = (0.62, 0.28, 0.012)  # u, v of the sun's centre, angular radius in v units


def sky_texel(u, v):
    """Linear radiance of a clear sky: a horizon-to-zenith gradient, a warm
    ground below the horizon (v > 1/2), a small sun of radiance 2000."""
    su, sv, sr = SKY_SUN
    du = min(abs(u - su), 1.0 - abs(u - su)) * 2.0  # u spans twice the angle of v
    if du * du + (v - sv) ** 2 < sr * sr:
        return (2000.0, 1850.0, 1600.0)
    if v < 0.5:
        t = v / 0.5  # 0 at the zenith, 1 at the horizon
        glow = 1.0 + 0.8 * math.exp(-((du ** 2 + (v - sv) ** 2) / 0.02))
        return ((0.15 + 0.6 * t) * glow, (0.3 + 0.55 * t) * glow, (0.8 + 0.2 * t) * glow)
    return (0.25, 0.2, 0.14)


def write_sky(path):
    """Radiance RGBE (.hdr), flat scanlines, row 0 at the top (+Y)."""
    w, h = SKY_SIZE
    data = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {h} +X {w}\n".encode())
    for y in range(h):
        for x in range(w):
            data += rgbe(*sky_texel((x + 0.5) / w, (y + 0.5) / h))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(bytes(data))
    print("wrote", path)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "scenes")
    write_sky(os.path.join(out, "env", "sky.hdr"))
    for name, build in (("materials-board.gltf", materials_board),
                        ("materials-board-env.gltf", lambda: materials_board(lamps=False)),
                        ("cornell-glass.gltf", cornell_glass),
                        ("veach-mis.gltf", veach_mis)):
        w, text = build()
        write(out, name, text)
        print(f"  {count_triangles(w)} triangles")


if __name__ == "__main__":
    main()
