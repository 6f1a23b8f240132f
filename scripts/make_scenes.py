#!/usr/bin/env python3
"""Writes the scenes strata ships (scenes/*.gltf) and the invariance test
scenes (tests/data/invariance/*.gltf); Python 3 stdlib only.

Each scene is one .gltf with its buffer embedded as a base64 data URI. The
output is deterministic: running this again rewrites identical bytes. All
geometry and numbers are our own (CC0). Front faces are counter-clockwise;
the renderer emits light from the front face only unless doubleSided.

    python3 scripts/make_scenes.py [OUTDIR]
        default: scenes/ and tests/data/invariance/;
        with OUTDIR: OUTDIR/ and OUTDIR/invariance/
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.dont_write_bytecode = True  # keep the tree free of __pycache__
sys.path.insert(0, HERE)

import square_light as analytic  # noqa: E402
from gltf_writer import UNSIGNED_INT, GltfWriter, f32  # noqa: E402

GENERATOR = "strata scripts/make_scenes.py"
COPYRIGHT = "CC0 1.0 (public domain), the strata authors"


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

    def mapped(self, transform):
        """The quads with every corner mapped by `transform` (affine, det > 0)
        on its own, so corners shared between quads stay shared; normals
        recomputed from the mapped corners."""
        out = Quads()
        for i in range(0, len(self.positions), 4):
            p = [transform(x) for x in self.positions[i:i + 4]]
            base = len(out.positions)
            out.positions += p
            out.normals += [normalize(cross(sub(p[1], p[0]), sub(p[3], p[0])))] * 4
            out.indices += [base, base + 1, base + 2, base, base + 2, base + 3]
        return out


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


def writer():
    return GltfWriter(GENERATOR, copyright=COPYRIGHT)


def lambert(w, name, rgb, emissive=None, strength=None):
    """Metallic 0 and no specular layer (KHR_materials_specular factor 0):
    exactly Lambertian with baseColor rgb."""
    return w.add_material(name, base_color=list(rgb) + [1.0], metallic=0.0, roughness=1.0,
                          emissive=emissive, strength=strength, specular=0.0)


def mesh(w, name, quads, material):
    return w.add_triangles(name, quads.positions, normals=quads.normals,
                           indices=quads.indices, material=material)


def camera(w, name, yfov_degrees, znear=0.01):
    return w.add_perspective(name, math.radians(yfov_degrees), znear=znear, aspect_ratio=1.0)


def rotation_y(degrees):
    """Quaternion (x, y, z, w) for a rotation about +Y."""
    h = math.radians(degrees) / 2
    return [0.0, math.sin(h), 0.0, math.cos(h)]


def rotation_x(radians):
    """Quaternion (x, y, z, w) for a rotation about +X."""
    return [math.sin(radians / 2), 0.0, 0.0, math.cos(radians / 2)]


def trs(translation, y_degrees, scale):
    """The map p -> T R_y S p of a glTF node (translation, rotation about +Y, scale)."""
    c, s = math.cos(math.radians(y_degrees)), math.sin(math.radians(y_degrees))

    def apply(p):
        x, y, z = (p[i] * scale[i] for i in range(3))
        return (c * x + s * z + translation[0], y + translation[1], -s * x + c * z + translation[2])
    return apply


# Cornell box: room x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +Z.
CORNELL_CAMERA = (0.0, 1.0, 3.8)   # looks down -Z (the glTF camera default), yfov 40 deg
CORNELL_BOXES = (                  # node name, translation, rotation about +Y (deg), scale
    ("ShortBox", (0.4, 0.0, 0.4), -18.0, (0.6, 0.6, 0.6)),
    ("TallBox", (-0.4, 0.0, -0.35), 17.0, (0.6, 1.2, 0.6)),
)


def cornell_room():
    """(name, quads, material name) of the room and the lamp, in world space."""
    up, down = (0, 1, 0), (0, -1, 0)
    return (
        ("Floor", Quads().add((-1, 0, -1), (0, 0, 2), (2, 0, 0), up), "White"),
        ("Ceiling", Quads().add((-1, 2, -1), (2, 0, 0), (0, 0, 2), down), "White"),
        ("BackWall", Quads().add((-1, 0, -1), (2, 0, 0), (0, 2, 0), (0, 0, 1)), "White"),
        ("LeftWall", Quads().add((-1, 0, -1), (0, 2, 0), (0, 0, 2), (1, 0, 0)), "Red"),
        ("RightWall", Quads().add((1, 0, -1), (0, 0, 2), (0, 2, 0), (-1, 0, 0)), "Green"),
        # 0.46 x 0.46 (23% of the ceiling width), 0.02 below the ceiling, facing down.
        ("Light", Quads().add((-0.23, 1.98, -0.23), (0.46, 0, 0), (0, 0, 0.46), down), "Light"),
    )


def cornell_unit_box():
    """Unit box x, z in [-0.5, 0.5], y in [0, 1], no bottom face; front faces out."""
    cube = box_faces(inward=False)
    box = Quads()
    for i in range(0, len(cube.positions), 4):
        n = cube.normals[i]
        if n[1] < -0.5:
            continue  # bottom
        p = [(x * 0.5, y * 0.5 + 0.5, z * 0.5) for x, y, z in cube.positions[i:i + 4]]
        box.add(p[0], sub(p[1], p[0]), sub(p[3], p[0]), n)
    return box


def cornell_materials(w):
    mats = {
        "White": lambert(w, "White", (0.73, 0.73, 0.73)),
        "Red": lambert(w, "Red", (0.63, 0.065, 0.05)),
        "Green": lambert(w, "Green", (0.14, 0.45, 0.09)),
        "Light": lambert(w, "Light", (0.73, 0.73, 0.73), emissive=(1.0, 1.0, 1.0), strength=15.0),
    }
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular"])
    return mats


def cornell_box():
    """The shipped scene: the two boxes are one mesh instanced by two TRS nodes."""
    w = writer()
    mats = cornell_materials(w)
    room = cornell_room()
    walls = [w.add_node(name, mesh=mesh(w, name, q, mats[m])) for name, q, m in room[:-1]]
    box = mesh(w, "Box", cornell_unit_box(), mats["White"])
    boxes = [w.add_node(name, mesh=box, translation=list(t), rotation=rotation_y(deg),
                        scale=list(s)) for name, t, deg, s in CORNELL_BOXES]
    name, q, m = room[-1]
    lamp = w.add_node(name, mesh=mesh(w, name, q, mats[m]))
    cam = w.add_node("Camera", camera=camera(w, "Camera", 40.0),
                     translation=list(CORNELL_CAMERA))
    w.set_scene(walls + boxes + [lamp, cam], name="Scene")
    return w.gltf_text()


def cornell_gold():
    """The Cornell box with a rough gold sphere (radius 0.3, metallic 1,
    roughness 0.3) where the short box stands: the glossy scene of the time
    to error against Cycles (issue 43)."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "data"))
    from make_lights import icosphere  # noqa: E402
    w = writer()
    mats = cornell_materials(w)
    gold = w.add_material("Gold", base_color=[1.0, 0.766, 0.336, 1.0], metallic=1.0, roughness=0.3)
    room = cornell_room()
    walls = [w.add_node(name, mesh=mesh(w, name, q, mats[m])) for name, q, m in room[:-1]]
    verts, faces = icosphere(4)
    sphere = w.add_triangles("Sphere", verts, normals=verts, indices=[i for f in faces for i in f],
                             material=gold, index_type=UNSIGNED_INT)
    ball = w.add_node("GoldSphere", mesh=sphere, translation=[0.4, 0.3, 0.4], scale=[0.3, 0.3, 0.3])
    name, t, deg, s = CORNELL_BOXES[1]
    box = w.add_node(name, mesh=mesh(w, "Box", cornell_unit_box(), mats["White"]),
                     translation=list(t), rotation=rotation_y(deg), scale=list(s))
    name, q, m = room[-1]
    lamp = w.add_node(name, mesh=mesh(w, name, q, mats[m]))
    cam = w.add_node("Camera", camera=camera(w, "Camera", 40.0),
                     translation=list(CORNELL_CAMERA))
    w.set_scene(walls + [ball, box, lamp, cam], name="Scene")
    return w.gltf_text()


def cornell_box_baked(transform, znear, lamp_grid=None):
    """The Cornell box with `transform` (affine, det > 0, no rotation) baked
    into the vertex data: every node has the identity transform, so the
    renderer sees the transformed world coordinates. The boxes are baked
    as two meshes; the camera moves with the scene. With lamp_grid, the
    lamp's corner and edges are rounded to multiples of lamp_grid (see
    snapped)."""
    w = writer()
    mats = cornell_materials(w)
    room = cornell_room()
    parts = [(name, q.mapped(transform), m) for name, q, m in room[:-1]]
    unit = cornell_unit_box()
    for name, t, deg, s in CORNELL_BOXES:
        local = trs(t, deg, s)
        parts.append((name, unit.mapped(lambda p, local=local: transform(local(p))), "White"))
    name, q, m = room[-1]
    lamp = q.mapped(transform)
    parts.append((name, lamp if lamp_grid is None else snapped(lamp, lamp_grid), m))
    roots = [w.add_node(name, mesh=mesh(w, name, q, mats[m])) for name, q, m in parts]
    roots.append(w.add_node("Camera", camera=camera(w, "Camera", 40.0, znear),
                            translation=list(transform(CORNELL_CAMERA))))
    w.set_scene(roots, name="Scene")
    return w.gltf_text()


def snap(v, grid):
    return tuple(round(c / grid) * grid for c in v)


def snapped(quads, grid):
    """Quads with each quad's first corner and its two edge vectors rounded
    to multiples of grid: where grid is the float32 spacing, every corner is
    exact in float32 and the edges keep their length to within grid / 2,
    where rounding each corner independently can change it by a full grid."""
    out = Quads()
    for i in range(0, len(quads.positions), 4):
        p = quads.positions[i:i + 4]
        u, v = snap(sub(p[1], p[0]), grid), snap(sub(p[3], p[0]), grid)
        out.add(snap(p[0], grid), u, v, cross(u, v))
    return out


def furnace(albedo=0.5, le=0.5):
    """Closed cube [-1, 1]^3 facing inward, emissive and diffuse everywhere."""
    w = writer()
    wall = lambert(w, "Furnace", (albedo, albedo, albedo), emissive=(le, le, le))
    roots = [
        w.add_node("Cube", mesh=mesh(w, "Cube", box_faces(inward=True), wall)),
        w.add_node("Camera", camera=camera(w, "Camera", 60.0)),  # at the centre, looking at -Z
    ]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_specular"])
    return w.gltf_text()


SQUARE_LIGHT_CAMERA = (0.0, 0.6, 2.5)   # looks at the origin, yfov 30 deg


def square_light(lower=0.0):
    """Known answer for direct lighting (scripts/square_light.py): a 20 x 20
    Lambertian plane y = 0 under a black, one-sided square emitter. `lower`
    moves the whole scene down (lower = h puts the emitter in the plane y = 0,
    where its coordinates give the shadow rays' end no rounding to scale by)."""
    w = writer()
    a, le = analytic.ALBEDO, analytic.LE
    hw, h = analytic.HALF_SIDE, analytic.HEIGHT
    plane = lambert(w, "Plane", (a, a, a))
    light = lambert(w, "Light", (0.0, 0.0, 0.0), emissive=(le, le, le))
    floor = Quads().add((-10, 0.0 - lower, -10), (0, 0, 20), (20, 0, 0), (0, 1, 0))
    lamp = Quads().add((-hw, h - lower, -hw), (2 * hw, 0, 0), (0, 0, 2 * hw), (0, -1, 0))
    x, y, z = SQUARE_LIGHT_CAMERA
    assert x == 0.0, "the camera only pitches"
    pitch = -math.atan2(y, z)  # about +X: -Z turns towards -Y
    roots = [
        w.add_node("Plane", mesh=mesh(w, "Plane", floor, plane)),
        w.add_node("Light", mesh=mesh(w, "Light", lamp, light)),
        w.add_node("Camera", camera=camera(w, "Camera", 30.0),
                   translation=[x, y - lower, z], rotation=rotation_x(pitch)),
    ]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_specular"])
    return w.gltf_text()


def translate(offset):
    return lambda p: tuple(x + o for x, o in zip(p, offset))


def scale(factor):
    return lambda p: tuple(x * factor for x in p)


def write(directory, name, text):
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, name)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    print("wrote", path)


# Invariance scenes (tests/data/invariance/): file, transform, znear, lamp grid, length scale.
# At 1e4 the float32 spacing is 2^-10 (floats in [2^13, 2^14)): rounding the
# lamp's corners independently would make its side 472/1024 instead of 0.46
# (area +0.41%), so the moved lamp is snapped to side 471/1024 (area -0.017%).
INVARIANCE = (
    ("cornell-moved.gltf", translate((1e4, 1e4, 1e4)), 0.01, 2.0 ** -10, 1.0),
    ("cornell-small.gltf", scale(1e-3), 0.01 * 1e-3, None, 1e-3),
    ("cornell-large.gltf", scale(1e3), 0.01 * 1e3, None, 1e3),
)


def lamp_area(quads):
    """Area of the first quad with its corners rounded to float32 (a parallelogram)."""
    p = [tuple(f32(x) for x in v) for v in quads.positions[:4]]
    n = cross(sub(p[1], p[0]), sub(p[3], p[0]))
    return math.sqrt(dot(n, n))


def main():
    if len(sys.argv) > 1:
        scenes_dir, invariance_dir = sys.argv[1], os.path.join(sys.argv[1], "invariance")
    else:
        scenes_dir = os.path.join(ROOT, "scenes")
        invariance_dir = os.path.join(ROOT, "tests", "data", "invariance")
    write(scenes_dir, "cornell-box.gltf", cornell_box())
    write(scenes_dir, "cornell-gold.gltf", cornell_gold())
    write(scenes_dir, "furnace.gltf", furnace())
    # Le = 0.1 is not a float32 dyadic: sums of it drift in float32.
    write(scenes_dir, "furnace-a0.8-le0.1.gltf", furnace(albedo=0.8, le=0.1))
    write(scenes_dir, "square-light.gltf", square_light())
    write(invariance_dir, "square-light-origin.gltf", square_light(lower=analytic.HEIGHT))
    lamp = [q for name, q, m in cornell_room() if name == "Light"][0]
    for name, transform, znear, grid, length in INVARIANCE:
        write(invariance_dir, name, cornell_box_baked(transform, znear, grid))
        moved = lamp.mapped(transform)
        if grid is not None:
            moved = snapped(moved, grid)
        ratio = lamp_area(moved) / length ** 2 / lamp_area(lamp)
        print(f"  float32 lamp area / original lamp area, in original units: {ratio:.6f}")


if __name__ == "__main__":
    main()
