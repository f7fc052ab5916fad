#!/usr/bin/env python3
"""Writes Candela's Cornell box (the built-in demo, scenes/demo.dae) in
every format Candela reads, from the same numbers: COLLADA (cornell.dae),
glTF 2.0 (cornell.gltf + cornell.bin), Wavefront OBJ + MTL (cornell.obj),
PLY (one file per material) and Mitsuba 3 XML (cornell.xml, which draws
the PLY files).

demo.dae is Z-up; glTF, OBJ, PLY and the Mitsuba file are written Y-up
(x' = -x, y' = z, z' = y, the same turn the COLLADA loader applies), and
cornell.dae keeps demo.dae's Z-up (the loader turns it), so every format
loads to the same world. The spheres, analytic in demo.dae, are the same
32 x 16 UV spheres in every file (glTF, OBJ and PLY have no analytic
spheres), and every number is rounded once to its 6-digit text, so text
and binary files hold the same floats. The .dae, .gltf and .xml carry
demo.dae's camera (eye (0, 0.75, 3.2) in Y-up, 49.13 degree horizontal
field of view, looking down -z); OBJ and PLY cannot, so a scene or test
that uses them must give it. Run from anywhere:
`python3 scenes/cornell/make.py`. Standard library only.
"""
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# Quads in demo.dae's Z-up coordinates, corner order as in the file
# (triangulated there as (0 1 2) (0 2 3), the fan OBJ and PLY use too).
WALLS = [
    ("floor", "white", [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], (0, 0, 1)),
    ("ceiling", "white", [(-1, -1, 1.5), (-1, 1, 1.5), (1, 1, 1.5), (1, -1, 1.5)], (0, 0, -1)),
    ("backWall", "white", [(-1, -1, 0), (-1, -1, 1.5), (1, -1, 1.5), (1, -1, 0)], (0, 1, 0)),
    ("redWall", "red", [(1, -1, 0), (1, -1, 1.5), (1, 1, 1.5), (1, 1, 0)], (-1, 0, 0)),
    ("greenWall", "green", [(-1, -1, 0), (-1, 1, 0), (-1, 1, 1.5), (-1, -1, 1.5)], (1, 0, 0)),
    ("lamp", "lamp", [(-0.3, -0.3, 1.49), (-0.3, 0.3, 1.49), (0.3, 0.3, 1.49), (0.3, -0.3, 1.49)], (0, 0, -1)),
]
SPHERES = [
    ("matteSphere", "matte", (0.45, -0.3, 0.3), 0.3),
    ("mirrorSphere", "mirror", (-0.45, 0.25, 0.3), 0.3),
]
# Diffuse albedos, the lamp's radiance (a pure emitter, black BSDF, as
# Candela reads demo.dae's CGL emission) and the mirror's reflectance.
DIFFUSE = {
    "white": (0.725, 0.71, 0.68),
    "red": (0.63, 0.065, 0.05),
    "green": (0.14, 0.45, 0.091),
    "matte": (0.8, 0.8, 0.8),
}
LAMP, LAMP_RADIANCE = "lamp", 10.0
MIRROR, MIRROR_REFLECTANCE = "mirror", 0.95
MATERIAL_ORDER = ["white", "red", "green", "lamp", "matte", "mirror"]
# demo.dae's camera: horizontal field of view (degrees), 4:3 frame, and
# the eye in Y-up, looking down -z.
XFOV_DEG, ASPECT, EYE = 49.13434, 4.0 / 3.0, (0.0, 0.75, 3.2)
SEGMENTS, RINGS = 32, 16


def mtl_body(name):
    """The MTL statements of a material (see the README's OBJ/MTL table)."""
    if name == LAMP:
        r = fmt(LAMP_RADIANCE)
        return f"Kd 0 0 0\nKe {r} {r} {r}"
    if name == MIRROR:
        k = fmt(MIRROR_REFLECTANCE)
        return f"illum 3\nKs {k} {k} {k}"
    return "Kd " + " ".join(fmt(c) for c in DIFFUSE[name])


def y_up(p):
    x, y, z = p
    return (-x, z, y)


def sphere(center, radius):
    """A UV sphere: positions, unit normals and faces (triangles at the
    poles, quads elsewhere), 0-based, wound outwards."""
    verts, normals = [], []
    for i in range(RINGS + 1):
        theta = math.pi * i / RINGS
        for j in range(SEGMENTS):
            phi = 2 * math.pi * j / SEGMENTS
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            normals.append(n)
            verts.append(tuple(c + radius * d for c, d in zip(center, n)))
    faces = []
    for i in range(RINGS):
        for j in range(SEGMENTS):
            a, b = i * SEGMENTS + j, i * SEGMENTS + (j + 1) % SEGMENTS
            c, d = a + SEGMENTS, b + SEGMENTS
            if i == 0:
                faces.append((a, d, c))
            elif i == RINGS - 1:
                faces.append((a, b, c))
            else:
                faces.append((a, b, d, c))
    return verts, normals, faces


def rounded(points):
    """Every coordinate as the float its 6-digit text reads back as."""
    return [tuple(float(fmt(c)) for c in p) for p in points]


def groups():
    """(name, material, positions, normals, faces) in Y-up, normals per vertex."""
    out = []
    for name, mat, quad, n in WALLS:
        out.append((name, mat, [y_up(p) for p in quad], [y_up(n)] * 4, [(0, 1, 2, 3)]))
    for name, mat, center, radius in SPHERES:
        v, n, f = sphere(y_up(center), radius)
        out.append((name, mat, v, n, f))
    return [(name, mat, rounded(v), rounded(n), f) for name, mat, v, n, f in out]


def fan(face):
    """A polygon's triangles, fanned from its first corner as OBJ and PLY
    loaders split it."""
    return [(face[0], face[k], face[k + 1]) for k in range(1, len(face) - 1)]


def fmt(x):
    return f"{x:.6g}"


def write_obj():
    lines = ["# Candela's Cornell box (scenes/demo.dae), written by make.py.", "mtllib cornell.mtl"]
    base = 0
    for name, mat, verts, normals, faces in groups():
        lines.append(f"o {name}")
        lines += ["v " + " ".join(fmt(c) for c in p) for p in verts]
        lines += ["vn " + " ".join(fmt(c) for c in n) for n in normals]
        lines.append(f"usemtl {mat}")
        for f in faces:
            lines.append("f " + " ".join(f"{base + i + 1}//{base + i + 1}" for i in f))
        base += len(verts)
    with open(os.path.join(HERE, "cornell.obj"), "w", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")
    with open(os.path.join(HERE, "cornell.mtl"), "w", newline="\n") as fh:
        for name in MATERIAL_ORDER:
            fh.write(f"newmtl {name}\n{mtl_body(name)}\n\n")


def write_ply(path, verts, normals, faces, encoding):
    header = [
        "ply",
        f"format {encoding} 1.0",
        "comment Candela's Cornell box (scenes/demo.dae), written by make.py",
        f"element vertex {len(verts)}",
        "property float x", "property float y", "property float z",
        "property float nx", "property float ny", "property float nz",
        f"element face {len(faces)}",
        "property list uchar int vertex_indices",
        "end_header",
    ]
    with open(path, "wb") as fh:
        fh.write(("\n".join(header) + "\n").encode("ascii"))
        if encoding == "ascii":
            for p, n in zip(verts, normals):
                fh.write((" ".join(fmt(c) for c in p + n) + "\n").encode("ascii"))
            for f in faces:
                fh.write((f"{len(f)} " + " ".join(str(i) for i in f) + "\n").encode("ascii"))
        else:
            e = "<" if encoding == "binary_little_endian" else ">"
            for p, n in zip(verts, normals):
                fh.write(struct.pack(e + "6f", *(p + n)))
            for f in faces:
                fh.write(struct.pack(f"{e}B{len(f)}i", len(f), *f))


def write_plys():
    """One PLY per material group, the three encodings in turn."""
    by_material = {}
    for _, mat, verts, normals, faces in groups():
        v, n, f = by_material.setdefault(mat, ([], [], []))
        f += [tuple(i + len(v) for i in face) for face in faces]
        v += verts
        n += normals
    encodings = ["ascii", "binary_little_endian", "binary_big_endian"]
    for k, (mat, (v, n, f)) in enumerate(by_material.items()):
        write_ply(os.path.join(HERE, f"{mat}.ply"), v, n, f, encodings[k % 3])




def z_up(p):
    """The inverse of `y_up` (the turn is its own inverse)."""
    return y_up(p)


def dae_source(gid, kind, points):
    arr = " ".join(fmt(c) for p in points for c in p)
    n = len(points)
    return f"""        <source id="{gid}-{kind}">
          <float_array id="{gid}-{kind}-array" count="{3 * n}">{arr}</float_array>
          <technique_common>
            <accessor source="#{gid}-{kind}-array" count="{n}" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>"""


def dae_effect(name):
    if name == LAMP:
        r = fmt(LAMP_RADIANCE)
        common, extra = "<lambert><diffuse><color>0 0 0 1</color></diffuse></lambert>", (
            f"<emission><radiance>{r} {r} {r}</radiance></emission>")
    elif name == MIRROR:
        k = fmt(MIRROR_REFLECTANCE)
        common, extra = "<phong><diffuse><color>0.5 0.5 0.5 1</color></diffuse></phong>", (
            f"<mirror><reflectance>{k} {k} {k}</reflectance></mirror>")
    else:
        rgb = " ".join(fmt(c) for c in DIFFUSE[name])
        common, extra = f"<lambert><diffuse><color>{rgb} 1</color></diffuse></lambert>", None
    out = [f'    <effect id="{name}-effect">',
           f'      <profile_COMMON><technique sid="common">{common}</technique></profile_COMMON>']
    if extra:
        out.append(f'      <extra><technique profile="CGL">{extra}</technique></extra>')
    out.append("    </effect>")
    return "\n".join(out)


def write_dae():
    """cornell.dae: demo.dae's materials and camera, Z-up, with the UV
    spheres as meshes (polylists of the same quads and triangles)."""
    geoms, nodes = [], []
    for name, mat, verts, normals, faces in groups():
        vc = " ".join(str(len(f)) for f in faces)
        p = " ".join(f"{i} {i}" for f in faces for i in f)
        geoms.append(f"""    <geometry id="{name}-mesh" name="{name}">
      <mesh>
{dae_source(name, "positions", [z_up(v) for v in verts])}
{dae_source(name, "normals", [z_up(n) for n in normals])}
        <vertices id="{name}-vertices"><input semantic="POSITION" source="#{name}-positions"/></vertices>
        <polylist material="{mat}-symbol" count="{len(faces)}">
          <input semantic="VERTEX" source="#{name}-vertices" offset="0"/>
          <input semantic="NORMAL" source="#{name}-normals" offset="1"/>
          <vcount>{vc}</vcount>
          <p>{p}</p>
        </polylist>
      </mesh>
    </geometry>""")
        nodes.append(f"""      <node id="{name}" name="{name}" type="NODE">
        <instance_geometry url="#{name}-mesh">
          <bind_material><technique_common>
            <instance_material symbol="{mat}-symbol" target="#{mat}-material"/>
          </technique_common></bind_material>
        </instance_geometry>
      </node>""")
    effects = "\n".join(dae_effect(m) for m in MATERIAL_ORDER)
    materials = "\n".join(
        f'    <material id="{m}-material" name="{m}"><instance_effect url="#{m}-effect"/></material>'
        for m in MATERIAL_ORDER)
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<!-- Candela's Cornell box (scenes/demo.dae) with tessellated spheres, written by make.py. -->
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>
    <unit name="meter" meter="1"/>
    <up_axis>Z_UP</up_axis>
  </asset>
  <library_cameras>
    <camera id="main-camera" name="Camera">
      <optics><technique_common><perspective>
        <xfov>{XFOV_DEG}</xfov><aspect_ratio>{fmt(ASPECT)}</aspect_ratio><znear>0.1</znear><zfar>100</zfar>
      </perspective></technique_common></optics>
    </camera>
  </library_cameras>
  <library_effects>
{effects}
  </library_effects>
  <library_materials>
{materials}
  </library_materials>
  <library_geometries>
{chr(10).join(geoms)}
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="cornell" name="cornell">
      <node id="Camera" name="Camera" type="NODE">
        <translate>{" ".join(fmt(c) for c in z_up(EYE))}</translate>
        <rotate>0 0 1 180</rotate>
        <rotate>1 0 0 90</rotate>
        <instance_camera url="#main-camera"/>
      </node>
{chr(10).join(nodes)}
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#cornell"/></scene>
</COLLADA>
"""
    with open(os.path.join(HERE, "cornell.dae"), "w", newline="\n") as fh:
        fh.write(text)


# KHR_materials_specular with specularFactor 0: no dielectric specular
# layer, so a glTF metallic-roughness material is exactly Lambertian (and a
# black one absorbs everything, as the .dae's pure-emitter lamp does).
NO_SPECULAR = {"KHR_materials_specular": {"specularFactor": 0}}


def gltf_material(name):
    m = {"name": name}
    if name == LAMP:
        # glTF's emissiveFactor is at most 1; the strength extension scales it.
        strength = max(LAMP_RADIANCE, 1.0)
        m["pbrMetallicRoughness"] = {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}
        m["emissiveFactor"] = [LAMP_RADIANCE / strength] * 3
        m["extensions"] = dict(NO_SPECULAR)
        if strength > 1.0:
            m["extensions"]["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
    elif name == MIRROR:
        # A smooth metal (roughness 0: a delta lobe in Candela) of Schlick
        # reflectance F0 + (1 - F0)(1 - cos)^5, F0 the base colour: the
        # .dae's mirror except for Schlick's grazing tail (on average 1/21
        # of 1 - F0 over the sphere's disc, 0.24 %).
        m["pbrMetallicRoughness"] = {
            "baseColorFactor": [MIRROR_REFLECTANCE] * 3 + [1],
            "metallicFactor": 1, "roughnessFactor": 0}
    else:
        m["pbrMetallicRoughness"] = {
            "baseColorFactor": list(DIFFUSE[name]) + [1], "metallicFactor": 0, "roughnessFactor": 1}
        m["extensions"] = dict(NO_SPECULAR)
    return m


def write_gltf():
    """cornell.gltf + cornell.bin: a node and mesh per group, the camera on
    its own node (glTF cameras look down -z, y up, as here)."""
    blob, views, accessors, meshes, nodes = bytearray(), [], [], [], []

    def add(data, count, kind, ctype, target, extra=None):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": kind}
        acc.update(extra or {})
        accessors.append(acc)
        return len(accessors) - 1

    for name, mat, verts, normals, faces in groups():
        tris = [t for f in faces for t in fan(f)]
        lo = [min(v[k] for v in verts) for k in range(3)]
        hi = [max(v[k] for v in verts) for k in range(3)]
        pos = add(struct.pack(f"<{3 * len(verts)}f", *(c for v in verts for c in v)),
                  len(verts), "VEC3", 5126, 34962, {"min": lo, "max": hi})
        nor = add(struct.pack(f"<{3 * len(normals)}f", *(c for n in normals for c in n)),
                  len(normals), "VEC3", 5126, 34962)
        idx = add(struct.pack(f"<{3 * len(tris)}I", *(i for t in tris for i in t)),
                  3 * len(tris), "SCALAR", 5125, 34963)
        meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": pos, "NORMAL": nor}, "indices": idx,
            "material": MATERIAL_ORDER.index(mat)}]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})
    yfov = 2 * math.atan(math.tan(math.radians(XFOV_DEG) / 2) / ASPECT)
    nodes.append({"name": "Camera", "camera": 0, "translation": list(EYE)})
    doc = {
        "asset": {"version": "2.0", "generator": "scenes/cornell/make.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_specular"],
        "scene": 0,
        "scenes": [{"name": "cornell", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [gltf_material(m) for m in MATERIAL_ORDER],
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": yfov, "aspectRatio": ASPECT, "znear": 0.1, "zfar": 100}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": "cornell.bin", "byteLength": len(blob)}],
    }
    with open(os.path.join(HERE, "cornell.bin"), "wb") as fh:
        fh.write(blob)
    with open(os.path.join(HERE, "cornell.gltf"), "w", newline="\n") as fh:
        json.dump(doc, fh, indent=1)
        fh.write("\n")


def xml_bsdf(name):
    if name == LAMP:
        return '<bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>'
    if name == MIRROR:
        # "none": Fresnel 1 at every angle, scaled by specular_reflectance.
        return ('<bsdf type="conductor"><string name="material" value="none"/>'
                f'<rgb name="specular_reflectance" value="{fmt(MIRROR_REFLECTANCE)}"/></bsdf>')
    rgb = ", ".join(fmt(c) for c in DIFFUSE[name])
    return f'<bsdf type="diffuse"><rgb name="reflectance" value="{rgb}"/></bsdf>'


def write_xml():
    """cornell.xml: Mitsuba 3, Y-up as written, drawing the PLY files. A
    Mitsuba camera looks down +z; `lookat` turns it to look down -z."""
    eye = " ".join(fmt(c) for c in EYE)
    target = " ".join(fmt(c) for c in (EYE[0], EYE[1], 0.0))
    shapes = []
    for mat in MATERIAL_ORDER:
        body = [f'    <string name="filename" value="{mat}.ply"/>', f"    {xml_bsdf(mat)}"]
        if mat == LAMP:
            r = fmt(LAMP_RADIANCE)
            body.append(f'    <emitter type="area"><rgb name="radiance" value="{r}"/></emitter>')
        shapes.append(f'  <shape type="ply" id="{mat}">\n' + "\n".join(body) + "\n  </shape>")
    text = f"""<?xml version="1.0" encoding="utf-8"?>
<!-- Candela's Cornell box (scenes/demo.dae) with tessellated spheres, written by make.py. -->
<scene version="3.0.0">
  <sensor type="perspective">
    <string name="fov_axis" value="x"/>
    <float name="fov" value="{XFOV_DEG}"/>
    <transform name="to_world"><lookat origin="{eye}" target="{target}" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="800"/><integer name="height" value="600"/></film>
  </sensor>
{chr(10).join(shapes)}
</scene>
"""
    with open(os.path.join(HERE, "cornell.xml"), "w", newline="\n") as fh:
        fh.write(text)


if __name__ == "__main__":
    write_obj()
    write_plys()
    write_dae()
    write_gltf()
    write_xml()
