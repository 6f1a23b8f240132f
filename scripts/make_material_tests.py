#!/usr/bin/env python3
"""Known-answer scenes for the BSDF render tests (tests/test_materials.cpp),
written to tests/data/materials/. Our own work, CC0.

mirror-*.gltf: a 6 x 6 floor y = 0 of one material under a one-sided square
emitter (side 2 * LAMP_HALF, at height LAMP_HEIGHT, facing down, radiance
LAMP_LE), seen by a camera that looks at the emitter's mirror image. With
maxDepth 1 a pixel whose every reflected ray meets the emitter shows
LAMP_LE times the floor's specular reflectance at that angle, and one whose
reflected rays all miss shows 0.

coat-*.gltf (KHR_materials_clearcoat), seen in a white furnace: a 40 x 40
plate z = 0 facing +Z under a smooth coat, seen by a camera 5 units away
(tests/test_material_layers.cpp). Every camera ray reflects off the coat
(and a smooth base) into the environment, so each pixel is the layers'
reflectance at its rays' incidence.

sheen-*.gltf (KHR_materials_sheen) are such plates under a sheen, seen
through a 1-degree field of view at the incidence cosine of a node of the
sheen albedo table (tools/sheen-albedo: mu_i = (i / 31)^3, roughness r_j =
(0.1 + 0.9 j / 31)^2), so the image mean is the sheen colour times the
table's E there (over black), or 1 (over white Lambert).

specular-*.gltf (KHR_materials_specular's colour) are such plates of a
smooth black dielectric with a specular colour, head-on (the spec's F0:
specular * min(F0 * specularColor, 1)) and at 60 degrees.

translucent-*.gltf (KHR_materials_diffuse_transmission, ior 1 so that no
Fresnel takes a share): such plates in a white furnace reflect (1 - factor)
baseColor and transmit factor diffuseTransmissionColor, so the image is
their sum; translucent-backlit.gltf is a sheet of ior 1.5 lit on its front
by a directional light and seen from behind at 60 degrees
(tests/test_diffuse_transmission.cpp has the closed form).

anisotropy-*.gltf (KHR_materials_anisotropy) are such plates of a white
GGX metal (roughness 0.3) of anisotropy strength 1, with texture
coordinates (u along +Y: the tangent) and anisotropyRotation 0 or pi/2,
seen at 60 degrees along the tangent through a 1-degree view: the image
is the lobe's directional albedo with the view along or across the
stretched axis.

layers.gltf holds the layer extensions' values and textures for the loader
tests, diffuse-transmission.gltf and anisotropy.gltf those extensions';
broken/ one bad value each.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tests", "data"))
from make_lights import add_sphere, icosphere  # noqa: E402
from make_scenes import Quads, camera, mesh, rotation_x, writer  # noqa: E402
from make_texture_scenes import LINEAR, Scene as TexturedScene, data_uri, png  # noqa: E402

GENERATOR = "strata scripts/make_material_tests.py"

LAMP_HALF = 0.5
LAMP_HEIGHT = 1.0
LAMP_LE = 2.0
CAMERA = (0.0, 0.8, 2.5)


def mirror_scene(floor_material):
    w = writer()
    floor = floor_material(w)
    lamp = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                          emissive=(1.0, 1.0, 1.0), strength=LAMP_LE, specular=0.0)
    h, y = LAMP_HALF, LAMP_HEIGHT
    floor_quad = Quads().add((-3, 0, -3), (0, 0, 6), (6, 0, 0), (0, 1, 0))
    lamp_quad = Quads().add((-h, y, -h), (2 * h, 0, 0), (0, 0, 2 * h), (0, -1, 0))
    x, cy, cz = CAMERA
    pitch = -math.atan2(cy + y, cz)  # towards the mirror image (0, -y, 0)
    roots = [
        w.add_node("Floor", mesh=mesh(w, "Floor", floor_quad, floor)),
        w.add_node("Lamp", mesh=mesh(w, "Lamp", lamp_quad, lamp)),
        w.add_node("Camera", camera=camera(w, "Camera", 40.0), translation=list(CAMERA),
                   rotation=rotation_x(pitch)),
    ]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_emissive_strength", "KHR_materials_specular"])
    return w.gltf_text()


def glass_sphere():
    """A faceted glass icosphere (level 3, flat facets: no normals), smooth,
    ior 1.5, white: under a uniform environment it vanishes (radiance 1 up
    to the depth cap). Camera at (0, 0, 3) looking down -Z."""
    w = writer()
    glass = w.add_material("Glass", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0,
                           transmission=1.0, ior=1.5)
    sphere = add_sphere(w, 3, glass, inward=False)
    roots = [w.add_node("Sphere", mesh=sphere),
             w.add_node("Camera", camera=camera(w, "Camera", 40.0), translation=[0, 0, 3])]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_ior", "KHR_materials_transmission"])
    return w.gltf_text()


def plate_scene(material, view_degrees, fov_degrees=2.0, extensions=()):
    """A 40 x 40 plate z = 0 facing +Z of material(w), seen at `view_degrees`
    from its normal (the camera turned about +X) by a camera 5 units away
    with a `fov_degrees` field of view."""
    w = writer()
    plate_material = material(w)
    quad = Quads().add((-20, -20, 0), (40, 0, 0), (0, 40, 0), (0, 0, 1))
    t = math.radians(view_degrees)
    roots = [w.add_node("Plate", mesh=mesh(w, "Plate", quad, plate_material)),
             w.add_node("Camera", camera=camera(w, "Camera", fov_degrees),
                        translation=[0.0, -5.0 * math.sin(t), 5.0 * math.cos(t)],
                        rotation=rotation_x(t))]
    w.set_scene(roots, name="Scene")
    if extensions:
        w.use_extensions(list(extensions))
    return w.gltf_text()


def plate(roughness, view_degrees):
    """A white GGX metal plate seen with a 2-degree field of view: under a
    uniform environment each pixel is the directional albedo E(mu)."""
    return plate_scene(lambda w: w.add_material("Metal", base_color=(1, 1, 1, 1), metallic=1.0,
                                                roughness=roughness), view_degrees)


def coat(factor=1.0, roughness=0.0, **textures):
    return {"KHR_materials_clearcoat": dict({"clearcoatFactor": factor, "clearcoatRoughnessFactor": roughness},
                                            **textures)}


def coat_plate(metal, view_degrees, fov_degrees):
    """A smooth coat over a black base: metal (baseColor 0, metallic 1,
    roughness 0: Schlick reflectance (1 - mu)^5), or a dielectric of
    specular 0 that reflects nothing."""
    def material(w):
        if metal:
            return w.add_material("CoatOverBlackMetal", base_color=(0, 0, 0, 1), metallic=1.0,
                                  roughness=0.0, extensions=coat())
        return w.add_material("CoatOverBlack", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                              specular=0.0, extensions=coat())
    used = ["KHR_materials_clearcoat"] + ([] if metal else ["KHR_materials_specular"])
    return plate_scene(material, view_degrees, fov_degrees, used)


def textured_plate(path, fields, extensions, camera_fov, view_degrees=0.0):
    """plate_scene's plate and camera with texture coordinates (u along +X,
    v along -Y, so generated tangents are +X) and a material of raw JSON
    `fields(s)`."""
    s = TexturedScene()
    s.w.doc["asset"]["generator"] = GENERATOR
    corners = [(-20, -20, 0), (20, -20, 0), (20, 20, 0), (-20, 20, 0)]
    s.quad("Plate", corners, [(0, 1), (1, 1), (1, 0), (0, 0)], s.material(**fields(s)), (0, 0, 1))
    t = math.radians(view_degrees)
    s.camera(math.radians(camera_fov), (0.0, -5.0 * math.sin(t), 5.0 * math.cos(t)), rotation_x(t))
    s.write(path, extensions)


def constant_texture(s, rgba):
    """A 2 x 2 texture of one RGBA texel value, bilinear."""
    return s.texture(s.image(data_uri(png([[rgba] * 2] * 2))), mag=LINEAR)


COAT_TEXEL = (128, 0, 0, 255)      # clearcoatTexture: R = 128/255; roughness texture G = 0
COAT_NORMAL = (191, 128, 221)      # clearcoatNormalTexture texel
COAT_NORMAL_SCALE = 0.8


def coat_textured(path):
    """clearcoatFactor 1 x texture R (COAT_TEXEL), roughness factor 1 x
    texture G = 0 (smooth), over a black dielectric of specular 0, seen at
    45 degrees with a 50-degree field of view: each pixel is R Fc(mu)."""
    def fields(s):
        tex = constant_texture(s, COAT_TEXEL)
        return {"name": "TexturedCoat", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                "extensions": dict(coat(1.0, 1.0, clearcoatTexture={"index": tex},
                                        clearcoatRoughnessTexture={"index": tex}),
                                   KHR_materials_specular={"specularFactor": 0.0})}
    textured_plate(path, fields, ["KHR_materials_clearcoat", "KHR_materials_specular"], 50.0, 45.0)


def coat_normal_mapped(path):
    """A smooth coat with a constant clearcoatNormalTexture (COAT_NORMAL,
    scale COAT_NORMAL_SCALE) over a black dielectric of specular 0, seen
    head-on with a 20-degree field of view: each pixel is Fc at the view
    against the mapped coat normal."""
    def fields(s):
        tex = constant_texture(s, COAT_NORMAL + (255,))
        return {"name": "MappedCoat", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                "extensions": dict(coat(clearcoatNormalTexture={"index": tex, "scale": COAT_NORMAL_SCALE}),
                                   KHR_materials_specular={"specularFactor": 0.0})}
    textured_plate(path, fields, ["KHR_materials_clearcoat", "KHR_materials_specular"], 20.0)


def sheen(color, roughness, **textures):
    return {"KHR_materials_sheen": dict({"sheenColorFactor": list(color), "sheenRoughnessFactor": roughness},
                                        **textures)}


SHEEN_MU_NODE, SHEEN_ROUGHNESS_NODE = 24, 20
SHEEN_MU = (SHEEN_MU_NODE / 31) ** 3
SHEEN_ROUGHNESS = (0.1 + 0.9 * SHEEN_ROUGHNESS_NODE / 31) ** 2
SHEEN_COLOR = (0.9, 0.6, 0.3)
SHEEN_TEXEL = (188, 128, 64, 128)  # sRGB colour; roughness A = 128/255


def sheen_plate(base):
    """A sheen of SHEEN_COLOR and roughness SHEEN_ROUGHNESS over black
    (metallic 0, specular 0) or white Lambert."""
    def material(w):
        return w.add_material("Sheen", base_color=(base, base, base, 1), metallic=0.0, roughness=1.0, specular=0.0,
                              extensions=sheen(SHEEN_COLOR, SHEEN_ROUGHNESS))
    return plate_scene(material, math.degrees(math.acos(SHEEN_MU)), 1.0,
                       ["KHR_materials_sheen", "KHR_materials_specular"])


def sheen_textured(path):
    """The black plate's sheen from textures: colour factor 1 x the sRGB
    texel SHEEN_TEXEL, roughness factor SHEEN_ROUGHNESS * 255 / 128 x its A."""
    def fields(s):
        tex = constant_texture(s, SHEEN_TEXEL)
        return {"name": "TexturedSheen", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                "extensions": dict(sheen((1, 1, 1), SHEEN_ROUGHNESS * 255 / 128, sheenColorTexture={"index": tex},
                                         sheenRoughnessTexture={"index": tex}),
                                   KHR_materials_specular={"specularFactor": 0.0})}
    textured_plate(path, fields, ["KHR_materials_sheen", "KHR_materials_specular"], 1.0,
                   math.degrees(math.acos(SHEEN_MU)))


SPECULAR_FACTOR = 0.8
SPECULAR_COLOR = (0.5, 2.0, 30.0)   # F0 0.04 x colour: 0.02, 0.08, 1.2 -> clamped to 1
SPECULAR_TEXEL = (255, 128, 64, 128)  # sRGB colour; specular A = 128/255
SPECULAR_TEXTURED_COLOR = 20.0


def diffuse_transmission(factor, color=None, **textures):
    fields = {"diffuseTransmissionFactor": factor}
    if color is not None:
        fields["diffuseTransmissionColorFactor"] = list(color)
    return {"KHR_materials_diffuse_transmission": dict(fields, **textures)}


TRANSLUCENT_BASE = (0.2, 0.6, 1.0)
TRANSLUCENT_COLOR = (1.0, 0.5, 0.25)


def translucent_plate(base, factor, color):
    """A Lambertian plate (metallic 0, ior 1) of baseColor `base` that
    diffusely transmits `factor` of its light in `color`, seen head-on."""
    def material(w):
        return w.add_material("Translucent", base_color=tuple(base) + (1,), metallic=0.0, roughness=1.0, ior=1.0,
                              extensions=diffuse_transmission(factor, color))
    return plate_scene(material, 0.0, 20.0, ["KHR_materials_diffuse_transmission", "KHR_materials_ior"])


BACKLIT_FACTOR, BACKLIT_COLOR, BACKLIT_IRRADIANCE, BACKLIT_VIEW = 0.7, (0.9, 0.6, 0.3), 2.0, 60.0


def translucent_backlit():
    """A 40 x 40 sheet z = 0 facing +Z (black base, ior 1.5, diffuse
    transmission BACKLIT_FACTOR of colour BACKLIT_COLOR) under a directional
    light travelling -Z (irradiance BACKLIT_IRRADIANCE on its front), seen from
    below at BACKLIT_VIEW degrees from -Z through a 1-degree field of view."""
    w = writer()
    sheet = w.add_material("Leaf", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                           extensions=diffuse_transmission(BACKLIT_FACTOR, BACKLIT_COLOR))
    quad = Quads().add((-20, -20, 0), (40, 0, 0), (0, 40, 0), (0, 0, 1))
    t = math.radians(BACKLIT_VIEW)
    sun = w.add_light("Sun", "directional", intensity=BACKLIT_IRRADIANCE)
    roots = [w.add_node("Sheet", mesh=mesh(w, "Sheet", quad, sheet)),
             w.add_node("Sun", light=sun, translation=[0.0, 0.0, 5.0]),
             w.add_node("Camera", camera=camera(w, "Camera", 1.0),
                        translation=[0.0, -5.0 * math.sin(t), -5.0 * math.cos(t)],
                        rotation=rotation_x(math.pi - t))]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_diffuse_transmission", "KHR_lights_punctual"])
    return w.gltf_text()


ANISOTROPY_ROUGHNESS = 0.3


def anisotropy_plate(path, rotation):
    """plate_scene's plate and camera (60 degrees, 1-degree view) with u
    along +Y (the generated tangent: not the frame strata would choose
    about +Z without one) and a brushed white metal."""
    s = TexturedScene()
    s.w.doc["asset"]["generator"] = GENERATOR
    material = s.material(name="Brushed", pbrMetallicRoughness={
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 1.0, "roughnessFactor": ANISOTROPY_ROUGHNESS},
        extensions={"KHR_materials_anisotropy": {"anisotropyStrength": 1.0, "anisotropyRotation": rotation}})
    corners = [(-20, -20, 0), (20, -20, 0), (20, 20, 0), (-20, 20, 0)]
    s.quad("Plate", corners, [(0, 1), (0, 0), (1, 0), (1, 1)], material, (0, 0, 1))
    t = math.radians(60.0)
    s.camera(math.radians(1.0), (0.0, -5.0 * math.sin(t), 5.0 * math.cos(t)), rotation_x(t))
    s.write(path, ["KHR_materials_anisotropy"])


ANISOTROPY_TEXEL = (128, 255, 255, 255)  # direction (1/255, 1): the bitangent; strength 1


def anisotropy_textured(path):
    """anisotropy_plate's plate with rotation 0 and the direction from a
    constant anisotropyTexture (ANISOTROPY_TEXEL): along the bitangent (X),
    as rotation pi/2 puts it."""
    s = TexturedScene()
    s.w.doc["asset"]["generator"] = GENERATOR
    tex = s.texture(s.image(data_uri(png([[ANISOTROPY_TEXEL] * 2] * 2))), mag=LINEAR)
    material = s.material(name="Brushed", pbrMetallicRoughness={
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 1.0, "roughnessFactor": ANISOTROPY_ROUGHNESS},
        extensions={"KHR_materials_anisotropy": {"anisotropyStrength": 1.0, "anisotropyTexture": {"index": tex}}})
    corners = [(-20, -20, 0), (20, -20, 0), (20, 20, 0), (-20, 20, 0)]
    s.quad("Plate", corners, [(0, 1), (0, 0), (1, 0), (1, 1)], material, (0, 0, 1))
    t = math.radians(60.0)
    s.camera(math.radians(1.0), (0.0, -5.0 * math.sin(t), 5.0 * math.cos(t)), rotation_x(t))
    s.write(path, ["KHR_materials_anisotropy"])


TRANSLUCENT_TEXEL = (188, 128, 64, 128)  # sRGB colour; factor A = 128/255


def translucent_textured(path):
    """A black Lambertian plate of ior 1, its diffuse transmission from a
    constant texture (TRANSLUCENT_TEXEL): factor 1 x A, colour 1 x the sRGB
    RGB, seen head-on."""
    def fields(s):
        tex = constant_texture(s, TRANSLUCENT_TEXEL)
        return {"name": "TexturedTranslucent", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1],
                                                                         "metallicFactor": 0.0},
                "extensions": dict(diffuse_transmission(1.0, (1, 1, 1), diffuseTransmissionTexture={"index": tex},
                                                        diffuseTransmissionColorTexture={"index": tex}),
                                   KHR_materials_ior={"ior": 1.0})}
    textured_plate(path, fields, ["KHR_materials_diffuse_transmission", "KHR_materials_ior"], 20.0)


def anisotropy_materials(s, tex):
    """anisotropy.gltf's materials (tests/test_anisotropy.cpp)."""
    return [
        {"name": "Brushed", "pbrMetallicRoughness": {"metallicFactor": 1.0, "roughnessFactor": 0.4},
         "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyRotation": 0.5,
                                                     "anisotropyTexture": {"index": tex[0], "texCoord": 1}}}},
        {"name": "Defaults", "extensions": {"KHR_materials_anisotropy": {}}},
    ]


def diffuse_transmission_materials(s, tex):
    """diffuse-transmission.gltf's materials (tests/test_diffuse_transmission.cpp)."""
    return [
        {"name": "Translucent", "pbrMetallicRoughness": {"metallicFactor": 0.0}, "extensions": diffuse_transmission(
            0.6, (0.9, 0.5, 0.2), diffuseTransmissionTexture={"index": tex[1]},
            diffuseTransmissionColorTexture={"index": tex[0], "texCoord": 1})},
        {"name": "Defaults", "extensions": {"KHR_materials_diffuse_transmission": {}}},
    ]


def specular_plate(view_degrees, fov_degrees):
    """A smooth black dielectric of specularFactor SPECULAR_FACTOR and
    specularColorFactor SPECULAR_COLOR."""
    def material(w):
        return w.add_material("Tinted", base_color=(0, 0, 0, 1), metallic=0.0, roughness=0.0,
                              extensions={"KHR_materials_specular": {"specularFactor": SPECULAR_FACTOR,
                                                                     "specularColorFactor": list(SPECULAR_COLOR)}})
    return plate_scene(material, view_degrees, fov_degrees, ["KHR_materials_specular"])


# KHR_materials_iridescence plates (tests/test_material_layers.cpp mirrors these).
FILM_IOR = 1.3
FILM_METAL_COLOR = (0.9, 0.6, 0.3)
FILM_METAL_THICKNESS = 250.0


def film_plate(metal, view_degrees, fov_degrees):
    """A smooth plate under a thin film of index FILM_IOR: a black dielectric
    (ior 1.5, the film's default thickness 400 nm), or a metal of base colour
    FILM_METAL_COLOR under FILM_METAL_THICKNESS nm."""
    def material(w):
        if metal:
            film = {"iridescenceFactor": 1.0, "iridescenceIor": FILM_IOR,
                    "iridescenceThicknessMaximum": FILM_METAL_THICKNESS}
            return w.add_material("FilmMetal", base_color=list(FILM_METAL_COLOR) + [1.0], metallic=1.0,
                                  roughness=0.0, extensions={"KHR_materials_iridescence": film})
        film = {"iridescenceFactor": 1.0, "iridescenceIor": FILM_IOR}
        return w.add_material("FilmDielectric", base_color=(0, 0, 0, 1), metallic=0.0, roughness=0.0,
                              extensions={"KHR_materials_iridescence": film})
    return plate_scene(material, view_degrees, fov_degrees, ["KHR_materials_iridescence"])


def specular_textured(path):
    """The same from textures: colour factor SPECULAR_TEXTURED_COLOR x the
    sRGB texel SPECULAR_TEXEL, specular factor 1 x its A; seen at 60 degrees."""
    def fields(s):
        tex = constant_texture(s, SPECULAR_TEXEL)
        return {"name": "TexturedTint",
                "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0, "roughnessFactor": 0.0},
                "extensions": {"KHR_materials_specular": {
                    "specularColorFactor": [SPECULAR_TEXTURED_COLOR] * 3, "specularColorTexture": {"index": tex},
                    "specularTexture": {"index": tex}}}}
    textured_plate(path, fields, ["KHR_materials_specular"], 30.0, 60.0)


def look_at(eye, target):
    """The node rotation (quaternion x, y, z, w) of a camera at `eye` looking
    at `target` with +Y up (the camera looks down its local -Z)."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    r = [-f[2], 0.0, f[0]]  # cross(f, +Y)
    n = math.sqrt(sum(c * c for c in r))
    r = [c / n for c in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]  # columns: right, up, back
    w = math.sqrt(max(0.0, 1.0 + m[0][0] + m[1][1] + m[2][2])) / 2.0
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]


COAT_LAMP_Z = -2.0
COAT_LAMP_EYE = (3.2, 0.6, COAT_LAMP_Z + 2.4)


def coat_lamp():
    """A 2 x 2 emitter (radiance 1, facing +Z at z = COAT_LAMP_Z, centred on
    the z axis) under a smooth clear coat, over a white Lambert floor
    y = -1.2 (albedo 0.8), seen from COAT_LAMP_EYE: the coat darkens the
    emission leaving at cosine mu by 1 - Schlick(0.04, mu), for the camera
    and for the floor alike. (Off z = 0: next-event estimation loses light
    from an emitter in a coordinate plane through the origin, a fault of the
    shadow rays' end point outside the layers.)"""
    w = writer()
    lamp = w.add_material("CoatedLamp", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0, specular=0.0,
                          emissive=(1.0, 1.0, 1.0), extensions=coat())
    floor_material = w.add_material("Floor", base_color=(0.8, 0.8, 0.8, 1), metallic=0.0, roughness=1.0,
                                    specular=0.0)
    z = COAT_LAMP_Z
    light = Quads().add((-1, -1, z), (2, 0, 0), (0, 2, 0), (0, 0, 1))
    floor = Quads().add((-5, -1.2, z - 1), (0, 0, 7), (10, 0, 0), (0, 1, 0))
    roots = [w.add_node("Lamp", mesh=mesh(w, "Lamp", light, lamp)),
             w.add_node("Floor", mesh=mesh(w, "Floor", floor, floor_material)),
             w.add_node("Camera", camera=camera(w, "Camera", 50.0), translation=list(COAT_LAMP_EYE),
                        rotation=look_at(COAT_LAMP_EYE, (0.0, -0.5, COAT_LAMP_Z + 0.8)))]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_clearcoat", "KHR_materials_specular"])
    return w.gltf_text()


def layer_spheres():
    """Three smooth spheres (radius 0.5) on a grey floor under a square lamp,
    seen from the front: a red plastic under a clear coat, a dark velvet (a
    sheen over a dark base), a dielectric of gold specular colour. For the
    README's picture and the wavefront integrator's test."""
    w = writer()
    verts, faces = icosphere(4)
    sphere_idx = [i for f in faces for i in f]
    materials = [
        w.add_material("CoatedRed", base_color=(0.6, 0.05, 0.04, 1), metallic=0.0, roughness=0.6,
                       extensions=coat(1.0, 0.05)),
        w.add_material("Velvet", base_color=(0.05, 0.02, 0.12, 1), metallic=0.0, roughness=1.0,
                       extensions=sheen((0.7, 0.5, 1.0), 0.4)),
        w.add_material("GoldTint", base_color=(0.02, 0.02, 0.02, 1), metallic=0.0, roughness=0.25,
                       extensions={"KHR_materials_specular": {"specularColorFactor": [25.0, 17.0, 6.0]}}),
    ]
    floor_material = w.add_material("Floor", base_color=(0.5, 0.5, 0.5, 1), metallic=0.0, roughness=1.0,
                                    specular=0.0)
    lamp = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                          emissive=(1.0, 1.0, 1.0), strength=8.0, specular=0.0)
    roots = []
    for k, m in enumerate(materials):
        mesh_index = w.add_triangles("Sphere%d" % k, verts, normals=verts, indices=sphere_idx, material=m)
        roots.append(w.add_node("Sphere%d" % k, mesh=mesh_index, translation=[1.2 * (k - 1), 0.5, 0.0],
                                scale=[0.5, 0.5, 0.5]))
    floor = Quads().add((-4, 0, -4), (0, 0, 8), (8, 0, 0), (0, 1, 0))
    light = Quads().add((-1, 3, -1), (2, 0, 0), (0, 0, 2), (0, -1, 0))
    roots.append(w.add_node("Floor", mesh=mesh(w, "Floor", floor, floor_material)))
    roots.append(w.add_node("Lamp", mesh=mesh(w, "Lamp", light, lamp)))
    roots.append(w.add_node("Camera", camera=camera(w, "Camera", 30.0), translation=[0.0, 1.2, 4.5],
                            rotation=rotation_x(-math.atan2(0.7, 4.5))))
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_clearcoat", "KHR_materials_emissive_strength", "KHR_materials_sheen",
                      "KHR_materials_specular"])
    return w.gltf_text()


LAYER_EXTENSIONS = ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
                    "KHR_texture_transform"]


def layers_scene(path, materials, extensions=LAYER_EXTENSIONS):
    """Loader checks: one quad per material of raw JSON `materials(s, tex)`
    (tex: two constant textures), with TEXCOORD_0 and TEXCOORD_1."""
    s = TexturedScene()
    s.w.doc["asset"]["generator"] = GENERATOR
    tex = [constant_texture(s, (10, 20, 30, 40)), constant_texture(s, (200, 150, 100, 50))]
    for i, fields in enumerate(materials(s, tex)):
        corners = [(i, 0, 0), (i + 1, 0, 0), (i + 1, 1, 0), (i, 1, 0)]
        uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]
        s.quad(fields["name"], corners, uvs, s.material(**fields), (0, 0, 1), uv_sets=[uvs, uvs])
    s.camera(0.7, (0, 0, 3))
    s.write(path, extensions)


def layer_materials(s, tex):
    """layers.gltf's materials (tests/test_gltf_materials.cpp checks them)."""
    transform = {"KHR_texture_transform": {"offset": [0.5, 0.25], "scale": [2.0, 2.0]}}
    return [
        {"name": "Coat", "extensions": coat(0.8, 0.3, clearcoatTexture={"index": tex[0]},
                                            clearcoatRoughnessTexture={"index": tex[1], "texCoord": 1},
                                            clearcoatNormalTexture={"index": tex[1], "scale": 0.5,
                                                                    "extensions": transform})},
        {"name": "Sheen", "extensions": sheen((0.9, 0.6, 0.3), 0.4, sheenColorTexture={"index": tex[0]},
                                              sheenRoughnessTexture={"index": tex[1], "texCoord": 1})},
        {"name": "Specular", "extensions": {"KHR_materials_specular": {
            "specularFactor": 0.7, "specularColorFactor": [2.0, 0.5, 1.0], "specularTexture": {"index": tex[1]},
            "specularColorTexture": {"index": tex[0], "texCoord": 1}}}},
        {"name": "Defaults", "extensions": {"KHR_materials_clearcoat": {}, "KHR_materials_sheen": {},
                                            "KHR_materials_specular": {}}},
    ]


# broken/: file -> the one bad material (tests/test_gltf_materials.cpp has
# each file's message).
BROKEN = {
    "clearcoat-negative.gltf": lambda tex: {"name": "Bad", "extensions": coat(-0.5)},
    "clearcoat-roughness-above-1.gltf": lambda tex: {"name": "Bad", "extensions": coat(1.0, 1.5)},
    "clearcoat-missing-texture.gltf":
        lambda tex: {"name": "Bad", "extensions": coat(1.0, clearcoatTexture={"index": 5})},
    "sheen-color-above-1.gltf": lambda tex: {"name": "Bad", "extensions": sheen((1.5, 0, 0), 0.5)},
    "sheen-roughness-negative.gltf": lambda tex: {"name": "Bad", "extensions": sheen((1, 1, 1), -0.1)},
    "specular-color-negative.gltf": lambda tex: {"name": "Bad", "extensions": {"KHR_materials_specular": {
        "specularColorFactor": [1.0, -0.5, 1.0]}}},
    "specular-texture-missing.gltf": lambda tex: {"name": "Bad", "extensions": {"KHR_materials_specular": {
        "specularColorTexture": {"index": 9}}}},
    "sheen-color-two-numbers.gltf":
        lambda tex: {"name": "Bad", "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1]}}},
    "iridescence-factor-above-1.gltf":
        lambda tex: {"name": "Bad", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.5}}},
    "iridescence-ior-below-1.gltf":
        lambda tex: {"name": "Bad", "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.0,
                                                                                 "iridescenceIor": 0.5}}},
    "iridescence-thickness-negative.gltf":
        lambda tex: {"name": "Bad", "extensions": {"KHR_materials_iridescence": {
            "iridescenceFactor": 1.0, "iridescenceThicknessMaximum": -10.0}}},
    "diffuse-transmission-above-1.gltf": lambda tex: {"name": "Bad", "extensions": diffuse_transmission(1.5)},
    "diffuse-transmission-string.gltf": lambda tex: {"name": "Bad", "extensions": diffuse_transmission("0.5")},
    "diffuse-transmission-color-negative.gltf":
        lambda tex: {"name": "Bad", "extensions": diffuse_transmission(1.0, (1.0, -0.5, 1.0))},
    "diffuse-transmission-texture-missing.gltf": lambda tex: {"name": "Bad", "extensions": diffuse_transmission(
        1.0, diffuseTransmissionColorTexture={"index": 7})},
    "anisotropy-strength-above-1.gltf":
        lambda tex: {"name": "Bad", "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.5}}},
    "anisotropy-rotation-string.gltf": lambda tex: {"name": "Bad", "extensions": {"KHR_materials_anisotropy": {
        "anisotropyStrength": 0.5, "anisotropyRotation": "1"}}},
    "anisotropy-texture-missing.gltf": lambda tex: {"name": "Bad", "extensions": {"KHR_materials_anisotropy": {
        "anisotropyStrength": 0.5, "anisotropyTexture": {"index": 3}}}},
}


def metal(roughness):
    return lambda w: w.add_material("Mirror", base_color=(1, 1, 1, 1), metallic=1.0,
                                    roughness=roughness)


def black_gloss(w):
    """Smooth black dielectric: only Fresnel reflection (ior 1.5)."""
    return w.add_material("BlackGloss", base_color=(0, 0, 0, 1), metallic=0.0, roughness=0.0)


def unlit():
    """KHR_materials_unlit: a 4 x 4 quad at z = 0 of base colour UNLIT (and an
    emissive factor, which unlit ignores) fills the view of a camera at
    (0, 0, 2) looking down -Z (yfov 40 degrees), next to a point light and
    under a lit white floor; every pixel shows UNLIT exactly."""
    w = writer()
    flat = w.add_material("Flat", base_color=UNLIT + (1,), emissive=(5, 5, 5), unlit=True)
    white = w.add_material("White", base_color=(1, 1, 1, 1), metallic=0.0, roughness=1.0)
    lamp = w.add_light("Lamp", "point", intensity=10.0)
    quad = Quads().add((-2, -2, 0), (4, 0, 0), (0, 4, 0), (0, 0, 1))
    floor = Quads().add((-3, -2.5, -3), (0, 0, 6), (6, 0, 0), (0, 1, 0))
    roots = [
        w.add_node("Flat", mesh=mesh(w, "Flat", quad, flat)),
        w.add_node("Floor", mesh=mesh(w, "Floor", floor, white)),
        w.add_node("Lamp", light=lamp, translation=[0, 0, 1]),
        w.add_node("Camera", camera=camera(w, "Camera", 40.0), translation=[0, 0, 2]),
    ]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_unlit", "KHR_lights_punctual"])
    return w.gltf_text()


UNLIT = (0.2, 0.5, 0.9)


def volume_slab():
    """KHR_materials_volume: a closed 10 x 10 x 1 slab (z in [-0.5, 0.5]) of
    clear glass of ior 1 (no reflection, no bending), attenuation distance 2
    and colour VOLUME_COLOR, seen by a camera at (0, 0, 3) looking down -Z
    (yfov 1 degree) against the default white environment (no light in the
    file): every pixel shows VOLUME_COLOR^(1 / 2) to within 1e-4."""
    w = writer()
    glass = w.add_material("Tinted", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0, ior=1.0,
                           transmission=1.0, volume=(1.0, 2.0, VOLUME_COLOR))
    h, t = 5.0, 0.5
    box = Quads()
    box.add((-h, -h, t), (2 * h, 0, 0), (0, 2 * h, 0), (0, 0, 1))       # front, +Z
    box.add((-h, -h, -t), (0, 2 * h, 0), (2 * h, 0, 0), (0, 0, -1))     # back, -Z
    box.add((-h, -h, -t), (0, 0, 2 * t), (0, 2 * h, 0), (-1, 0, 0))     # -X
    box.add((h, -h, -t), (0, 2 * h, 0), (0, 0, 2 * t), (1, 0, 0))       # +X
    box.add((-h, -h, -t), (2 * h, 0, 0), (0, 0, 2 * t), (0, -1, 0))     # -Y
    box.add((-h, h, -t), (0, 0, 2 * t), (2 * h, 0, 0), (0, 1, 0))       # +Y
    roots = [w.add_node("Slab", mesh=mesh(w, "Slab", box, glass)),
             w.add_node("Camera", camera=camera(w, "Camera", 1.0), translation=[0, 0, 3])]
    w.set_scene(roots, name="Scene")
    w.use_extensions(["KHR_materials_ior", "KHR_materials_transmission", "KHR_materials_volume"])
    return w.gltf_text()


VOLUME_COLOR = (0.5, 0.25, 0.8)


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "materials")
    os.makedirs(out, exist_ok=True)
    scenes = {
        "mirror-r0.gltf": mirror_scene(metal(0.0)),
        "mirror-r1e-4.gltf": mirror_scene(metal(1e-4)),
        "black-gloss.gltf": mirror_scene(black_gloss),
        "glass-sphere.gltf": glass_sphere(),
        # alpha = roughness^2: 0.5 seen at mu = 1 and 0.5, 0.1 at mu = 1
        "plate-a0.5-mu1.gltf": plate(math.sqrt(0.5), 0.0),
        "plate-a0.5-mu0.5.gltf": plate(math.sqrt(0.5), 60.0),
        "plate-a0.1-mu1.gltf": plate(math.sqrt(0.1), 0.0),
        "unlit.gltf": unlit(),
        "volume-slab.gltf": volume_slab(),
        # KHR_materials_clearcoat in a white furnace (the metal base only
        # below mu 0.75: tests/test_material_layers.cpp says why).
        "coat-black-metal.gltf": coat_plate(True, 60.0, 24.0),
        "coat-black.gltf": coat_plate(False, 45.0, 50.0),
        "sheen-black.gltf": sheen_plate(0.0),
        "sheen-white.gltf": sheen_plate(1.0),
        "specular-color-0.gltf": specular_plate(0.0, 2.0),
        "specular-color-60.gltf": specular_plate(60.0, 30.0),
        "iridescence-0.gltf": film_plate(False, 0.0, 2.0),
        "iridescence-60.gltf": film_plate(False, 60.0, 30.0),
        "iridescence-metal.gltf": film_plate(True, 45.0, 30.0),
        "layer-spheres.gltf": layer_spheres(),
        "coat-lamp.gltf": coat_lamp(),
        "translucent-white.gltf": translucent_plate((0, 0, 0), 1.0, (1, 1, 1)),
        "translucent-mix.gltf": translucent_plate(TRANSLUCENT_BASE, 0.5, TRANSLUCENT_COLOR),
        "translucent-backlit.gltf": translucent_backlit(),
    }
    for name, text in scenes.items():
        path = os.path.normpath(os.path.join(out, name))
        with open(path, "w") as f:
            f.write(text)
        print("wrote", path)
    coat_textured(os.path.join(out, "coat-textured.gltf"))
    coat_normal_mapped(os.path.join(out, "coat-normal-map.gltf"))
    sheen_textured(os.path.join(out, "sheen-textured.gltf"))
    specular_textured(os.path.join(out, "specular-textured.gltf"))
    layers_scene(os.path.join(out, "layers.gltf"), layer_materials)
    layers_scene(os.path.join(out, "diffuse-transmission.gltf"), diffuse_transmission_materials,
                 ["KHR_materials_diffuse_transmission"])
    layers_scene(os.path.join(out, "anisotropy.gltf"), anisotropy_materials, ["KHR_materials_anisotropy"])
    anisotropy_plate(os.path.join(out, "anisotropy-0.gltf"), 0.0)
    anisotropy_plate(os.path.join(out, "anisotropy-90.gltf"), math.pi / 2)
    anisotropy_textured(os.path.join(out, "anisotropy-textured.gltf"))
    translucent_textured(os.path.join(out, "translucent-textured.gltf"))
    os.makedirs(os.path.join(out, "broken"), exist_ok=True)
    for name, material in BROKEN.items():
        layers_scene(os.path.join(out, "broken", name), lambda s, tex, m=material: [m(tex)])


if __name__ == "__main__":
    main()
