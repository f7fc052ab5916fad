"""Builds the glTF conformance scene in Blender and exports it as a .glb.

Run with a Python that has the `bpy` module (Blender as a Python package):

    python make_scene.py OUT.glb

The scene is a row of spheres on a floor before a wall, one per material
model a glTF file can ask for (dielectric, metals, glass, clear coat,
sheen, an image texture), lit by a directional light, a point light and an
emissive quad: every light kind glTF has. Blender's glTF exporter writes
the file, so it is as a Blender user would hand it to Candela; both
renderers then read that same file (`render_cycles.py` imports it anew).
"""

import json
import math
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector


def material(name, base, *, metallic=0.0, roughness=0.5, transmission=0.0,
             coat=0.0, coat_roughness=0.03, sheen=0.0, sheen_tint=(1, 1, 1),
             sheen_roughness=0.5, emission=None, strength=1.0, image=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (*base, 1.0)
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Roughness"].default_value = roughness
    p.inputs["Transmission Weight"].default_value = transmission
    p.inputs["IOR"].default_value = 1.5
    p.inputs["Coat Weight"].default_value = coat
    p.inputs["Coat Roughness"].default_value = coat_roughness
    p.inputs["Sheen Weight"].default_value = sheen
    p.inputs["Sheen Tint"].default_value = (*sheen_tint, 1.0)
    p.inputs["Sheen Roughness"].default_value = sheen_roughness
    if emission is not None:
        p.inputs["Emission Color"].default_value = (*emission, 1.0)
        p.inputs["Emission Strength"].default_value = strength
    if image is not None:
        tex = m.node_tree.nodes.new("ShaderNodeTexImage")
        tex.image = image
        m.node_tree.links.new(tex.outputs["Color"], p.inputs["Base Color"])
    return m


def checker_image():
    """An 8×8 checker of two colours, packed into the file."""
    n = 64
    img = bpy.data.images.new("checker", n, n)
    px = []
    for y in range(n):
        for x in range(n):
            on = ((x // 8) + (y // 8)) % 2 == 0
            px += [0.8, 0.75, 0.1, 1.0] if on else [0.1, 0.3, 0.7, 1.0]
    img.pixels = px
    img.file_format = "PNG"
    img.pack()
    return img


def main(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    bpy.ops.mesh.primitive_plane_add(size=12, location=(0, 0, 0))
    bpy.context.object.data.materials.append(material("floor", (0.5, 0.5, 0.5), roughness=1.0))
    bpy.ops.mesh.primitive_plane_add(size=12, location=(0, 3, 3), rotation=(math.pi / 2, 0, 0))
    bpy.context.object.data.materials.append(material("wall", (0.6, 0.6, 0.55), roughness=1.0))

    spheres = [
        material("plastic", (0.8, 0.25, 0.2), roughness=0.35),
        material("gold", (1.0, 0.77, 0.34), metallic=1.0, roughness=0.3),
        material("mirror", (0.95, 0.95, 0.95), metallic=1.0, roughness=0.0),
        material("glass", (1.0, 1.0, 1.0), transmission=1.0, roughness=0.0),
        # Coat roughness 0.1, not Blender's default 0.03: the exporter leaves
        # 0.03 out of the file (glTF's default 0, a smooth coat), and the
        # importer then keeps 0.03, so Cycles would render another coat.
        material("coated", (0.1, 0.2, 0.8), roughness=0.6, coat=1.0, coat_roughness=0.1),
        material("velvet", (0.3, 0.05, 0.1), roughness=1.0, sheen=1.0,
                 sheen_tint=(1.0, 0.9, 0.9), sheen_roughness=0.5),
        material("textured", (1, 1, 1), roughness=0.7, image=checker_image()),
    ]
    centres = []
    for i, m in enumerate(spheres):
        x = (i - (len(spheres) - 1) / 2) * 1.15
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.5,
                                             location=(x, 0, 0.5))
        bpy.ops.object.shade_smooth()
        bpy.context.object.data.materials.append(m)
        centres.append((m.name, Vector((x, 0, 0.5))))

    # An emissive quad above the row, facing down.
    bpy.ops.mesh.primitive_plane_add(size=1.5, location=(-1.0, -0.5, 3.5),
                                     rotation=(math.pi, 0, 0))
    bpy.context.object.data.materials.append(
        material("lamp", (0, 0, 0), roughness=1.0, emission=(1.0, 0.9, 0.8), strength=8.0))

    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 2.0
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = (math.radians(40), math.radians(-25), math.radians(-20))
    scene.collection.objects.link(sun_obj)

    point = bpy.data.lights.new("point", "POINT")
    point.energy = 300.0
    point.shadow_soft_size = 0.0
    point_obj = bpy.data.objects.new("point", point)
    point_obj.location = (2.5, -2.0, 3.0)
    scene.collection.objects.link(point_obj)

    cam = bpy.data.cameras.new("camera")
    cam.lens_unit = "FOV"
    cam.angle = math.radians(50)
    cam.sensor_fit = "HORIZONTAL"
    cam_obj = bpy.data.objects.new("camera", cam)
    cam_obj.location = (0, -7.5, 2.2)
    cam_obj.rotation_euler = (math.radians(80), 0, 0)
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj
    scene.render.resolution_x = 480
    scene.render.resolution_y = 240

    bpy.ops.export_scene.gltf(filepath=out, export_format="GLB", export_cameras=True,
                              export_lights=True, export_yup=True)
    write_regions(scene, cam_obj, centres, out + ".regions.json")


def write_regions(scene, cam_obj, centres, path):
    """Each sphere's disc in the image (pixels from the top left, radius
    shrunk to 70% so edges, where the two renderers' pixel filters differ,
    stay out), for `compare.py`'s per-material figures."""
    w, h = scene.render.resolution_x, scene.render.resolution_y
    regions = {}
    for name, c in centres:
        p = world_to_camera_view(scene, cam_obj, c)
        # The silhouette's radius, from a point half a unit to the side as seen.
        right = cam_obj.matrix_world.to_3x3() @ Vector((1, 0, 0))
        q = world_to_camera_view(scene, cam_obj, c + 0.5 * right)
        regions[name] = [p.x * w, (1 - p.y) * h, 0.7 * abs(q.x - p.x) * w]
    with open(path, "w") as f:
        json.dump({"width": w, "height": h, "regions": regions}, f, indent=1)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else sys.argv[1])
