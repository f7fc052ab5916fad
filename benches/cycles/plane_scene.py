"""Writes a one-plane glTF scene for angle sweeps against Cycles.

    python3 plane_scene.py OUT.gltf ELEVATION_DEG [SPECULAR ROUGHNESS COAT BASE METALLIC]

A 100-unit plane of the glTF metallic-roughness material (base colour BASE,
metalness METALLIC (0 by default),
`KHR_materials_specular`'s specularFactor SPECULAR, roughness ROUGHNESS, a
`KHR_materials_clearcoat` coat of strength COAT and roughness 0.3) under a
directional light of 1 W/m² (683 lux) at 24° from the normal, seen through a
narrow camera (yfov 0.05 rad) from ELEVATION_DEG above the plane, so every
pixel sees the plane at nearly one angle. With SPECULAR 0 the material is
exactly Lambertian and the expected radiance is BASE / π · cos 24.3°, which
both renderers must reproduce; the other settings show where the two
renderers' material models differ, angle by angle.
"""

import base64
import json
import math
import struct
import sys


def quaternion_from_to(a, b):
    """The rotation taking unit vector a to unit vector b, as glTF's xyzw."""
    cross = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    q = [cross[0], cross[1], cross[2], 1 + sum(x * y for x, y in zip(a, b))]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def plane_scene(elevation_deg, specular=1.0, roughness=1.0, coat=0.0, base=0.5, metallic=0.0):
    positions = [-50, 0, -50, 50, 0, -50, 50, 0, 50, -50, 0, 50]
    normals = [0, 1, 0] * 4
    indices = [0, 2, 1, 0, 3, 2]
    data = (struct.pack("<12f", *positions) + struct.pack("<12f", *normals)
            + struct.pack("<6H", *indices) + b"\0\0")
    travel = (0.3, -0.8, 0.2)  # the light's direction of travel
    n = math.sqrt(sum(c * c for c in travel))
    travel = tuple(c / n for c in travel)
    e = math.radians(elevation_deg)
    camera = {"camera": 0, "translation": [0, 5 * math.sin(e), 5 * math.cos(e)],
              "rotation": [-math.sin(e / 2), 0, 0, math.cos(e / 2)]}
    material = {
        "pbrMetallicRoughness": {"baseColorFactor": [base, base, base, 1],
                                 "metallicFactor": metallic, "roughnessFactor": roughness},
        "extensions": {"KHR_materials_specular": {"specularFactor": specular},
                       "KHR_materials_clearcoat": {"clearcoatFactor": coat,
                                                   "clearcoatRoughnessFactor": 0.3}},
    }
    return {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular",
                           "KHR_materials_clearcoat"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "intensity": 683.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0},
                  {"extensions": {"KHR_lights_punctual": {"light": 0}},
                   "rotation": quaternion_from_to((0, 0, -1), travel)},
                  camera],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.05, "aspectRatio": 1.0, "znear": 0.01}}],
        "materials": [material],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                                    "indices": 2, "material": 0}]}],
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-50, 0, -50], "max": [50, 0, 50]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }


if __name__ == "__main__":
    args = [float(a) for a in sys.argv[2:]]
    with open(sys.argv[1], "w") as f:
        json.dump(plane_scene(*args), f)
