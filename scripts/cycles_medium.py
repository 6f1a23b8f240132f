"""Renders tests/data/media/fog-cube.gltf's geometry and camera with
lantern.gltf's medium in Blender Cycles, as a peer for strata's media
(docs/benchmarks.md, "Media against Cycles"). Our own work, CC0.

The cube [-1, 1]^3 has no surface (Cycles then lets light through
unchanged, as strata's index-matched boundary) and a homogeneous volume:
Volume Scatter (g LANTERN_G) plus Volume Absorption with strata's
coefficients per channel: sigma_t = -ln(attenuationColor) / 1 and sigma_s
= sigma_t x the single-scatter albedo that KHR_materials_volume_scatter's
draft maps multiscatterColor to. A uniform white world of radiance 1;
the camera at z = 30 looking down -Z with a view 1.8 wide at z = 0; a
1-pixel box filter.

    blender -b --factory-startup --python scripts/cycles_medium.py -- OUT.exr SPP SIZE [SEED]
"""
import math
import sys
import time

import bpy

ATTENUATION = (0.5, 0.6, 0.7)   # lantern.gltf: attenuationColor at distance 1
MULTISCATTER = (0.8, 0.6, 0.9)  # its multiscatterColor
G = 0.4
CAMERA_Z, HALF_VIEW = 30.0, 0.9


def single_scatter(ms):
    r = 4.09712 + 4.20863 * ms - math.sqrt(9.59217 + 41.6808 * ms + 17.7126 * ms * ms)
    return min(max(1.0 - r * r, 0.0), 1.0)


def main():
    out, spp, size = sys.argv[sys.argv.index("--") + 1:][:3]
    rest = sys.argv[sys.argv.index("--") + 4:]
    seed = int(rest[0]) if rest else 0
    spp, size = int(spp), int(size)
    sigma_t = [-math.log(c) for c in ATTENUATION]
    sigma_s = [t * single_scatter(m) for t, m in zip(sigma_t, MULTISCATTER)]
    sigma_a = [t - s for t, s in zip(sigma_t, sigma_s)]

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.max_bounces = c.volume_bounces = c.transparent_max_bounces = 1024
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 1024
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"

    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bg.inputs["Strength"].default_value = 1.0
    scene.world = world

    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0.0, 0.0, 0.0))
    cube = bpy.context.active_object
    mat = bpy.data.materials.new("Medium")
    mat.use_nodes = True
    mat.cycles.homogeneous_volume = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    scatter = nodes.new("ShaderNodeVolumeScatter")
    absorb = nodes.new("ShaderNodeVolumeAbsorption")
    add = nodes.new("ShaderNodeAddShader")
    ds, da = max(sigma_s), max(sigma_a)
    scatter.inputs["Color"].default_value = tuple(s / ds for s in sigma_s) + (1.0,)
    scatter.inputs["Density"].default_value = ds
    scatter.inputs["Anisotropy"].default_value = G
    # Volume Absorption absorbs density x (1 - colour).
    absorb.inputs["Color"].default_value = tuple(1.0 - a / da for a in sigma_a) + (1.0,)
    absorb.inputs["Density"].default_value = da
    links.new(scatter.outputs[0], add.inputs[0])
    links.new(absorb.outputs[0], add.inputs[1])
    links.new(add.outputs[0], output.inputs["Volume"])
    cube.data.materials.append(mat)

    cam_data = bpy.data.cameras.new("Camera")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = 2.0 * math.atan(HALF_VIEW / CAMERA_Z)
    cam = bpy.data.objects.new("Camera", cam_data)
    cam.location = (0.0, 0.0, CAMERA_Z)  # Blender's camera looks down its -Z
    scene.collection.objects.link(cam)
    scene.camera = cam

    scene.render.filepath = out
    start = time.time()
    bpy.ops.render.render(write_still=True)
    print(f"PEER_RESULT render_s={time.time() - start:.3f} sigma_t={sigma_t} sigma_s={sigma_s}")


main()
