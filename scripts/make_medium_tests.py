#!/usr/bin/env python3
"""Known-answer scenes for media (KHR_materials_volume_scatter over
KHR_materials_volume; tests/test_volume_scatter.cpp), written to
tests/data/media/. Our own work, CC0.

Every scene is the cube [-1, 1]^3 filled with a homogeneous medium behind an
index-matched boundary (a clear dielectric of ior 1: no reflection, no
bending), seen head-on by a camera at z = CAMERA_Z looking down -Z whose view
is HALF_VIEW wide at z = 0 (strata has no orthographic camera): every camera
ray crosses 2 / cos(theta) units of medium, theta below 1.8 degrees.

fog-cube.gltf: attenuation colour FOG_COLOR at distance 1, a multi-scatter
albedo of 1 (single-scatter albedo 1: no absorption) and g = FOG_G. In a
white furnace every path leaves with weight 1 in expectation, whatever g:
the image is 1. Seen through max depth 2 (the boundary's two crossings) only
the unscattered light is left: FOG_COLOR^(2 / cos(theta)), Beer-Lambert of
the whole attenuation.

lantern.gltf: attenuation LANTERN_COLOR at distance 1, multi-scatter albedo
LANTERN_MS, g = LANTERN_G, a point light of intensity LANTERN_I at the
centre and nothing else. Through max depth 2 a pixel shows single scattering
alone, an integral along its ray that the test evaluates by quadrature.

sunlit-fog.gltf: lantern.gltf's medium lit by a directional light of
irradiance SUN_E travelling down -Y instead: through max depth 2 a pixel
shows single scattering of the sun, whose shadow rays leave through the
top face (the index-matched boundary lets them through).

lamp-fog.gltf: lantern.gltf's medium under a 3 x 3 lamp of radiance
LAMP_LE at y = 1.1 facing down, nothing else: light sampling, BSDF (phase)
sampling and their MIS must agree, the lamp found beyond the boundary's
crossing weighed from the scattering event before it.

factor-spelling.gltf: lantern.gltf's medium with multiscatterColor written
as multiscatterColorFactor, as some exporters do, and no light.

lamp-inside-fog.gltf, glass-inside-fog.gltf, fog-on-floor.gltf,
scatter-texture.gltf: what the loader warns about in one line (a lamp, an
absorbing glass cube inside the medium; a multiscatterTexture, not read) and
what it does not (a floor touching the medium's bottom face).

broken/: one bad KHR_materials_volume_scatter value each.

    python3 scripts/make_medium_tests.py [--haze OUT.gltf]
        --haze: only lantern.gltf's medium, without its light, to OUT.gltf
        (the comparison with Cycles, scripts/cycles_medium.py)
"""
import base64
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
from make_scenes import Quads, box_faces, mesh  # noqa: E402
from gltf_writer import GltfWriter, write_texts  # noqa: E402
from make_texture_scenes import png  # noqa: E402

GENERATOR = "strata scripts/make_medium_tests.py"
COPYRIGHT = "CC0 1.0 (public domain), the strata authors"

CAMERA_Z, HALF_VIEW = 30.0, 0.9
FOG_COLOR, FOG_G = (0.2, 0.5, 0.8), 0.3
LANTERN_COLOR, LANTERN_MS, LANTERN_G, LANTERN_I = (0.5, 0.6, 0.7), (0.8, 0.6, 0.9), 0.4, 5.0
SUN_E = 3.0
LAMP_LE = 2.0
EXTENSIONS = ["KHR_materials_ior", "KHR_materials_transmission", "KHR_materials_volume",
              "KHR_materials_volume_scatter"]


def medium_material(w, color, scatter):
    """A clear boundary of ior 1 around a medium of attenuation `color` at
    distance 1; `scatter` is the KHR_materials_volume_scatter object."""
    return w.add_material("Medium", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0, ior=1.0,
                          transmission=1.0, volume=(2.0, 1.0, color),
                          extensions={"KHR_materials_volume_scatter": scatter})


def cube_scene(color, scatter, light=None, sun=None, lamp=None, inside=None):
    """`inside`: the name of something added for the loader's check of
    surfaces inside a medium (INSIDE)."""
    w = GltfWriter(GENERATOR, copyright=COPYRIGHT)
    yfov = 2.0 * math.atan(HALF_VIEW / CAMERA_Z)
    roots = [w.add_node("Cube", mesh=mesh(w, "Cube", box_faces(False), medium_material(w, color, scatter))),
             w.add_node("Camera", camera=w.add_perspective("Camera", yfov, znear=0.1, aspect_ratio=1.0),
                        translation=[0, 0, CAMERA_Z])]
    extensions = list(EXTENSIONS)
    if inside is not None:
        roots += INSIDE[inside](w)
    if light is not None:
        point = w.add_light("Lantern", "point", intensity=light)
        roots.append(w.add_node("Lantern", light=point))
        extensions.append("KHR_lights_punctual")
    if sun is not None:  # a directional light shines down its node's -Z: turned to -Y
        directional = w.add_light("Sun", "directional", intensity=sun)
        h = math.pi / 4
        roots.append(w.add_node("Sun", light=directional, rotation=[-math.sin(h), 0.0, 0.0, math.cos(h)]))
        extensions.append("KHR_lights_punctual")
    if lamp is not None:  # a 3 x 3 quad at y = 1.1 facing down
        quad = Quads().add((-1.5, 1.1, -1.5), (3.0, 0.0, 0.0), (0.0, 0.0, 3.0), (0.0, -1.0, 0.0))
        glow = w.add_material("Lamp", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                              emissive=[1.0, 1.0, 1.0], strength=lamp, specular=0.0)
        roots.append(w.add_node("Lamp", mesh=mesh(w, "Lamp", quad, glow)))
        extensions += ["KHR_materials_emissive_strength", "KHR_materials_specular"]
    w.set_scene(roots, name="Scene")
    w.use_extensions(sorted(set(extensions)))
    return w.gltf_text()


def inner_lamp(w):
    """A 0.5 x 0.5 lamp (2 triangles) facing down at y = 0.5, inside the cube."""
    quad = Quads().add((-0.25, 0.5, -0.25), (0.5, 0.0, 0.0), (0.0, 0.0, 0.5), (0.0, -1.0, 0.0))
    glow = w.add_material("Bulb", base_color=(0, 0, 0, 1), metallic=0.0, roughness=1.0,
                          emissive=[1.0, 1.0, 1.0], strength=LAMP_LE, specular=0.0)
    return [w.add_node("Bulb", mesh=mesh(w, "Bulb", quad, glow))]


def inner_glass(w):
    """An absorbing glass cube (12 triangles) of half size 0.3 placed inside
    the medium: nested media."""
    glass = w.add_material("Glass", base_color=(1, 1, 1, 1), metallic=0.0, roughness=0.0, ior=1.5,
                           transmission=1.0, volume=(0.6, 1.0, (0.9, 0.5, 0.5)))
    return [w.add_node("Ice", mesh=mesh(w, "Ice", box_faces(False), glass), scale=[0.3, 0.3, 0.3],
                       translation=[0.2, -0.1, 0.3])]


def floor(w):
    """A grey floor of 8 x 8 quads (128 triangles) over [-4, 4]^2 at y = -1:
    the 8 triangles under the cube lie on its bottom face, on the boundary,
    not inside."""
    q = Quads()
    for i in range(8):
        for k in range(8):
            q.add((-4.0 + i, -1.0, -4.0 + k), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    grey = w.add_material("Floor", base_color=(0.5, 0.5, 0.5, 1), metallic=0.0, roughness=1.0)
    return [w.add_node("Floor", mesh=mesh(w, "Floor", q, grey))]


# The loader warns, in one line, about the lamp and the glass and not about
# the floor.
INSIDE = {"lamp": inner_lamp, "glass": inner_glass, "floor": floor}


def textured_scatter(text):
    """`text` (a scene) with a multiscatterTexture on its medium: a 1 x 1
    white PNG that strata does not read."""
    doc = json.loads(text)
    white = png([[(255, 255, 255)]])
    doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(white).decode("ascii")}]
    doc["textures"] = [{"source": 0}]
    doc["materials"][0]["extensions"]["KHR_materials_volume_scatter"]["multiscatterTexture"] = {"index": 0}
    return json.dumps(doc, indent=1) + "\n"


BROKEN = {
    "scatter-anisotropy-1.gltf": {"multiscatterColor": [0.5, 0.5, 0.5], "scatterAnisotropy": 1.0},
    "scatter-anisotropy-string.gltf": {"scatterAnisotropy": "forward"},
    "scatter-color-negative.gltf": {"multiscatterColor": [0.5, -0.1, 0.5]},
    "scatter-color-two.gltf": {"multiscatterColor": [0.5, 0.5]},
}


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--haze":
        # lantern.gltf's medium alone, for the comparison with Cycles
        # (scripts/cycles_medium.py; lit by --env-color 1,1,1).
        with open(sys.argv[2], "w") as f:
            f.write(cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS), "scatterAnisotropy": LANTERN_G}))
        return
    out = os.path.join(HERE, "..", "tests", "data", "media")
    scenes = {
        "fog-cube.gltf": cube_scene(FOG_COLOR, {"multiscatterColor": [1, 1, 1], "scatterAnisotropy": FOG_G}),
        "lantern.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS),
                                                   "scatterAnisotropy": LANTERN_G}, LANTERN_I),
        "sunlit-fog.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS),
                                                      "scatterAnisotropy": LANTERN_G}, sun=SUN_E),
        "lamp-fog.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS),
                                                    "scatterAnisotropy": LANTERN_G}, lamp=LAMP_LE),
        "factor-spelling.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColorFactor": list(LANTERN_MS),
                                                           "scatterAnisotropy": LANTERN_G}),
        "lamp-inside-fog.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS)}, inside="lamp"),
        "glass-inside-fog.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS)},
                                            lamp=LAMP_LE, inside="glass"),
        "fog-on-floor.gltf": cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS)},
                                        lamp=LAMP_LE, inside="floor"),
        "scatter-texture.gltf": textured_scatter(cube_scene(LANTERN_COLOR, {"multiscatterColor": list(LANTERN_MS)},
                                                            lamp=LAMP_LE)),
    }
    for name, scatter in BROKEN.items():
        scenes[os.path.join("broken", name)] = cube_scene(FOG_COLOR, scatter)
    write_texts(out, scenes)


if __name__ == "__main__":
    main()
