"""Renders a glTF file with Blender Cycles as a reference for Candela.

    python render_cycles.py SCENE.glb OUT.exr WIDTH HEIGHT SPP

The file is imported by Blender's own glTF importer into an empty scene and
rendered with Cycles on the CPU, its biasing shortcuts switched off so the
image converges to the light transport the file describes: no clamping of
direct or indirect samples, no glossy blur, caustics on, 64 bounces of every
kind, no denoiser, a 1-pixel box filter (Candela's), punctual lights kept
punctual (no radius, no soft falloff), linear EXR output with no view
transform. What Cycles' Principled BSDF itself does differently from the
glTF specification's model (multiple-scattering GGX, Fresnel by IOR rather
than Schlick's, its own sheen) stays, and shows in the comparison.
"""

import sys

import bpy


def main(scene_path, out, width, height, spp):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=scene_path)
    scene = bpy.context.scene
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    scene.camera = cams[0]
    for o in scene.objects:
        if o.type == "LIGHT" and o.data.type in {"POINT", "SPOT"}:
            o.data.shadow_soft_size = 0.0
            o.data.use_soft_falloff = False
        if o.type == "LIGHT" and o.data.type == "SUN":
            o.data.angle = 0.0
    # A black world, as glTF has no environment. A new world has a node
    # tree whose background is Blender's default grey (0.05), which would
    # light everything: its strength is set to 0.
    world = bpy.data.worlds.new("black")
    world.color = (0.0, 0.0, 0.0)
    if world.node_tree is None:
        world.use_nodes = True
    for node in world.node_tree.nodes:
        if node.type == "BACKGROUND":
            node.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
            node.inputs["Strength"].default_value = 0.0
    scene.world = world

    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    for bounces in ("max_bounces", "diffuse_bounces", "glossy_bounces",
                    "transmission_bounces", "volume_bounces", "transparent_max_bounces"):
        setattr(c, bounces, 64)
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = 1
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "AUTO"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    a = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    main(a[0], a[1], int(a[2]), int(a[3]), int(a[4]))
