#!/usr/bin/env python3
"""Writes the Mitsuba conformance scenes of this folder: small scenes (128x96,
box filter) that each isolate a group of the Mitsuba loader's features, for
`benches/mitsuba_reference.py` (Mitsuba 3 reference, then Candela against it).

    /tmp/mitsuba-venv/bin/python benches/mitsuba_conformance/make_scenes.py

Writes every `*.xml`, the small generated images under `textures/` (with
Mitsuba's own `mi.Bitmap`) and `regions.json`: per scene, pixel rectangles
inside each object (from the camera's projection), which the comparison
reports one by one.

Most scenes are the Cornell box of ../cornell-materials.xml (same camera,
walls and ceiling light) with four objects at the same four places; the
emitter and sensor scenes are an open stage (floor and back wall) lit only by
the light under test.
"""

import json
import math
import struct
import zlib
from pathlib import Path

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")

HERE = Path(__file__).resolve().parent
W, H = 128, 96
CAM_Z, FOV_X = 3.6, 48.0

# The four places of the Cornell-box scenes, in a row on the floor so that
# none hides another: (centre, radius).
SLOTS = [((x, -0.76, 0.0), 0.22) for x in (-0.72, -0.24, 0.24, 0.72)]


def project(p):
    """Pixel (x, y) of world point p for the default camera."""
    s = (W / 2) / math.tan(math.radians(FOV_X / 2))
    d = CAM_Z - p[2]
    return W / 2 + s * p[0] / d, H / 2 - s * p[1] / d


def rect(center, radius, frac=0.45):
    """A pixel rectangle inside a sphere's image (half-width frac * r)."""
    x, y = project(center)
    r = (W / 2) / math.tan(math.radians(FOV_X / 2)) * radius / (CAM_Z - center[2]) * frac
    return [int(round(x - r)), int(round(y - r)), int(round(x + r)), int(round(y + r))]


def header(comment, fov_axis="x", fov=FOV_X, sensor="perspective", extra_sensor="",
           lookat='origin="0, 0, 3.6" target="0, 0, 0" up="0, 1, 0"', max_depth=8,
           integrator="path"):
    return f"""<?xml version="1.0" encoding="utf-8"?>
<!--
  Conformance scene (written by make_scenes.py; edit that, not this).
  {comment}
-->
<scene version="3.0.0">
    <default name="spp" value="64"/>
    <default name="max_depth" value="{max_depth}"/>
    <default name="seed" value="0"/>

    <integrator type="{integrator}">
        <integer name="max_depth" value="$max_depth"/>
    </integrator>

    <sensor type="{sensor}">
        <string name="fov_axis" value="{fov_axis}"/>
        <float name="fov" value="{fov}"/>{extra_sensor}
        <transform name="to_world">
            <lookat {lookat}/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
            <integer name="seed" value="$seed"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="{W}"/>
            <integer name="height" value="{H}"/>
            <string name="pixel_format" value="rgb"/>
            <rfilter type="box"/>
        </film>
    </sensor>
"""


def diffuse(id_, rgb, twosided=True):
    inner = f"""<bsdf type="diffuse">
            <rgb name="reflectance" value="{rgb}"/>
        </bsdf>"""
    if not twosided:
        return f'    <bsdf type="diffuse" id="{id_}">\n        <rgb name="reflectance" value="{rgb}"/>\n    </bsdf>\n'
    return f'    <bsdf type="twosided" id="{id_}">\n        {inner}\n    </bsdf>\n'


def wall(id_, transform, ref):
    return f"""    <shape type="rectangle" id="{id_}">
        <transform name="to_world">
            {transform}
        </transform>
        <ref id="{ref}"/>
    </shape>
"""


CEILING_LIGHT = """    <shape type="rectangle" id="light">
        <transform name="to_world">
            <scale value="0.35"/>
            <rotate x="1" angle="90"/>
            <translate y="0.99"/>
        </transform>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0, 0, 0"/>
        </bsdf>
        <emitter type="area">
            <rgb name="radiance" value="12, 10, 7"/>
        </emitter>
    </shape>
"""


def cornell(light=True):
    s = diffuse("white", "0.7, 0.7, 0.7") + diffuse("red", "0.63, 0.065, 0.05") \
        + diffuse("green", "0.14, 0.45, 0.09")
    if light:
        s += CEILING_LIGHT
    s += wall("floor", '<rotate x="1" angle="-90"/>\n            <translate y="-1"/>', "white")
    s += wall("ceiling", '<rotate x="1" angle="90"/>\n            <translate y="1"/>', "white")
    s += wall("back", '<translate z="-1"/>', "white")
    s += wall("left", '<rotate y="1" angle="90"/>\n            <translate x="-1"/>', "red")
    s += wall("right", '<rotate y="1" angle="-90"/>\n            <translate x="1"/>', "green")
    return s


def stage():
    """An open stage: a floor and a back wall (both twosided white)."""
    s = diffuse("white", "0.7, 0.7, 0.7")
    s += wall("floor", '<scale value="3"/>\n            <rotate x="1" angle="-90"/>\n            <translate y="-1"/>', "white")
    s += wall("back", '<scale value="3"/>\n            <translate z="-1"/>', "white")
    return s


def sphere(slot, bsdf, id_):
    (x, y, z), r = SLOTS[slot]
    return f"""    <shape type="sphere" id="{id_}">
        <point name="center" x="{x}" y="{y}" z="{z}"/>
        <float name="radius" value="{r}"/>
{bsdf}
    </shape>
"""


def slot_regions(names):
    return {n: rect(*SLOTS[i]) for i, n in enumerate(names) if n}


SCENES = {}
REGIONS = {}


def add(name, text, regions):
    SCENES[name] = text + "</scene>\n"
    REGIONS[name] = regions


def ind(s, n=8):
    return "\n".join(" " * n + line if line else line for line in s.strip("\n").splitlines())


# --- BSDFs -----------------------------------------------------------------

PLASTICS = [
    ("plastic (smooth)", """<bsdf type="plastic">
    <rgb name="diffuse_reflectance" value="0.7, 0.12, 0.08"/>
</bsdf>"""),
    ("roughplastic beckmann 0.2", """<bsdf type="roughplastic">
    <string name="distribution" value="beckmann"/>
    <float name="alpha" value="0.2"/>
    <rgb name="diffuse_reflectance" value="0.2, 0.4, 0.7"/>
</bsdf>"""),
    ("roughplastic ggx 0.3", """<bsdf type="roughplastic">
    <string name="distribution" value="ggx"/>
    <float name="alpha" value="0.3"/>
    <float name="int_ior" value="1.6"/>
    <rgb name="diffuse_reflectance" value="0.2, 0.6, 0.2"/>
</bsdf>"""),
    ("thindielectric", """<bsdf type="thindielectric">
    <float name="int_ior" value="1.5"/>
</bsdf>"""),
]

CONDUCTORS = [
    ("conductor Au", """<bsdf type="conductor">
    <string name="material" value="Au"/>
</bsdf>"""),
    ("conductor eta/k", """<bsdf type="conductor">
    <rgb name="eta" value="0.2, 0.9, 1.1"/>
    <rgb name="k" value="3.9, 2.4, 2.2"/>
</bsdf>"""),
    ("roughconductor anisotropic Cu", """<bsdf type="roughconductor">
    <string name="material" value="Cu"/>
    <string name="distribution" value="ggx"/>
    <float name="alpha_u" value="0.05"/>
    <float name="alpha_v" value="0.4"/>
</bsdf>"""),
    ("roughconductor beckmann Ag", """<bsdf type="roughconductor">
    <string name="material" value="Ag"/>
    <string name="distribution" value="beckmann"/>
    <float name="alpha" value="0.2"/>
</bsdf>"""),
]

PRINCIPLED = [
    ("principled dielectric r0.5", """<bsdf type="principled">
    <rgb name="base_color" value="0.7, 0.2, 0.1"/>
    <float name="roughness" value="0.5"/>
</bsdf>"""),
    ("principled metallic r0.3", """<bsdf type="principled">
    <rgb name="base_color" value="0.9, 0.7, 0.3"/>
    <float name="metallic" value="1.0"/>
    <float name="roughness" value="0.3"/>
</bsdf>"""),
    ("principled specular 1 r0.2", """<bsdf type="principled">
    <rgb name="base_color" value="0.1, 0.3, 0.7"/>
    <float name="specular" value="1.0"/>
    <float name="roughness" value="0.2"/>
</bsdf>"""),
    ("principled spec_trans 1", """<bsdf type="principled">
    <rgb name="base_color" value="0.9, 0.9, 0.9"/>
    <float name="spec_trans" value="1.0"/>
    <float name="roughness" value="0.1"/>
</bsdf>"""),
]

DIELECTRICS = [
    ("dielectric (glass)", """<bsdf type="dielectric">
    <float name="int_ior" value="1.5"/>
</bsdf>"""),
    ("dielectric water in air", """<bsdf type="dielectric">
    <string name="int_ior" value="water"/>
    <string name="ext_ior" value="air"/>
</bsdf>"""),
    ("roughdielectric beckmann 0.1", """<bsdf type="roughdielectric">
    <string name="distribution" value="beckmann"/>
    <float name="alpha" value="0.1"/>
    <float name="int_ior" value="1.5"/>
</bsdf>"""),
    ("roughdielectric ggx 0.3 tinted", """<bsdf type="roughdielectric">
    <string name="distribution" value="ggx"/>
    <float name="alpha" value="0.3"/>
    <float name="int_ior" value="1.7"/>
    <rgb name="specular_transmittance" value="0.9, 0.7, 0.4"/>
</bsdf>"""),
]

BLENDS = [
    ("blend diffuse + roughconductor Au, w 0.3", """<bsdf type="blendbsdf">
    <float name="weight" value="0.3"/>
    <bsdf type="diffuse">
        <rgb name="reflectance" value="0.7, 0.15, 0.1"/>
    </bsdf>
    <bsdf type="roughconductor">
        <string name="material" value="Au"/>
        <string name="distribution" value="ggx"/>
        <float name="alpha" value="0.2"/>
    </bsdf>
</bsdf>"""),
    # A one-value checkerboard: Mitsuba swaps its colours (as for roughness).
    # On a panel: textures on spheres do not agree yet (RESULTS.md).
    ("blend with a checkerboard weight (panel)", """<bsdf type="blendbsdf">
    <texture type="checkerboard" name="weight">
        <float name="color0" value="0.1"/>
        <float name="color1" value="0.9"/>
        <transform name="to_uv">
            <scale x="6" y="3"/>
        </transform>
    </texture>
    <bsdf type="diffuse">
        <rgb name="reflectance" value="0.1, 0.3, 0.7"/>
    </bsdf>
    <bsdf type="roughplastic">
        <float name="alpha" value="0.1"/>
        <rgb name="diffuse_reflectance" value="0.8, 0.7, 0.1"/>
    </bsdf>
</bsdf>"""),
    # Delta and smooth lobes together; the diffuse part is black inside.
    ("blend dielectric + diffuse, w 0.5", """<bsdf type="blendbsdf">
    <float name="weight" value="0.5"/>
    <bsdf type="dielectric">
        <float name="int_ior" value="1.5"/>
    </bsdf>
    <bsdf type="diffuse">
        <rgb name="reflectance" value="0.2, 0.6, 0.2"/>
    </bsdf>
</bsdf>"""),
    ("nested: roughplastic + (conductor Ag + diffuse)", """<bsdf type="blendbsdf">
    <float name="weight" value="0.6"/>
    <bsdf type="roughplastic">
        <string name="distribution" value="ggx"/>
        <float name="alpha" value="0.3"/>
        <rgb name="diffuse_reflectance" value="0.6, 0.3, 0.6"/>
    </bsdf>
    <bsdf type="blendbsdf">
        <float name="weight" value="0.5"/>
        <bsdf type="conductor">
            <string name="material" value="Ag"/>
        </bsdf>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0.8, 0.8, 0.2"/>
        </bsdf>
    </bsdf>
</bsdf>"""),
]

def bsdf_scene(name, comment, items):
    text = header(comment) + cornell()
    for i, (label, b) in enumerate(items):
        text += sphere(i, ind(b), f"s{i}")
    add(name, text, {**slot_regions([l for l, _ in items]), "back wall": [52, 14, 76, 38]})


bsdf_scene("bsdf-plastic", "Plastic, rough plastic (beckmann, ggx) and a thin dielectric.", PLASTICS)
bsdf_scene("bsdf-conductor", "Conductors: named (Au), eta/k, anisotropic rough (Cu), rough beckmann (Ag).", CONDUCTORS)
bsdf_scene("bsdf-dielectric", "Smooth and rough dielectrics: glass, named IORs, beckmann, tinted ggx.", DIELECTRICS)
bsdf_scene("bsdf-principled", "The principled BSDF with four parameter sets.", PRINCIPLED)

# One-sided BSDFs seen from the back, twosided, flip_normals: rectangles
# standing in the box facing away from / toward the camera.
def panel(id_, x, facing_camera, bsdf, flip=False):
    rot = "" if facing_camera else '\n            <rotate y="1" angle="180"/>'
    fl = '\n        <boolean name="flip_normals" value="true"/>' if flip else ""
    return f"""    <shape type="rectangle" id="{id_}">
        <transform name="to_world">
            <scale x="0.2" y="0.4"/>{rot}
            <translate x="{x}" y="-0.5" z="0"/>
        </transform>{fl}
{ind(bsdf)}
    </shape>
"""


def panel_rect(x):
    px, py = project((x, -0.5, 0))
    s = (W / 2) / math.tan(math.radians(FOV_X / 2)) / CAM_Z
    return [int(px - 0.13 * s), int(py - 0.25 * s), int(px + 0.13 * s), int(py + 0.25 * s)]


ONE = '<bsdf type="diffuse">\n    <rgb name="reflectance" value="0.2, 0.5, 0.8"/>\n</bsdf>'
TWO = '<bsdf type="twosided">\n    ' + ONE.replace("\n", "\n    ") + "\n</bsdf>"
text = header("One-sided diffuse seen from the front and back, twosided, flip_normals.") + cornell()
xs = [-0.7, -0.23, 0.23, 0.7]
text += panel("front_onesided", xs[0], True, ONE)
text += panel("back_onesided", xs[1], False, ONE)
text += panel("back_twosided", xs[2], False, TWO)
# (A different colour: Mitsuba 3.9 fails to merge a flipped mesh with
# unflipped ones of an identical BSDF.)
text += panel("flipped_onesided", xs[3], True, ONE.replace("0.2, 0.5, 0.8", "0.8, 0.5, 0.2"), flip=True)
add("bsdf-sides", text, {
    "one-sided, front": panel_rect(xs[0]),
    "one-sided, back": panel_rect(xs[1]),
    "twosided, back": panel_rect(xs[2]),
    "one-sided, flip_normals": panel_rect(xs[3]),
})

# --- Textures ---------------------------------------------------------------


def write_textures():
    t = HERE / "textures"
    t.mkdir(exist_ok=True)
    # An sRGB colour image: four coloured quadrants and a gradient.
    n = 64
    y, x = np.mgrid[0:n, 0:n] / (n - 1)
    img = np.zeros((n, n, 3), np.float32)
    img[..., 0] = np.where(x < 0.5, 0.9, 0.2)
    img[..., 1] = np.where(y < 0.5, 0.8, 0.15)
    img[..., 2] = 0.2 + 0.6 * x * y
    mi.Bitmap(img, mi.Bitmap.PixelFormat.RGB).convert(
        mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(str(t / "quadrants.png"))
    # A tangent-space normal map: a bumpy sine pattern (raw, linear).
    u = 2 * math.pi * 3 * x
    v = 2 * math.pi * 3 * y
    nx, ny = 0.5 * np.cos(u), 0.5 * np.cos(v)
    nz = np.ones_like(nx)
    ln = np.sqrt(nx * nx + ny * ny + nz * nz)
    nm = np.stack([nx / ln, ny / ln, nz / ln], -1) * 0.5 + 0.5
    mi.Bitmap(nm.astype(np.float32), mi.Bitmap.PixelFormat.RGB).convert(
        mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, False).write(str(t / "normals.png"))
    # A height field (grey, linear) for bumpmap.
    h = (0.5 + 0.5 * np.sin(u) * np.sin(v)).astype(np.float32)[..., None]
    mi.Bitmap(h, mi.Bitmap.PixelFormat.Y).convert(
        mi.Bitmap.PixelFormat.Y, mi.Struct.Type.UInt8, False).write(str(t / "height.png"))
    # An opacity mask: a disc (grey, linear).
    m = (((x - 0.5) ** 2 + (y - 0.5) ** 2) < 0.16).astype(np.float32)[..., None]
    mi.Bitmap(m, mi.Bitmap.PixelFormat.Y).convert(
        mi.Bitmap.PixelFormat.Y, mi.Struct.Type.UInt8, False).write(str(t / "disc.png"))
    # A 4x3 image of distinct colours (sRGB), for wrap modes: its texels are
    # large on screen, so where each mode folds them shows.
    cols = np.array([[0.9, 0.1, 0.1], [0.1, 0.8, 0.1], [0.1, 0.2, 0.9], [0.9, 0.8, 0.1]], np.float32)
    wrap = np.stack([cols, cols[::-1] * 0.6, np.roll(cols, 1, 0) * 0.3 + 0.05])
    mi.Bitmap(wrap, mi.Bitmap.PixelFormat.RGB).convert(
        mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(str(t / "wrap.png"))
    # An environment map (equirectangular, 64x32): coloured by direction so
    # that a wrong orientation or seam shows.
    ew, eh = 64, 32
    phi = (np.arange(ew) + 0.5) / ew
    theta = (np.arange(eh) + 0.5) / eh
    pp, tt = np.meshgrid(phi, theta)
    env = np.zeros((eh, ew, 3), np.float32)
    env[..., 0] = 0.2 + 1.5 * (pp < 0.25)
    env[..., 1] = 0.2 + 1.0 * ((pp > 0.5) & (pp < 0.75))
    env[..., 2] = 0.2 + 2.0 * (tt < 0.3)
    mi.Bitmap(env, mi.Bitmap.PixelFormat.RGB).write(str(t / "env.exr"))


def textured_panel(id_, x, bsdf, y=-0.35):
    return f"""    <shape type="rectangle" id="{id_}">
        <transform name="to_world">
            <scale x="0.2" y="0.4"/>
            <translate x="{x}" y="{y}" z="0"/>
        </transform>
{ind(bsdf)}
    </shape>
"""


def tpanel_rect(x, y=-0.35):
    px, py = project((x, y, 0))
    s = (W / 2) / math.tan(math.radians(FOV_X / 2)) / CAM_Z
    return [int(px - 0.13 * s), int(py - 0.25 * s), int(px + 0.13 * s), int(py + 0.25 * s)]


BITMAP = """<bsdf type="twosided"><bsdf type="diffuse">
    <texture type="bitmap" name="reflectance">
        <string name="filename" value="textures/quadrants.png"/>
        <string name="filter_type" value="nearest"/>
    </texture>
</bsdf></bsdf>"""
BITMAP_UV = """<bsdf type="twosided"><bsdf type="diffuse">
    <texture type="bitmap" name="reflectance">
        <string name="filename" value="textures/quadrants.png"/>
        <string name="filter_type" value="nearest"/>
        <transform name="to_uv">
            <scale x="2" y="3"/>
        </transform>
    </texture>
</bsdf></bsdf>"""
CHECKER = """<bsdf type="twosided"><bsdf type="diffuse">
    <texture type="checkerboard" name="reflectance">
        <rgb name="color0" value="0.8, 0.1, 0.1"/>
        <rgb name="color1" value="0.1, 0.1, 0.8"/>
    </texture>
</bsdf></bsdf>"""
CHECKER_UV = """<bsdf type="twosided"><bsdf type="diffuse">
    <texture type="checkerboard" name="reflectance">
        <rgb name="color0" value="0.8, 0.8, 0.1"/>
        <rgb name="color1" value="0.1, 0.6, 0.1"/>
        <transform name="to_uv">
            <scale x="4" y="2"/>
        </transform>
    </texture>
</bsdf></bsdf>"""
text = header("Diffuse with a bitmap and a checkerboard, each plain and with to_uv.") + cornell()
xs = [-0.7, -0.23, 0.23, 0.7]
for i, b in enumerate([BITMAP, BITMAP_UV, CHECKER, CHECKER_UV]):
    text += textured_panel(f"t{i}", xs[i], b)
add("tex-diffuse", text, {
    "bitmap": tpanel_rect(xs[0]), "bitmap to_uv": tpanel_rect(xs[1]),
    "checkerboard": tpanel_rect(xs[2]), "checkerboard to_uv": tpanel_rect(xs[3]),
})

# blendbsdf: spheres, but the textured weight on a panel (see BLENDS).
text = header("blendbsdf: a constant and a textured weight, delta with smooth parts, nested.") + cornell()
regions = {}
for i, (label, b) in enumerate(BLENDS):
    if "panel" in label:
        x = SLOTS[i][0][0]
        text += textured_panel(f"s{i}", x, b)
        regions[label] = tpanel_rect(x)
    else:
        text += sphere(i, ind(b), f"s{i}")
        regions[label] = rect(*SLOTS[i])
add("bsdf-blend", text, {**regions, "back wall": [52, 14, 76, 38]})

NORMALMAP = """<bsdf type="normalmap">
    <texture type="bitmap" name="normalmap">
        <string name="filename" value="textures/normals.png"/>
        <boolean name="raw" value="true"/>
    </texture>
    <bsdf type="roughplastic">
        <float name="alpha" value="0.1"/>
        <rgb name="diffuse_reflectance" value="0.6, 0.6, 0.6"/>
    </bsdf>
</bsdf>"""
BUMPMAP = """<bsdf type="bumpmap">
    <texture type="bitmap">
        <string name="filename" value="textures/height.png"/>
        <boolean name="raw" value="true"/>
    </texture>
    <float name="scale" value="0.5"/>
    <bsdf type="roughplastic">
        <float name="alpha" value="0.1"/>
        <rgb name="diffuse_reflectance" value="0.6, 0.6, 0.6"/>
    </bsdf>
</bsdf>"""
MASK = """<bsdf type="mask">
    <texture type="bitmap" name="opacity">
        <string name="filename" value="textures/disc.png"/>
        <boolean name="raw" value="true"/>
    </texture>
    <bsdf type="diffuse">
        <rgb name="reflectance" value="0.8, 0.5, 0.1"/>
    </bsdf>
</bsdf>"""
MASK_CONST = """<bsdf type="mask">
    <float name="opacity" value="0.5"/>
    <bsdf type="diffuse">
        <rgb name="reflectance" value="0.8, 0.5, 0.1"/>
    </bsdf>
</bsdf>"""
text = header("normalmap, bumpmap, mask (bitmap and constant opacity).") + cornell()
for i, b in enumerate([NORMALMAP, BUMPMAP, MASK, MASK_CONST]):
    text += textured_panel(f"t{i}", xs[i], b)
add("tex-maps", text, {
    "normalmap": tpanel_rect(xs[0]), "bumpmap": tpanel_rect(xs[1]),
    "mask bitmap": tpanel_rect(xs[2]), "mask 0.5": tpanel_rect(xs[3]),
})

VERTEX_COLOR = """<texture type="mesh_attribute" name="{slot}">
    <string name="name" value="vertex_color"/>{extra}
</texture>"""


def vertex_color_sphere_ply(n_theta=12, n_phi=24):
    """A coarse UV sphere as an ASCII PLY with vertex normals and float
    red/green/blue colours that vary with the normal (linear, as Mitsuba
    reads float colours)."""
    verts, faces = [], []
    for i in range(n_theta + 1):
        t = math.pi * i / n_theta
        for j in range(n_phi):
            p = 2 * math.pi * j / n_phi
            n = (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))
            rgb = (0.5 + 0.4 * n[0], 0.5 + 0.4 * n[1], 0.5 - 0.4 * n[2])
            verts.append(n + n + rgb)
    for i in range(n_theta):
        for j in range(n_phi):
            a, b = i * n_phi + j, i * n_phi + (j + 1) % n_phi
            c, d = a + n_phi, b + n_phi
            if i > 0:
                faces.append((a, b, c))
            if i < n_theta - 1:
                faces.append((b, d, c))
    head = (f"ply\nformat ascii 1.0\nelement vertex {len(verts)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            "property float red\nproperty float green\nproperty float blue\n"
            f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    body = "".join(" ".join(f"{c:.6f}" for c in v) + "\n" for v in verts)
    body += "".join(f"3 {a} {b} {c}\n" for a, b, c in faces)
    return head + body


def vertex_color_quad_ply():
    """A square of two triangles with a saturated colour at each corner."""
    corners = [(-1, -1, 0, 0.9, 0.1, 0.1), (1, -1, 0, 0.1, 0.9, 0.1),
               (1, 1, 0, 0.1, 0.1, 0.9), (-1, 1, 0, 0.9, 0.9, 0.1)]
    head = ("ply\nformat ascii 1.0\nelement vertex 4\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float red\nproperty float green\nproperty float blue\n"
            "element face 2\nproperty list uchar int vertex_indices\nend_header\n")
    body = "".join(" ".join(f"{c:g}" for c in v) + "\n" for v in corners)
    return head + body + "3 0 1 2\n3 0 2 3\n"


def write_vertex_color_meshes(t):
    (t / "sphere_colors.ply").write_text(vertex_color_sphere_ply())
    (t / "quad_colors.ply").write_text(vertex_color_quad_ply())


def vc_shape(id_, fname, transform, bsdf):
    return f"""    <shape type="ply" id="{id_}">
        <string name="filename" value="textures/{fname}"/>
        <transform name="to_world">
{ind(transform, 12)}
        </transform>
{ind(bsdf)}
    </shape>
"""


def vc_sphere_transform(i, extra=""):
    (x, y, z), r = SLOTS[i]
    return f'{extra}<scale value="{r}"/>\n<translate x="{x}" y="{y}" z="{z}"/>'


VC_DIFFUSE = ('<bsdf type="diffuse">\n'
              + ind(VERTEX_COLOR.format(slot="reflectance", extra=""), 4) + "\n</bsdf>")
VC_QUAD = ('<bsdf type="twosided"><bsdf type="diffuse">\n'
           + ind(VERTEX_COLOR.format(slot="reflectance",
                                     extra='\n    <float name="scale" value="0.8"/>'), 4)
           + "\n</bsdf></bsdf>")
# (Mitsuba's plastic and roughplastic need a texture's mean, which its
# mesh_attribute lacks; principled does not.)
VC_PRINCIPLED = ('<bsdf type="principled">\n'
                 + ind(VERTEX_COLOR.format(slot="base_color", extra=""), 4)
                 + '\n    <float name="roughness" value="0.4"/>\n</bsdf>')
text = header("Vertex colours: PLY red/green/blue read by mesh_attribute vertex_color on a "
              "diffuse sphere, a two-sided square (scale 0.8), a principled base_color, "
              "and a turned, squashed sphere.") + cornell()
VC_X = SLOTS[1][0][0]
text += vc_shape("vc_sphere", "sphere_colors.ply", vc_sphere_transform(0), VC_DIFFUSE)
text += vc_shape("vc_quad", "quad_colors.ply",
                 f'<scale x="0.2" y="0.4"/>\n<translate x="{VC_X}" y="-0.35" z="0"/>', VC_QUAD)
text += vc_shape("vc_principled", "sphere_colors.ply", vc_sphere_transform(2), VC_PRINCIPLED)
text += vc_shape("vc_turned", "sphere_colors.ply",
                 vc_sphere_transform(3, '<rotate y="1" angle="70"/>\n<scale x="1" y="0.7" z="1"/>\n'),
                 VC_DIFFUSE)
add("tex-vertex-color", text, {
    "diffuse sphere": rect(*SLOTS[0]), "square, scale 0.8": tpanel_rect(VC_X),
    "principled sphere": rect(*SLOTS[2]), "turned sphere": rect(*SLOTS[3], frac=0.35),
})

# --- Shapes -----------------------------------------------------------------

BLUE = '<bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.8"/></bsdf></bsdf>'
ORANGE = '<bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.4, 0.1"/></bsdf></bsdf>'
text = header("Sphere (centre+radius, to_world scale), disk, cube, shapegroup + instance.") + cornell()
text += f"""    <shape type="sphere" id="sphere_scaled">
        <float name="radius" value="0.5"/>
        <transform name="to_world">
            <scale value="0.44"/>
            <translate x="{SLOTS[0][0][0]}" y="{SLOTS[0][0][1]}" z="{SLOTS[0][0][2]}"/>
        </transform>
        {BLUE}
    </shape>
    <shape type="disk" id="disk">
        <transform name="to_world">
            <scale value="0.2"/>
            <rotate x="1" angle="-20"/>
            <translate x="{SLOTS[1][0][0]}" y="-0.7" z="{SLOTS[1][0][2]}"/>
        </transform>
        {ORANGE}
    </shape>
    <shape type="cube" id="cube">
        <transform name="to_world">
            <scale value="0.15"/>
            <rotate y="1" angle="30"/>
            <rotate x="1" angle="20"/>
            <translate x="{SLOTS[2][0][0]}" y="-0.8" z="{SLOTS[2][0][2]}"/>
        </transform>
        {ORANGE}
    </shape>
    <shape type="shapegroup" id="group">
        <shape type="sphere">
            <float name="radius" value="0.5"/>
            {BLUE}
        </shape>
        <shape type="cube">
            <transform name="to_world">
                <scale value="0.3"/>
                <translate y="0.6"/>
            </transform>
            {ORANGE}
        </shape>
    </shape>
    <shape type="instance">
        <ref id="group"/>
        <transform name="to_world">
            <scale value="0.3"/>
            <rotate z="1" angle="-30"/>
            <translate x="{SLOTS[3][0][0]}" y="-0.82" z="{SLOTS[3][0][2]}"/>
        </transform>
    </shape>
    <shape type="instance">
        <ref id="group"/>
        <transform name="to_world">
            <scale value="0.25"/>
            <translate x="0" y="0.1" z="-0.6"/>
        </transform>
    </shape>
"""
add("shapes", text, {
    "sphere to_world": rect(SLOTS[0][0], 0.22),
    "disk": rect((SLOTS[1][0][0], -0.7, SLOTS[1][0][2]), 0.18),
    "cube": rect((SLOTS[2][0][0], -0.8, SLOTS[2][0][2]), 0.15),
    "instance": rect((SLOTS[3][0][0], -0.82, SLOTS[3][0][2]), 0.13),
    "back wall": [52, 14, 76, 38],
})

# Cylinders: p0/p1/radius, to_world, a bitmap on Mitsuba's uv, flip_normals.
QUAD = """<bsdf type="diffuse">
    <texture type="bitmap" name="reflectance">
        <string name="filename" value="textures/quadrants.png"/>
    </texture>
</bsdf>"""
CX = [slot[0][0] for slot in SLOTS]
text = header("Cylinders: p0/p1/radius, to_world, a bitmap on its uv, flip_normals.") + cornell()
text += f"""    <shape type="cylinder" id="cyl_points">
        <point name="p0" x="{CX[0]}" y="-1" z="0"/>
        <point name="p1" x="{CX[0]}" y="-0.55" z="0"/>
        <float name="radius" value="0.18"/>
        {BLUE}
    </shape>
    <shape type="cylinder" id="cyl_textured">
        <transform name="to_world">
            <scale x="0.18" y="0.18" z="0.45"/>
            <rotate x="1" angle="-90"/>
            <rotate y="1" angle="40"/>
            <translate x="{CX[1]}" y="-1" z="0"/>
        </transform>
{ind(QUAD)}
    </shape>
    <shape type="cylinder" id="cyl_flipped">
        <transform name="to_world">
            <scale x="0.18" y="0.18" z="0.4"/>
            <rotate x="1" angle="-60"/>
            <translate x="{CX[2]}" y="-1" z="0.1"/>
        </transform>
        <boolean name="flip_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.7, 0.2"/></bsdf>
    </shape>
    <shape type="cylinder" id="cyl_lying">
        <point name="p0" x="-0.2" y="0" z="0"/>
        <point name="p1" x="0.2" y="0" z="0"/>
        <float name="radius" value="0.16"/>
        <transform name="to_world">
            <rotate y="1" angle="-30"/>
            <translate x="{CX[3]}" y="-0.84" z="0"/>
        </transform>
        {ORANGE}
    </shape>
"""
add("shapes-cylinder", text, {
    "cylinder p0 p1": rect((CX[0], -0.78, 0.0), 0.18),
    "cylinder textured": rect((CX[1], -0.78, 0.0), 0.18),
    "cylinder flipped": rect((CX[2], -0.8, 0.25), 0.14),
    "cylinder lying": rect((CX[3], -0.84, 0.0), 0.16),
    "back wall": [52, 14, 76, 38],
})


def write_ply_sphere(path, n_theta=12, n_phi=24):
    """A coarse UV sphere as a binary PLY with per-vertex normals."""
    verts, faces = [], []
    for i in range(n_theta + 1):
        t = math.pi * i / n_theta
        for j in range(n_phi):
            p = 2 * math.pi * j / n_phi
            v = (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))
            verts.append(v + v)
    for i in range(n_theta):
        for j in range(n_phi):
            a, b = i * n_phi + j, i * n_phi + (j + 1) % n_phi
            c, d = a + n_phi, b + n_phi
            if i > 0:
                faces.append((a, b, c))
            if i < n_theta - 1:
                faces.append((b, d, c))
    head = (f"ply\nformat ascii 1.0\nelement vertex {len(verts)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    body = "".join(" ".join(f"{c:.6f}" for c in v) + "\n" for v in verts)
    body += "".join(f"3 {a} {b} {c}\n" for a, b, c in faces)
    path.write_text(head + body)


text = header("A coarse PLY sphere with its vertex normals and with face_normals.") + cornell()
for i, fn in enumerate([False, True]):
    (x, y, z), r = SLOTS[2 + i]
    fnx = '\n        <boolean name="face_normals" value="true"/>' if fn else ""
    text += f"""    <shape type="ply" id="ply{i}">
        <string name="filename" value="textures/sphere.ply"/>{fnx}
        <transform name="to_world">
            <scale value="{r}"/>
            <translate x="{x}" y="{y}" z="{z}"/>
        </transform>
        <bsdf type="roughplastic">
            <float name="alpha" value="0.1"/>
            <rgb name="diffuse_reflectance" value="0.3, 0.5, 0.7"/>
        </bsdf>
    </shape>
"""
add("shapes-normals", text, {"ply smooth normals": rect(*SLOTS[2]), "ply face_normals": rect(*SLOTS[3])})


def uv_sphere(n_theta=12, n_phi=24):
    """A coarse UV sphere with its seam column doubled: positions, uvs, faces
    (counter-clockwise seen from outside)."""
    pos, uv, faces = [], [], []
    for i in range(n_theta + 1):
        t = math.pi * i / n_theta
        for j in range(n_phi + 1):
            p = 2 * math.pi * j / n_phi
            pos.append((math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p)))
            uv.append((j / n_phi, i / n_theta))
    cols = n_phi + 1
    for i in range(n_theta):
        for j in range(n_phi):
            a, b = i * cols + j, i * cols + j + 1
            c, d = a + cols, b + cols
            if i > 0:
                faces.append((a, b, c))
            if i < n_theta - 1:
                faces.append((b, d, c))
    return pos, uv, faces


def write_serialized(path, meshes):
    """Meshes [(name, flags, pos, normals, uv, faces)] as a version 4
    .serialized file (the layout of Mitsuba's `serialized` documentation)."""
    out, offsets = b"", []
    for name, flags, pos, nrm, uv, faces in meshes:
        real = "d" if flags & 0x2000 else "f"
        raw = struct.pack("<I", flags) + name.encode() + b"\0"
        raw += struct.pack("<QQ", len(pos), len(faces))
        raw += struct.pack(f"<{3 * len(pos)}{real}", *[c for p in pos for c in p])
        if flags & 0x1:
            raw += struct.pack(f"<{3 * len(nrm)}{real}", *[c for n in nrm for c in n])
        if flags & 0x2:
            raw += struct.pack(f"<{2 * len(uv)}{real}", *[c for t in uv for c in t])
        raw += struct.pack(f"<{3 * len(faces)}I", *[i for f in faces for i in f])
        offsets.append(len(out))
        out += struct.pack("<HH", 0x041C, 4) + zlib.compress(raw)
    out += struct.pack(f"<{len(offsets)}Q", *offsets) + struct.pack("<I", len(offsets))
    path.write_bytes(out)


def write_mesh_files(t):
    pos, uv, faces = uv_sphere()
    write_serialized(t / "spheres.serialized", [
        ("with normals and uv", 0x1 | 0x2 | 0x1000, pos, pos, uv, faces),
        ("positions only, double", 0x2000, pos, None, None, faces),
    ])
    (t / "sphere_bare.ply").write_text(
        f"ply\nformat ascii 1.0\nelement vertex {len(pos)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
        + "".join(" ".join(f"{c:.6f}" for c in p) + "\n" for p in pos)
        + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces))
    # The same sphere with its uv, as PLY and OBJ (the same numbers in both
    # files: Mitsuba flips the OBJ's v and keeps the PLY's).
    (t / "sphere_uv.ply").write_text(
        f"ply\nformat ascii 1.0\nelement vertex {len(pos)}\n"
        "property float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
        + "".join(" ".join(f"{c:.6f}" for c in p + t_) + "\n" for p, t_ in zip(pos, uv))
        + "".join(f"3 {a} {b} {c}\n" for a, b, c in faces))
    (t / "sphere_uv.obj").write_text(
        "".join("v " + " ".join(f"{c:.6f}" for c in p) + "\n" for p in pos)
        + "".join(f"vt {u:.6f} {v:.6f}\n" for u, v in uv)
        + "".join(f"f {a + 1}/{a + 1} {b + 1}/{b + 1} {c + 1}/{c + 1}\n" for a, b, c in faces))
    (t / "sphere_bare.obj").write_text(
        "".join("v " + " ".join(f"{c:.6f}" for c in p) + "\n" for p in pos)
        + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces))


MESH_SHAPES = [
    ("serialized, its normals and uv", "serialized", "spheres.serialized", "", QUAD),
    ("serialized shape_index 1, no normals", "serialized", "spheres.serialized",
     '\n        <integer name="shape_index" value="1"/>',
     '<bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>'),
    ("ply without normals", "ply", "sphere_bare.ply", "",
     '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>'),
    ("obj without normals", "obj", "sphere_bare.obj", "",
     '<bsdf type="diffuse"><rgb name="reflectance" value="0.4, 0.7, 0.4"/></bsdf>'),
]
text = header("Mesh files: serialized (two meshes, normals and uv, double precision), "
              "and meshes without normals, which Mitsuba shades smoothly.") + cornell()
for i, (label, kind, fname, extra, bsdf) in enumerate(MESH_SHAPES):
    (x, y, z), r = SLOTS[i]
    text += f"""    <shape type="{kind}" id="mesh{i}">
        <string name="filename" value="textures/{fname}"/>{extra}
        <transform name="to_world">
            <scale value="{r}"/>
            <rotate y="1" angle="-60"/>
            <translate x="{x}" y="{y}" z="{z}"/>
        </transform>
{ind(bsdf)}
    </shape>
"""
add("shapes-meshes", text, {**slot_regions([m[0] for m in MESH_SHAPES]), "back wall": [52, 14, 76, 38]})

# --- Emitters ---------------------------------------------------------------

GREY_SPHERES = "".join(
    sphere(i, '        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf>', f"s{i}")
    for i in range(4))
EMIT_REGIONS = {**slot_regions(["sphere 1", "sphere 2", "sphere 3", "sphere 4"]),
                "floor front": [40, 84, 88, 94], "back wall": [40, 10, 88, 30]}


def emitter_scene(name, comment, emitters, max_depth=8):
    text = header(comment, max_depth=max_depth) + stage() + GREY_SPHERES + emitters
    add(name, text, EMIT_REGIONS)


emitter_scene("emit-point", "A point light (intensity), off-centre.", """    <emitter type="point">
        <point name="position" x="-0.5" y="1.2" z="1.0"/>
        <rgb name="intensity" value="3, 2.5, 2"/>
    </emitter>
""")
emitter_scene("emit-spot-hard", "A spot light with beam_width = cutoff_angle (a hard edge).", """    <emitter type="spot">
        <transform name="to_world">
            <lookat origin="0.3, 1.5, 1.5" target="0, -1, -0.3"/>
        </transform>
        <rgb name="intensity" value="8, 7, 6"/>
        <float name="cutoff_angle" value="25"/>
        <float name="beam_width" value="25"/>
    </emitter>
""")
emitter_scene("emit-spot-soft", "A spot light with Mitsuba's default fade (beam_width 0.75 cutoff).", """    <emitter type="spot">
        <transform name="to_world">
            <lookat origin="0.3, 1.5, 1.5" target="0, -1, -0.3"/>
        </transform>
        <rgb name="intensity" value="8, 7, 6"/>
        <float name="cutoff_angle" value="30"/>
    </emitter>
""")
emitter_scene("emit-directional", "A directional light (irradiance) from upper left.", """    <emitter type="directional">
        <vector name="direction" x="0.5" y="-1" z="-0.4"/>
        <rgb name="irradiance" value="2, 1.8, 1.5"/>
    </emitter>
""")
emitter_scene("emit-constant", "A constant environment.", """    <emitter type="constant">
        <rgb name="radiance" value="0.8, 0.9, 1.0"/>
    </emitter>
""")
emitter_scene("emit-envmap", "An environment map (generated, 64x32) with scale 1.5; max_depth 2 (direct only).", """    <emitter type="envmap">
        <string name="filename" value="textures/env.exr"/>
        <float name="scale" value="1.5"/>
    </emitter>
""", max_depth=2)

# The environment seen directly: no stage, a mirror ball and a diffuse ball.
text = header("An environment map seen directly and in a mirror sphere (orientation).",
              lookat='origin="0, 0.3, 3.6" target="0, 0, 0" up="0, 1, 0"')
text += """    <emitter type="envmap">
        <string name="filename" value="textures/env.exr"/>
    </emitter>
    <shape type="sphere" id="mirror">
        <point name="center" x="-0.5" y="0" z="0"/>
        <float name="radius" value="0.45"/>
        <bsdf type="conductor"/>
    </shape>
    <shape type="sphere" id="diffuse">
        <point name="center" x="0.5" y="0" z="0"/>
        <float name="radius" value="0.45"/>
        <bsdf type="diffuse"/>
    </shape>
"""
add("emit-envmap-direct", text, {"left sky": [0, 0, 20, 30], "right sky": [108, 0, 128, 30],
                                 "centre bottom sky": [54, 80, 74, 96]})

# The same, the map turned by its to_world (a yaw and a tilt).
add("emit-envmap-rotated", text.replace(
    "An environment map seen directly and in a mirror sphere (orientation).",
    "An environment map turned by its to_world, seen directly and in a mirror sphere.").replace(
    """        <string name="filename" value="textures/env.exr"/>
    </emitter>""", """        <string name="filename" value="textures/env.exr"/>
        <transform name="to_world">
            <rotate y="1" angle="70"/>
            <rotate x="1" angle="25"/>
        </transform>
    </emitter>"""), {"left sky": [0, 0, 20, 30], "right sky": [108, 0, 128, 30],
                     "centre bottom sky": [54, 80, 74, 96]})

emitter_scene("emit-area", "Area emitters on a sphere and on a rectangle (one-sided, facing down-forward).", """    <shape type="sphere" id="lamp_sphere">
        <point name="center" x="-0.6" y="0.5" z="0"/>
        <float name="radius" value="0.15"/>
        <emitter type="area">
            <rgb name="radiance" value="6, 5, 4"/>
        </emitter>
    </shape>
    <shape type="rectangle" id="lamp_rect">
        <transform name="to_world">
            <scale x="0.3" y="0.15"/>
            <rotate x="1" angle="120"/>
            <translate x="0.6" y="0.6" z="0.2"/>
        </transform>
        <emitter type="area">
            <rgb name="radiance" value="5, 6, 8"/>
        </emitter>
    </shape>
""")

# --- hide_emitters and spectra ---------------------------------------------

# The integrator's hide_emitters (a lamp and the sky seen directly are
# black; in the mirror they show), with colours given as spectra: light in
# an emitter (equal-energy white is not RGB white), reflectances under D65,
# a conductor's eta and k.
text = header("hide_emitters, with spectra for light, reflectances and a conductor's eta and k.",
              lookat='origin="0, 0.35, 3.6" target="0, -0.2, 0" up="0, 1, 0"')
text = text.replace('<integer name="max_depth" value="$max_depth"/>',
                    '<integer name="max_depth" value="$max_depth"/>\n        <boolean name="hide_emitters" value="true"/>')
text += """    <emitter type="constant">
        <spectrum name="radiance" value="0.6"/>
    </emitter>
    <shape type="rectangle" id="floor">
        <transform name="to_world">
            <scale value="3"/>
            <rotate x="1" angle="-90"/>
            <translate y="-1"/>
        </transform>
        <bsdf type="diffuse">
            <spectrum name="reflectance" value="400:0.2, 450:0.35, 500:0.6, 550:0.7, 600:0.55, 650:0.4, 700:0.3"/>
        </bsdf>
    </shape>
    <shape type="sphere" id="lamp">
        <point name="center" x="-0.7" y="-0.55" z="-0.3"/>
        <float name="radius" value="0.3"/>
        <emitter type="area">
            <spectrum name="radiance" value="400:0, 500:8, 600:15.6, 700:18.4"/>
        </emitter>
    </shape>
    <shape type="sphere" id="mirror">
        <point name="center" x="0.05" y="-0.6" z="0.1"/>
        <float name="radius" value="0.38"/>
        <bsdf type="conductor">
            <spectrum name="eta" value="400:1.2, 550:0.6, 700:0.2"/>
            <spectrum name="k" value="400:2.0, 550:2.6, 700:3.8"/>
        </bsdf>
    </shape>
    <shape type="sphere" id="ball">
        <point name="center" x="0.75" y="-0.7" z="-0.1"/>
        <float name="radius" value="0.3"/>
        <bsdf type="diffuse">
            <spectrum name="reflectance" value="400:0.05, 480:0.1, 520:0.5, 560:0.6, 620:0.2, 700:0.1"/>
        </bsdf>
    </shape>
"""
add("emit-hide-spectra", text, {"mirror": [60, 52, 74, 66], "ball": [86, 60, 98, 72], "lit floor": [10, 68, 50, 82]})

# --- Wrap modes, null surfaces, flipped spheres -----------------------------

# A 4x3 bitmap read at uv in [-1, 2]^2 (to_uv scale 3, shift -1): outside the
# image mirror and clamp fold the texels, for both filters.
def wrapped(mode, filt):
    return f"""<bsdf type="twosided"><bsdf type="diffuse">
    <texture type="bitmap" name="reflectance">
        <string name="filename" value="textures/wrap.png"/>
        <string name="wrap_mode" value="{mode}"/>
        <string name="filter_type" value="{filt}"/>
        <transform name="to_uv">
            <scale x="3" y="3"/>
            <translate x="-1" y="-1"/>
        </transform>
    </texture>
</bsdf></bsdf>"""


WRAPS = [("mirror", "nearest"), ("clamp", "nearest"), ("mirror", "bilinear"), ("clamp", "bilinear")]
text = header("Bitmap wrap_mode mirror and clamp, nearest and bilinear, read at uv in [-1, 2].") + cornell()
xs = [-0.7, -0.23, 0.23, 0.7]
for i, (mode, filt) in enumerate(WRAPS):
    text += textured_panel(f"t{i}", xs[i], wrapped(mode, filt))
add("tex-wrap", text, {f"{m} {f}": tpanel_rect(xs[i]) for i, (m, f) in enumerate(WRAPS)})

# Textures on analytic spheres: Mitsuba's sphere puts its pole on local +z
# (here toward the camera unless turned) with u around it from +x, so the
# parameterisation, the seam and the poles all show.
TSPHERES = [
    ("bitmap, pole to the camera", BITMAP, ""),
    ("bitmap, turned: pole up", BITMAP, '<rotate x="1" angle="-90"/>\n            <rotate y="1" angle="30"/>'),
    ("checkerboard to_uv, pole to the camera", CHECKER_UV, ""),
    ("checkerboard to_uv, turned", CHECKER_UV, '<rotate x="1" angle="-60"/>\n            <rotate z="1" angle="40"/>'),
]


def textured_sphere(id_, x, bsdf, turn):
    return f"""    <shape type="sphere" id="{id_}">
        <transform name="to_world">
            {turn}
            <scale value="0.3"/>
            <translate x="{x}" y="-0.45" z="0"/>
        </transform>
{ind(bsdf)}
    </shape>
"""


def tsphere_rect(x):
    px, py = project((x, -0.45, 0))
    s = (W / 2) / math.tan(math.radians(FOV_X / 2)) / CAM_Z
    return [int(px - 0.22 * s), int(py - 0.22 * s), int(px + 0.22 * s), int(py + 0.22 * s)]


text = header("Bitmap and checkerboard textures on analytic spheres, pole toward the camera and turned.") + cornell()
xs = [-0.7, -0.23, 0.23, 0.7]
for i, (label, b, turn) in enumerate(TSPHERES):
    text += textured_sphere(f"s{i}", xs[i], b, turn)
add("tex-sphere", text, {label: tsphere_rect(xs[i]) for i, (label, _, _) in enumerate(TSPHERES)})

# Shading frames on analytic spheres: a normal map and a bump map (both
# read dp/du and dp/dv), an anisotropic rough conductor (its tangent is
# dp/du) and a sphere lamp with a bitmap radiance, all turned.
ANISO = """<bsdf type="roughconductor">
    <string name="material" value="Au"/>
    <float name="alpha_u" value="0.05"/>
    <float name="alpha_v" value="0.4"/>
</bsdf>"""
TEX_LAMP = """<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.2, 0.2"/></bsdf>
<emitter type="area">
    <texture type="bitmap" name="radiance">
        <string name="filename" value="textures/quadrants.png"/>
        <string name="filter_type" value="nearest"/>
    </texture>
</emitter>"""
TURN = '<rotate x="1" angle="-70"/>\n            <rotate y="1" angle="25"/>'
SPHERE_MAPS = [("normalmap", NORMALMAP), ("bumpmap", BUMPMAP), ("anisotropic roughconductor", ANISO),
               ("bitmap area emitter", TEX_LAMP)]
text = header("Normal map, bump map, anisotropic conductor and a bitmap lamp on turned analytic spheres.") + cornell()
for i, (label, b) in enumerate(SPHERE_MAPS):
    text += textured_sphere(f"s{i}", xs[i], b, TURN)
add("tex-sphere-maps", text, {label: tsphere_rect(xs[i]) for i, (label, _) in enumerate(SPHERE_MAPS)})

# Textures in the parameters of BSDFs other than diffuse: a checkerboard
# roughness on a rough conductor, bitmaps in plastic's diffuse reflectance
# (smooth and rough), and a principled BSDF with a bitmap base colour and a
# checkerboard roughness and metallic.
TEX_BSDFS = [
    ("roughconductor, checkerboard alpha", """<bsdf type="roughconductor">
    <string name="material" value="Al"/>
    <texture type="checkerboard" name="alpha">
        <float name="color0" value="0.05"/>
        <float name="color1" value="0.5"/>
        <transform name="to_uv"><scale x="2" y="3"/></transform>
    </texture>
</bsdf>"""),
    ("plastic, bitmap", """<bsdf type="plastic">
    <texture type="bitmap" name="diffuse_reflectance">
        <string name="filename" value="textures/quadrants.png"/>
        <string name="filter_type" value="nearest"/>
    </texture>
</bsdf>"""),
    ("roughplastic ggx, bitmap", """<bsdf type="roughplastic">
    <string name="distribution" value="ggx"/>
    <float name="alpha" value="0.25"/>
    <texture type="bitmap" name="diffuse_reflectance">
        <string name="filename" value="textures/quadrants.png"/>
        <string name="filter_type" value="nearest"/>
    </texture>
</bsdf>"""),
    ("principled, textured", """<bsdf type="principled">
    <texture type="bitmap" name="base_color">
        <string name="filename" value="textures/quadrants.png"/>
        <string name="filter_type" value="nearest"/>
    </texture>
    <texture type="checkerboard" name="roughness">
        <float name="color0" value="0.15"/>
        <float name="color1" value="0.6"/>
        <transform name="to_uv"><scale x="2" y="2"/></transform>
    </texture>
    <texture type="checkerboard" name="metallic">
        <float name="color0" value="0.0"/>
        <float name="color1" value="0.8"/>
        <transform name="to_uv"><scale x="1" y="3"/></transform>
    </texture>
</bsdf>"""),
]
text = header("Textures in the parameters of conductor, plastic and principled BSDFs.") + cornell()
for i, (label, b) in enumerate(TEX_BSDFS):
    text += textured_panel(f"t{i}", xs[i], b)
add("tex-bsdfs", text, {label: tpanel_rect(xs[i]) for i, (label, _) in enumerate(TEX_BSDFS)})

# Textures and shading frames on the built-in shapes Candela tessellates,
# each turned by its to_world (a non-uniform scale where Mitsuba allows one:
# the cylinder only along its axis): where each puts uv (0, 0) and which
# way u and v run (a `nearest` bitmap), its dp/du (the tangent of an
# anisotropic conductor) and its tangent frame (normal and bump maps). The
# cubes are turned two ways so that all six faces show between them.
TSHAPE_Y = -0.45


def turned_shape(kind, id_, x, bsdf, turn, extra=""):
    return f"""    <shape type="{kind}" id="{id_}">{extra}
        <transform name="to_world">
            {turn}
            <translate x="{x}" y="{TSHAPE_Y}" z="0"/>
        </transform>
{ind(bsdf)}
    </shape>
"""


def tshape_rect(x, half=0.12):
    px, py = project((x, TSHAPE_Y, 0))
    s = (W / 2) / math.tan(math.radians(FOV_X / 2)) / CAM_Z
    return [int(px - half * s), int(py - half * s), int(px + half * s), int(py + half * s)]


TSHAPES = [
    ("rectangle", '<scale x="0.2" y="0.32"/>\n            <rotate z="1" angle="30"/>\n'
                  '            <rotate y="1" angle="35"/>\n            <rotate x="1" angle="15"/>'),
    ("disk", '<scale x="0.3" y="0.22"/>\n            <rotate z="1" angle="20"/>\n'
             '            <rotate x="1" angle="-30"/>\n            <rotate y="1" angle="20"/>'),
    ("cube", '<scale x="0.16" y="0.2" z="0.13"/>\n            <rotate y="1" angle="35"/>\n'
             '            <rotate x="1" angle="25"/>'),
    ("cylinder", '<translate z="-0.5"/>\n            <scale x="0.17" y="0.17" z="0.5"/>\n'
                 '            <rotate z="1" angle="50"/>\n            <rotate x="1" angle="-75"/>\n'
                 '            <rotate z="1" angle="-25"/>'),
]
# The second cube shows the faces the first hides (-x, -y, -z).
CUBE_BACK = ('<scale x="0.16" y="0.2" z="0.13"/>\n            <rotate y="1" angle="215"/>\n'
             '            <rotate x="1" angle="-25"/>')
SHAPE_SCENES = [
    ("tex-shapes", "a nearest bitmap", BITMAP),
    ("tex-shapes-aniso", "an anisotropic rough conductor (alpha_u 0.05, alpha_v 0.4)", ANISO),
    ("tex-shapes-normalmap", "a normal map", NORMALMAP),
    ("tex-shapes-bumpmap", "a bump map", BUMPMAP),
]
for name, what, b in SHAPE_SCENES:
    text = header(f"Rectangle, disk, cube and cylinder, each turned and scaled, with {what}.") + cornell()
    for i, (kind, turn) in enumerate(TSHAPES):
        text += turned_shape(kind, f"s{i}", xs[i], b, turn)
    add(name, text, {kind: tshape_rect(xs[i]) for i, (kind, _) in enumerate(TSHAPES)})
CUBE_MAPS = [("bitmap", BITMAP), ("anisotropic roughconductor", ANISO), ("normalmap", NORMALMAP),
             ("bumpmap", BUMPMAP)]
text = header("Cubes turned to show their -x, -y and -z faces: bitmap, anisotropic conductor, "
              "normal map, bump map.") + cornell()
for i, (label, b) in enumerate(CUBE_MAPS):
    text += turned_shape("cube", f"c{i}", xs[i], b, CUBE_BACK)
add("tex-cube-back", text, {label: tshape_rect(xs[i]) for i, (label, _) in enumerate(CUBE_MAPS)})


# Mesh files with uv: PLY (Mitsuba keeps its v), OBJ (Mitsuba flips its v on
# reading), serialized (kept), and a sphere in a shape group placed by a
# turned instance. The same uv sphere in each (pole on +y, v = 0 there).
TURN_MESH = '<rotate x="1" angle="-40"/>\n            <rotate y="1" angle="-60"/>'
MESH_UV = [
    ("ply with uv", "ply", "sphere_uv.ply"),
    ("obj with uv", "obj", "sphere_uv.obj"),
    ("serialized with uv", "serialized", "spheres.serialized"),
]


def mesh_uv_shape(id_, kind, fname, x, bsdf):
    return turned_shape(kind, id_, x, bsdf, f'<scale value="0.3"/>\n            {TURN_MESH}',
                        f'\n        <string name="filename" value="textures/{fname}"/>')


def instanced_sphere(x, bsdf):
    return f"""    <shape type="shapegroup" id="group">
        <shape type="sphere">
            <transform name="to_world">
                <rotate z="1" angle="35"/>
            </transform>
{ind(bsdf, 12)}
        </shape>
    </shape>
    <shape type="instance">
        <ref id="group"/>
        <transform name="to_world">
            <scale value="0.3"/>
            <rotate x="1" angle="-70"/>
            <rotate y="1" angle="40"/>
            <translate x="{x}" y="{TSHAPE_Y}" z="0"/>
        </transform>
    </shape>
"""


for name, what, b in [("tex-meshes", "a nearest bitmap", BITMAP),
                      ("tex-meshes-aniso", "an anisotropic rough conductor", ANISO)]:
    text = header(f"PLY, OBJ and serialized spheres with uv, turned, and a sphere in a turned instance, "
                  f"with {what}.") + cornell()
    for i, (label, kind, fname) in enumerate(MESH_UV):
        text += mesh_uv_shape(f"m{i}", kind, fname, xs[i], b)
    text += instanced_sphere(xs[3], b)
    labels = [m[0] for m in MESH_UV] + ["sphere in a turned instance"]
    add(name, text, {label: tsphere_rect(xs[i]) for i, label in enumerate(labels)})

# Meshes without uv: Mitsuba's dp/du (an anisotropic BSDF's tangent) is
# then a triangle's first edge, p1 - p0, and dp/dv its second.
MESH_NO_UV = [
    ("ply without uv", "ply", "sphere_bare.ply", ""),
    ("obj without uv", "obj", "sphere_bare.obj", ""),
    ("serialized without uv", "serialized", "spheres.serialized",
     '\n        <integer name="shape_index" value="1"/>'),
]
text = header("PLY, OBJ and serialized spheres without uv, turned, with an anisotropic rough conductor.") + cornell()
for i, (label, kind, fname, extra) in enumerate(MESH_NO_UV):
    text += turned_shape(kind, f"m{i}", xs[i], ANISO, f'<scale value="0.3"/>\n            {TURN_MESH}',
                         f'\n        <string name="filename" value="textures/{fname}"/>{extra}')
add("tex-meshes-nouv-aniso", text, {m[0]: tsphere_rect(xs[i]) for i, m in enumerate(MESH_NO_UV)})

# Null surfaces and flip_normals on spheres, under volpath (Mitsuba's path
# integrator shows a null emitter black and stops shadow rays at null
# surfaces; volpath passes them both ways). max_depth 32 so that whether a
# crossing counts as a bounce does not matter.
NULL_FLIP = [
    ("null", """<bsdf type="null"/>"""),
    ("null, area emitter", """<bsdf type="null"/>
<emitter type="area">
    <rgb name="radiance" value="1.5, 2.5, 4"/>
</emitter>"""),
    ("flip_normals, area emitter (outside)", """<boolean name="flip_normals" value="true"/>
<bsdf type="diffuse">
    <rgb name="reflectance" value="0.6, 0.6, 0.6"/>
</bsdf>
<emitter type="area">
    <rgb name="radiance" value="6, 5, 4"/>
</emitter>"""),
    ("flip_normals, twosided", """<boolean name="flip_normals" value="true"/>
<bsdf type="twosided"><bsdf type="diffuse">
    <rgb name="reflectance" value="0.2, 0.5, 0.8"/>
</bsdf></bsdf>"""),
]
text = header("Null spheres (one emitting) and flip_normals spheres (one emitting, seen from outside).",
              max_depth=32, integrator="volpath") + cornell()
for i, (label, b) in enumerate(NULL_FLIP):
    text += sphere(i, ind(b), f"s{i}")
add("shapes-null-flip", text, {**slot_regions([l for l, _ in NULL_FLIP]), "back wall": [52, 14, 76, 38]})

# The camera inside a large emitting sphere with flip_normals (one-sided
# diffuse 0.5, radiance 0.5: a furnace of about 1), three grey balls in it.
text = header("Inside an emitting sphere with flip_normals: it lights and shows its inside.")
text += """    <shape type="sphere" id="room">
        <float name="radius" value="8"/>
        <boolean name="flip_normals" value="true"/>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0.5, 0.5, 0.5"/>
        </bsdf>
        <emitter type="area">
            <rgb name="radiance" value="0.5, 0.4, 0.3"/>
        </emitter>
    </shape>
"""
BALLS = ["0.8, 0.2, 0.2", "0.2, 0.8, 0.2", "0.2, 0.2, 0.8"]
for i, rgb in enumerate(BALLS):
    text += sphere(i, f'        <bsdf type="diffuse"><rgb name="reflectance" value="{rgb}"/></bsdf>', f"s{i}")
add("shapes-flip-inside", text, {**slot_regions(["red ball", "green ball", "blue ball"]),
                                 "room wall": [100, 10, 124, 30]})

# --- Sensors ----------------------------------------------------------------

SENSOR_BODY = cornell()
for i in range(4):
    SENSOR_BODY += sphere(i, '        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf></bsdf>', f"s{i}")
WHOLE = {"whole image": [0, 0, W, H]}
for axis, fov in [("y", 38.0), ("diagonal", 58.0), ("smaller", 38.0), ("larger", 48.0)]:
    add(f"sensor-fov-{axis}", header(f"fov_axis {axis}.", fov_axis=axis, fov=fov) + SENSOR_BODY, WHOLE)
add("sensor-thinlens", header(
    "A thin lens focused in front of the spheres.", sensor="thinlens",
    extra_sensor='\n        <float name="aperture_radius" value="0.08"/>\n        <float name="focus_distance" value="2.8"/>')
    + SENSOR_BODY, {**slot_regions(["sphere 1", "sphere 2", "sphere 3", "sphere 4"]), **WHOLE})
add("sensor-up", header("lookat with a tilted up vector (the image turns).",
                        lookat='origin="0.4, 0.3, 3.6" target="0, -0.2, 0" up="0.3, 1, 0"') + SENSOR_BODY, WHOLE)
# An orthographic sensor: to_world's uniform scale 1.4 makes the view 2.8
# wide (Mitsuba's film spans camera x in [-1, 1]); a slight tilt.
ortho = header("An orthographic sensor, 2.8 wide, looking slightly down.", sensor="orthographic",
               lookat='origin="0, 0.3, 3.6" target="0, -0.3, 0" up="0, 1, 0"')
ortho = ortho.replace('        <string name="fov_axis" value="x"/>\n        <float name="fov" value="48.0"/>\n', '')
ortho = ortho.replace('<transform name="to_world">\n            <lookat', '<transform name="to_world">\n            <scale value="1.4"/>\n            <lookat')
add("sensor-orthographic", ortho + SENSOR_BODY, WHOLE)
add("sensor-clip", header("near_clip 3.5 cuts the spheres' front caps away (twosided, so their inside shows).",
                          extra_sensor='\n        <float name="near_clip" value="3.5"/>\n        <float name="far_clip" value="100"/>')
    + SENSOR_BODY, WHOLE)


# Participating media (Mitsuba's volpath): homogeneous media inside spheres
# (behind null and dielectric boundaries, inline and by reference) and a fog
# the camera sits in.
SMOKE = """    <medium type="homogeneous" id="smoke">
        <float name="sigma_t" value="8"/>
        <float name="scale" value="0.5"/>
        <rgb name="albedo" value="0.95, 0.7, 0.4"/>
        <phase type="hg">
            <float name="g" value="0.6"/>
        </phase>
    </medium>
"""
MEDIA = [
    ("null ball of grey isotropic fog", """<bsdf type="null"/>
<medium type="homogeneous" name="interior">
    <float name="sigma_t" value="6"/>
    <rgb name="albedo" value="0.9, 0.9, 0.9"/>
    <phase type="isotropic"/>
</medium>"""),
    ("glass with an absorbing coloured inside", """<bsdf type="dielectric">
    <float name="int_ior" value="1.5"/>
</bsdf>
<medium type="homogeneous" name="interior">
    <rgb name="sigma_t" value="0.05, 0.3, 0.6"/>
    <float name="scale" value="10"/>
    <float name="albedo" value="0"/>
</medium>"""),
    ("null ball of coloured forward smoke", """<bsdf type="null"/>
<ref name="interior" id="smoke"/>"""),
    ("diffuse", """<bsdf type="diffuse">
    <rgb name="reflectance" value="0.6, 0.6, 0.6"/>
</bsdf>"""),
]
text = header("Homogeneous media inside spheres: null and dielectric boundaries, inline and referenced media, "
              "isotropic and Henyey-Greenstein phase, coloured sigma_t and albedo.", integrator="volpath") \
    + SMOKE + cornell()
for i, (label, b) in enumerate(MEDIA):
    text += sphere(i, ind(b), f"s{i}")
add("media-spheres", text, {**slot_regions([l for l, _ in MEDIA]), "back wall": [52, 14, 76, 38]})

FOG = """    <medium type="homogeneous" id="fog">
        <float name="sigma_t" value="0.25"/>
        <rgb name="albedo" value="0.8, 0.85, 0.9"/>
        <phase type="hg">
            <float name="g" value="0.3"/>
        </phase>
    </medium>
"""
text = header("A fog filling the box, the camera in it (the sensor's medium); a diffuse and a glass ball.",
              integrator="volpath", extra_sensor='\n        <ref id="fog"/>')
text = text.replace("    <sensor", FOG + "    <sensor", 1) + cornell()
text += sphere(0, ind(MEDIA[3][1]), "s0") + sphere(2, ind(MEDIA[1][1].split("<medium")[0]), "s2")
add("media-fog", text, {**slot_regions(["diffuse", None, "glass"]), "back wall": [52, 14, 76, 38]})


def main():
    write_textures()
    write_ply_sphere(HERE / "textures" / "sphere.ply")
    write_mesh_files(HERE / "textures")
    write_vertex_color_meshes(HERE / "textures")
    for name, text in SCENES.items():
        (HERE / f"{name}.xml").write_text(text)
    (HERE / "regions.json").write_text(json.dumps(REGIONS, indent=1) + "\n")
    print(f"wrote {len(SCENES)} scenes to {HERE}")


if __name__ == "__main__":
    main()
