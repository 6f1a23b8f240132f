#!/usr/bin/env python3
"""Writes the texture test scenes (tests/data/textures/): Python 3 stdlib only,
PNG images written with zlib + struct. Deterministic: running it again
rewrites identical bytes. All content is our own (CC0).

    python3 scripts/make_texture_scenes.py [OUTDIR]     (default tests/data/textures)

The numbers below are mirrored in tests/test_textures.cpp; change both.

"Direct" scenes (seen at max depth 0): a camera at (0, 0, 2) looking down -Z,
yfov 2 atan(1/2), aspect 1, sees exactly the quad [-1, 1]^2 at z = 0 (front
face +Z). The quad's uv is affine in the image: pixel centre (s, t) in [0, 1]^2
(s = (px + 0.5) / W, t = (py + 0.5) / H) sees uv = UV0 + (s, t) * UV_SPAN.
Its material is black with emissiveFactor EMISSIVE times the texture.

Alpha scenes: the same emitter quad (white, radiance 1, no texture) behind a
blocker quad [-0.75, 0.75]^2 at z = 0.5 that fills the view exactly; the
blocker's uv is (s, t) as above.

Normal-map scenes: the square light of scenes/square-light.gltf (side 1 at
height 1, radiance 1, facing down) over the plane y = 0 (baseColor 0.5,
metallic 0, KHR_materials_specular 0: Lambertian), uv = ((x + 10) / 20,
(z + 10) / 20), no TANGENT (the loader generates it: +X, w = +1); the camera
at (0, 0.9, 0) looks straight down (its up is -Z), yfov 60 degrees.
plane-half-light.gltf gives the light a 2 x 1 NEAREST emissive texture, white
then black along u = x + 0.5: only its half x < 0 emits.
"""

import base64
import math
import os
import random
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)

from gltf_writer import FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, GltfWriter  # noqa: E402

GENERATOR = "strata scripts/make_texture_scenes.py"
COPYRIGHT = "CC0 1.0 (public domain), the strata authors"

NEAREST, LINEAR = 9728, 9729
REPEAT, CLAMP, MIRROR = 10497, 33071, 33648

EMISSIVE = (1.0, 0.5, 0.25)
# 4 x 2 RGB texels, sRGB bytes, rows top to bottom.
CHECKER = [[(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255)],
           [(10, 20, 30), (128, 64, 200), (40, 200, 90), (0, 0, 0)]]
# 3 x 2 RGBA texels, 16-bit.
CHECKER16 = [[(65535, 0, 1000, 65535), (300, 40000, 65535, 65535), (12345, 54321, 7, 65535)],
             [(0, 0, 0, 65535), (65535, 65535, 65535, 65535), (32768, 16384, 49152, 65535)]]
# Alpha mask: 8 x 8, alpha 127 (0.498 < cutoff 0.5: a hole) and 128 (kept),
# in a checkerboard; rgb white.
MASK_ALPHA = (127, 128)
BLEND_ALPHA = 0.3
FLAT_NORMAL = (128, 128, 255)
TILTED_NORMAL = (191, 128, 221)


def png(rows, bits=8, channels=None):
    """PNG bytes of rows of pixel tuples (grey, RGB or RGBA by tuple length)."""
    channels = channels or len(rows[0][0])
    color_type = {1: 0, 3: 2, 4: 6}[channels]
    fmt = ">" + ("B" if bits == 8 else "H") * channels
    raw = b"".join(b"\0" + b"".join(struct.pack(fmt, *p) for p in row) for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", len(rows[0]), len(rows), bits, color_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


def data_uri(png_bytes):
    return "data:image/png;base64," + base64.b64encode(png_bytes).decode("ascii")


class Scene:
    def __init__(self):
        self.w = GltfWriter(GENERATOR, COPYRIGHT)
        self.roots = []

    def vec(self, values, count, type_, component=FLOAT, normalized=False, fmt="<f", stride=None):
        view = self.w.add_view(b"".join(struct.pack(fmt, v) for v in values), stride=stride)
        acc = self.w.add_accessor(view, component, count, type_)
        if normalized:
            self.w.doc["accessors"][acc]["normalized"] = True
        return acc

    def image(self, uri):
        return self.w._add("images", {"uri": uri})

    def texture(self, image, wrap_s=REPEAT, wrap_t=REPEAT, mag=NEAREST):
        sampler = self.w._add("samplers", {"magFilter": mag, "minFilter": mag,
                                           "wrapS": wrap_s, "wrapT": wrap_t})
        return self.w._add("textures", {"source": image, "sampler": sampler})

    def material(self, **fields):
        return self.w._add("materials", fields)

    def quad(self, name, corners, uvs, material, normal, uv_sets=None, tangents=None):
        """Quad c0 c1 c2 c3 (counter-clockwise seen from `normal`), uv per corner."""
        attributes = {"POSITION": self.w.add_vec3(corners),
                      "NORMAL": self.w.add_vec3([normal] * 4, with_bounds=False)}
        for i, uv in enumerate(uv_sets or [uvs]):
            attributes[f"TEXCOORD_{i}"] = self.vec([c for p in uv for c in p], 4, "VEC2")
        if tangents is not None:
            attributes["TANGENT"] = self.vec([c for t in tangents for c in t], 4, "VEC4")
        prim = {"attributes": attributes, "indices": self.w.add_indices([0, 1, 2, 0, 2, 3]),
                "material": material}
        mesh = self.w.add_mesh(name, [prim])
        self.roots.append(self.w.add_node(name, mesh=mesh))

    def camera(self, yfov, translation, rotation=None):
        cam = self.w.add_perspective("Camera", yfov, aspect_ratio=1.0)
        fields = {"camera": cam, "translation": list(translation)}
        if rotation:
            fields["rotation"] = rotation
        self.roots.append(self.w.add_node("Camera", **fields))

    def write(self, path, extensions=()):
        self.w.set_scene(self.roots)
        if extensions:
            self.w.use_extensions(list(extensions))
        self.w.write_gltf(path)


def view_quad(z, half):
    return [(-half, -half, z), (half, -half, z), (half, half, z), (-half, half, z)]


def uv_corners(uv0, span):
    """uv at the quad corners (-1,-1), (1,-1), (1,1), (-1,1): t grows downwards."""
    (u0, v0), (du, dv) = uv0, span
    return [(u0, v0 + dv), (u0 + du, v0 + dv), (u0 + du, v0), (u0, v0)]


def direct_scene(path, image_uri, uv0=(0, 0), span=(1, 1), wrap=(REPEAT, REPEAT), mag=NEAREST,
                 transform=None, tex_coord=None, uv_sets=None, index=None):
    s = Scene()
    tex = s.texture(s.image(image_uri), wrap[0], wrap[1], mag)
    info = {"index": tex if index is None else index}
    if transform is not None:
        info["extensions"] = {"KHR_texture_transform": transform}
    if tex_coord is not None:
        info["texCoord"] = tex_coord
    mat = s.material(name="Emitter", pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1],
                                                           "metallicFactor": 0.0},
                     emissiveFactor=list(EMISSIVE), emissiveTexture=info)
    s.quad("Quad", view_quad(0.0, 1.0), uv_corners(uv0, span), mat, (0, 0, 1), uv_sets=uv_sets)
    s.camera(2 * math.atan(0.5), (0, 0, 2))
    s.write(path, ["KHR_texture_transform"] if transform is not None else ())


def alpha_scene(path, blocker_material):
    s = Scene()
    light = s.material(name="Light", pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1],
                                                           "metallicFactor": 0.0},
                       emissiveFactor=[1, 1, 1])
    s.quad("Light", view_quad(0.0, 1.0), uv_corners((0, 0), (1, 1)), light, (0, 0, 1))
    mat = blocker_material(s)
    s.quad("Blocker", view_quad(0.5, 0.75), uv_corners((0, 0), (1, 1)), mat, (0, 0, 1))
    s.camera(2 * math.atan(0.5), (0, 0, 2))
    s.write(path)


def plane_scene(path, normal_rgb, half_light=False):
    s = Scene()
    pbr = {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0.0}
    fields = {"name": "Plane", "pbrMetallicRoughness": pbr,
              "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
    if normal_rgb is not None:
        img = s.image(data_uri(png([[normal_rgb] * 2] * 2)))
        fields["normalTexture"] = {"index": s.texture(img, mag=LINEAR)}
    plane = s.material(**fields)
    corners = [(-10, 0, 10), (10, 0, 10), (10, 0, -10), (-10, 0, -10)]
    uvs = [((x + 10) / 20, (z + 10) / 20) for x, _, z in corners]
    s.quad("Plane", corners, uvs, plane, (0, 1, 0))
    light_fields = {}
    if half_light:  # emissive texture: white for x < 0, black for x > 0 (u = x + 0.5)
        img = s.image(data_uri(png([[(255, 255, 255), (0, 0, 0)]])))
        light_fields["emissiveTexture"] = {"index": s.texture(img, CLAMP, CLAMP)}
    light = s.material(name="Light", pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1],
                                                           "metallicFactor": 0.0},
                       emissiveFactor=[1, 1, 1], **light_fields)
    lamp = [(-0.5, 1, -0.5), (0.5, 1, -0.5), (0.5, 1, 0.5), (-0.5, 1, 0.5)]
    s.quad("Light", lamp, [(x + 0.5, z + 0.5) for x, _, z in lamp], light, (0, -1, 0))
    half = -math.pi / 4  # rotation about +X by -90 degrees: -Z (forward) turns to -Y
    s.camera(math.radians(60), (0, 0.9, 0), [math.sin(half), 0, 0, math.cos(half)])
    s.write(path, ["KHR_materials_specular"])


def loader_scene(path):
    """CPU loader checks: TEXCOORD_0 normalized u8, TEXCOORD_1 normalized u16,
    TANGENT, on a node mirrored in x (scale -1, 1, 1); a second primitive
    without texture coordinates. No camera, no light."""
    s = Scene()
    w = s.w
    pos = w.add_vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    nrm = w.add_vec3([(0, 0, 1)] * 3, with_bounds=False)
    # u8 pairs padded to a 4-byte stride (glTF 3.6.2.4: attributes are 4-byte aligned).
    uv0 = s.vec([0, 255, 0, 0, 51, 102, 0, 0, 255, 0, 0, 0], 3, "VEC2", UNSIGNED_BYTE, True,
                "<B", stride=4)
    uv1 = s.vec([0, 65535, 13107, 0, 65535, 32768], 3, "VEC2", UNSIGNED_SHORT, True, "<H")
    tan = s.vec([1, 0, 0, 1] * 3, 3, "VEC4")
    img = s.image(data_uri(png([[FLAT_NORMAL]])))
    mat = s.material(name="Mapped", normalTexture={"index": s.texture(img), "scale": 0.5})
    textured = {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv0,
                               "TEXCOORD_1": uv1, "TANGENT": tan}, "material": mat}
    plain = {"attributes": {"POSITION": pos}}
    first = w.add_node("Plain", mesh=w.add_mesh("Plain", [plain]))
    mirrored = w.add_node("Mirrored", mesh=w.add_mesh("Textured", [textured]), scale=[-1, 1, 1])
    s.roots += [first, mirrored]
    s.write(path)


def broken_scenes(out):
    """Each fails to load with one error line (tests/test_textures.cpp)."""
    with open(os.path.join(out, "corrupt.png"), "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + b"this is not a PNG stream" * 4)
    direct_scene(os.path.join(out, "missing-image.gltf"), "does-not-exist.png")
    direct_scene(os.path.join(out, "corrupt-image.gltf"), "corrupt.png")
    open(os.path.join(out, "empty.png"), "wb").close()
    direct_scene(os.path.join(out, "empty-image.gltf"), "empty.png")
    direct_scene(os.path.join(out, "directory-image.gltf"), ".")  # the folder itself
    direct_scene(os.path.join(out, "missing-texcoord.gltf"), "checker.png", tex_coord=1)
    direct_scene(os.path.join(out, "bad-texture-index.gltf"), "checker.png", index=3)  # of 1


def checker_emitter(s, name):
    """A material emitting a 64x64 checker of single texels (sRGB 0 and 255,
    bilinear, repeated), on black."""
    rows = [[(255, 255, 255) if (x + y) % 2 else (0, 0, 0) for x in range(64)] for y in range(64)]
    tex = s.texture(s.image(data_uri(png(rows))), REPEAT, REPEAT, LINEAR)
    return s.material(name=name, pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                      emissiveFactor=[1, 1, 1], emissiveTexture={"index": tex})


def receding_scene(path):
    """A floor (x in [-20, 20], z in [-60, 0], y = 0) emitting a 64x64
    checker of single texels (sRGB 0 and 255, bilinear, repeated once per
    world unit), seen from (0, 1, 2) looking 15 degrees down: minified by up
    to hundreds of texels per pixel towards the horizon (texture LOD)."""
    s = Scene()
    mat = checker_emitter(s, "Floor")
    s.quad("Floor", [(-20, 0, 0), (20, 0, 0), (20, 0, -60), (-20, 0, -60)],
           [(0, 0), (40, 0), (40, 60), (0, 60)], mat, (0, 1, 0))
    a = math.radians(-15) / 2
    s.camera(2 * math.atan(0.5), (0, 1, 2), [math.sin(a), 0, 0, math.cos(a)])
    s.write(path)


def receding_octaves_scene(path):
    """receding.gltf's floor emitting a 256x256 texture with detail at every
    level: the sum of checkers of 1 to 32 texels (weights 1/sqrt(2)^k) in
    red, its complement in green, a ramp in blue; repeated 10 x 15 times.
    docs/benchmarks.md measures texture LOD's error and blur on it (a
    single-texel checker is uniform from its second level on, so it cannot
    show blur)."""
    n, sizes = 256, [1, 2, 4, 8, 16, 32]
    total = sum(0.5 ** (k * 0.5) for k in range(len(sizes)))
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            v = sum(((x // c + y // c) % 2) * 0.5 ** (k * 0.5) for k, c in enumerate(sizes)) / total
            row.append((round(255 * v), round(255 * (1 - v)), x * 255 // (n - 1)))
        rows.append(row)
    s = Scene()
    tex = s.texture(s.image(data_uri(png(rows))), REPEAT, REPEAT, LINEAR)
    mat = s.material(name="Floor", pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                     emissiveFactor=[1, 1, 1], emissiveTexture={"index": tex})
    s.quad("Floor", [(-20, 0, 0), (20, 0, 0), (20, 0, -60), (-20, 0, -60)],
           [(0, 0), (10, 0), (10, 15), (0, 15)], mat, (0, 1, 0))
    a = math.radians(-15) / 2
    s.camera(2 * math.atan(0.5), (0, 1, 2), [math.sin(a), 0, 0, math.cos(a)])
    s.write(path)


def receding_bumps_scene(path):
    """A glossy metal floor (x in [-20, 20], z in [-60, 0]) whose 64x64
    normal map tilts each texel at random (slopes uniform in [-0.6, 0.6],
    bilinear, repeated twice per world unit), under a lit wall at its far end
    (z = -60, y in [0, 20]), seen as receding.gltf is. Far away, the mip
    levels average the bumps to a flat normal; the wall's reflection must
    stay as blurred as the bumps make it (Toksvig's roughness,
    docs/experiments/textures.md)."""
    rng = random.Random(11)
    rows = []
    for _ in range(64):
        row = []
        for _ in range(64):
            sx, sy = rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6)
            inv = 1.0 / math.sqrt(sx * sx + sy * sy + 1.0)
            row.append(tuple(round(255 * (0.5 * c * inv + 0.5)) for c in (sx, sy, 1.0)))
        rows.append(row)
    s = Scene()
    tex = s.texture(s.image(data_uri(png(rows))), REPEAT, REPEAT, LINEAR)
    floor = s.material(name="Floor", pbrMetallicRoughness={"baseColorFactor": [0.9, 0.9, 0.9, 1],
                                                           "metallicFactor": 1.0, "roughnessFactor": 0.2},
                       normalTexture={"index": tex})
    s.quad("Floor", [(-20, 0, 0), (20, 0, 0), (20, 0, -60), (-20, 0, -60)],
           [(0, 0), (80, 0), (80, 120), (0, 120)], floor, (0, 1, 0))
    wall = s.material(name="Wall", pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                      emissiveFactor=[1, 1, 1])
    s.quad("Wall", [(-20, 0, -60), (20, 0, -60), (20, 20, -60), (-20, 20, -60)],
           [(0, 0), (1, 0), (1, 1), (0, 1)], wall, (0, 0, 1))
    a = math.radians(-15) / 2
    s.camera(2 * math.atan(0.5), (0, 1, 2), [math.sin(a), 0, 0, math.cos(a)])
    s.write(path)


def lod_plane_scene(path, transform=None):
    """The plane z = 0 (x, y in [-10, 10], facing +Z) emitting a 64x64
    checker of single texels (bilinear) repeated 10 times across: a texel is
    20 / 640 world units. The test views it from several places (texture
    LOD's level against the ray cone's footprint). With `transform`, the
    emissive texture's KHR_texture_transform (lod-plane-transform.gltf: a
    scale of 2 turned and shifted, texels of 20 / 1280)."""
    s = Scene()
    mat = checker_emitter(s, "Plane")
    if transform is not None:
        s.w.doc["materials"][mat]["emissiveTexture"]["extensions"] = {"KHR_texture_transform": transform}
    s.quad("Plane", view_quad(0.0, 10.0), [(0, 10), (10, 10), (10, 0), (0, 0)], mat, (0, 0, 1))
    s.camera(math.radians(20), (0, 0, 4))
    s.write(path, ["KHR_texture_transform"] if transform is not None else ())


def lod_mirror_scene(path):
    """lod-plane.gltf's plane and a mirror (metal, white, smooth) at (0, 0, 3)
    facing (0, -1, -1): the camera at (0, -1.5, 3) looking along +Y sees the
    plane 3 below the mirror (texture LOD after a delta bounce)."""
    s = Scene()
    plane = checker_emitter(s, "Plane")
    s.quad("Plane", view_quad(0.0, 10.0), [(0, 10), (10, 10), (10, 0), (0, 0)], plane, (0, 0, 1))
    mirror = s.material(name="Mirror", pbrMetallicRoughness={"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 1.0,
                                                             "roughnessFactor": 0.0})
    h = 1.0 / math.sqrt(2)
    n = (0, -h, -h)
    s.quad("Mirror", [(-1, h, 3 - h), (1, h, 3 - h), (1, -h, 3 + h), (-1, -h, 3 + h)],
           [(0, 0), (1, 0), (1, 1), (0, 1)], mirror, n)
    a = math.radians(90) / 2  # the camera's -Z turned to +Y
    s.camera(math.radians(20), (0, -1.5, 3), [math.sin(a), 0, 0, math.cos(a)])
    s.write(path)


def leaves_rows(size=256, seed=7, coverage=0.35):
    """A tileable cut-out: discs of radius 4-12 texels (leaf: sRGB green,
    alpha 255) on holes (sRGB red, alpha 0) until `coverage` of the texels
    are leaf."""
    rng = random.Random(seed)
    leaf = [[False] * size for _ in range(size)]
    kept = 0
    while kept < coverage * size * size:
        cx, cy, r = rng.randrange(size), rng.randrange(size), rng.uniform(4, 12)
        for y in range(int(cy - r), int(cy + r) + 1):
            for x in range(int(cx - r), int(cx + r) + 1):
                if (x - cx) ** 2 + (y - cy) ** 2 <= r * r and not leaf[y % size][x % size]:
                    leaf[y % size][x % size] = True
                    kept += 1
    return [[(0, 255, 0, 255) if leaf[y][x] else (255, 0, 0, 0) for x in range(size)] for y in range(size)]


def foliage_scene(path):
    """A cut-out plane (z = 1, x and y in [-2, 2]) of leaves_rows repeated 8
    times across (MASK, cutoff 0.5, bilinear), its leaves emitting their
    colour (the same texture as emissive), in front of a blue emitter (z = 0),
    seen from (0, 0, 4): minified about 24 texels a pixel at 64x64 (texture
    LOD's alpha coverage and the colour of its levels)."""
    s = Scene()
    backdrop = s.material(name="Backdrop", pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1],
                                                                 "metallicFactor": 0.0},
                          emissiveFactor=[0, 0, 1])
    s.quad("Backdrop", view_quad(0.0, 20.0), uv_corners((0, 0), (1, 1)), backdrop, (0, 0, 1))
    tex = s.texture(s.image(data_uri(png(leaves_rows()))), REPEAT, REPEAT, LINEAR)
    leaves = s.material(name="Leaves", alphaMode="MASK", alphaCutoff=0.5,
                        pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0,
                                              "baseColorTexture": {"index": tex}},
                        emissiveFactor=[1, 1, 1], emissiveTexture={"index": tex})
    s.quad("Leaves", view_quad(1.0, 2.0), uv_corners((0, 0), (8, 8)), leaves, (0, 0, 1))
    s.camera(2 * math.atan(0.5), (0, 0, 4))
    s.write(path)


def lod_sphere_scene(path):
    """A smooth white metal mirror sphere (radius 1 at (0, 0, -4), 48 x 24
    segments, its vertex normals exact) seen from the origin along -Z (20
    degrees), reflecting a plane behind the camera (z = 0.5, facing -Z,
    x and y in [-12.8, 12.8]) that emits a 64x64 checker of single texels
    repeated twice across: a texel is 0.2 world units (texture LOD after a
    reflection off a curved surface)."""
    s = Scene()
    plane = checker_emitter(s, "Plane")
    h = 12.8
    s.quad("Plane", [(h, -h, 0.5), (-h, -h, 0.5), (-h, h, 0.5), (h, h, 0.5)],
           [(0, 2), (2, 2), (2, 0), (0, 0)], plane, (0, 0, -1))
    mirror = s.material(name="Mirror", pbrMetallicRoughness={"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 1.0,
                                                             "roughnessFactor": 0.0})
    rings, segments, centre = 24, 48, (0.0, 0.0, -4.0)
    normals = []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            normals.append((math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)))
    points = [tuple(c + n for c, n in zip(centre, v)) for v in normals]
    indices = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            if i > 0:
                indices += [a, a + 1, b]
            if i < rings - 1:
                indices += [a + 1, b + 1, b]
    prim = {"attributes": {"POSITION": s.w.add_vec3(points), "NORMAL": s.w.add_vec3(normals, with_bounds=False)},
            "indices": s.w.add_indices(indices), "material": mirror}
    s.roots.append(s.w.add_node("Sphere", mesh=s.w.add_mesh("Sphere", [prim])))
    s.camera(math.radians(20), (0, 0, 0))
    s.write(path)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "tests", "data", "textures")
    os.makedirs(os.path.join(out, "broken"), exist_ok=True)
    with open(os.path.join(out, "checker.png"), "wb") as f:
        f.write(png(CHECKER))
    with open(os.path.join(out, "broken", "checker.png"), "wb") as f:
        f.write(png(CHECKER))
    p = lambda name: os.path.join(out, name)  # noqa: E731
    direct_scene(p("nearest.gltf"), "checker.png")
    direct_scene(p("wrap-repeat.gltf"), "checker.png", (-1, -1), (3, 3), (REPEAT, REPEAT))
    direct_scene(p("wrap-clamp-mirror.gltf"), "checker.png", (-1, -1), (3, 3), (CLAMP, MIRROR))
    direct_scene(p("wrap-mirror-clamp.gltf"), "checker.png", (-1, -1), (3, 3), (MIRROR, CLAMP))
    # KHR_texture_transform, reading TEXCOORD_1 by its texCoord override
    # (TEXCOORD_0 is constant, so ignoring the override shows one texel).
    corners = uv_corners((0, 0), (1, 1))
    direct_scene(p("transform.gltf"), "checker.png",
                 transform={"offset": [0.25, -0.5], "rotation": 0.6, "scale": [1.5, -2.0],
                            "texCoord": 1},
                 uv_sets=[[(0.3, 0.3)] * 4, corners])
    direct_scene(p("bilinear.gltf"), "checker.png", wrap=(CLAMP, REPEAT), mag=LINEAR)
    direct_scene(p("nearest-16bit.gltf"), data_uri(png(CHECKER16, bits=16)))

    def mask_material(s):
        rows = [[(255, 255, 255, MASK_ALPHA[(x + y) % 2]) for x in range(8)] for y in range(8)]
        tex = s.texture(s.image(data_uri(png(rows))))
        return s.material(name="Mask", alphaMode="MASK", alphaCutoff=0.5,
                          pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1],
                                                "metallicFactor": 0.0,
                                                "baseColorTexture": {"index": tex}})

    def blend_material(s):
        return s.material(name="Blend", alphaMode="BLEND",
                          pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, BLEND_ALPHA],
                                                "metallicFactor": 0.0})
    alpha_scene(p("alpha-mask.gltf"), mask_material)
    alpha_scene(p("alpha-blend.gltf"), blend_material)
    plane_scene(p("plane-no-map.gltf"), None)
    plane_scene(p("plane-flat-map.gltf"), FLAT_NORMAL)
    plane_scene(p("plane-tilted-map.gltf"), TILTED_NORMAL)
    plane_scene(p("plane-half-light.gltf"), None, half_light=True)
    loader_scene(p("loader.gltf"))
    receding_scene(p("receding.gltf"))
    receding_octaves_scene(p("receding-octaves.gltf"))
    receding_bumps_scene(p("receding-bumps.gltf"))
    lod_plane_scene(p("lod-plane.gltf"))
    lod_plane_scene(p("lod-plane-transform.gltf"), {"scale": [2.0, 2.0], "rotation": 0.5, "offset": [0.3, 0.1]})
    lod_mirror_scene(p("lod-mirror.gltf"))
    lod_sphere_scene(p("lod-sphere.gltf"))
    foliage_scene(p("foliage.gltf"))
    broken_scenes(os.path.join(out, "broken"))


if __name__ == "__main__":
    main()
