#!/usr/bin/env python3
"""Writes Candela's material test ball: a Mitsuba 3 scene (ball.xml) and its
meshes (floor_light.ply, floor_dark.ply, pedestal.ply), all made here from
numbers, no third-party meshes.

The stage (Y up, metres): a 6 x 6 checkered floor at y = 0 (0.5 squares,
two PLY meshes so that each colour is a plain diffuse material), a
cylindrical pedestal of radius 0.5 and height 0.25, the test ball (an
analytic sphere of radius 1 resting on it, centre (0, 1.25, 0)) and an inner
diffuse ball of radius 0.55 at its centre, seen through the transparent
materials. Light: a dim constant environment and a 2 x 2 area light up and
to the left of the camera, which puts a highlight on the ball.

The ball's BSDF is `<ref id="$material"/>`: choose it with
`candela -D material=<id>` (Mitsuba: `mi.load_file(..., material=<id>)`).
Ids: roughglass, glass, roughplastic, plastic, and the measured metals
Au, Ag, Al, Cu, Cr, Fe, Ni, Ti, W (rough GGX, alpha = $alpha, default 0.1;
Fe, Ti and Ni are Candela-only names, Mitsuba 3 has Ni as "Ni_palik" and
neither Fe nor Ti), plus smooth_Au, a smooth conductor.

Run from anywhere: `python3 scenes/materials/make.py`. Standard library only.
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

FLOOR_HALF, SQUARE = 3.0, 0.5
PEDESTAL_RADIUS, PEDESTAL_HEIGHT, SEGMENTS = 0.5, 0.25, 64
BALL_RADIUS, INNER_RADIUS = 1.0, 0.55
METALS = ["Au", "Ag", "Al", "Cu", "Cr", "Fe", "Ni", "Ti", "W"]


def write_ply(name, verts, normals, tris):
    """Binary little-endian PLY with per-vertex normals."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"comment Candela material test ball, written by scenes/materials/make.py\n"
        f"element vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(os.path.join(HERE, name), "wb") as fh:
        fh.write(header.encode("ascii"))
        for p, n in zip(verts, normals):
            fh.write(struct.pack("<6f", *p, *n))
        for t in tris:
            fh.write(struct.pack("<B3i", 3, *t))


def floor(parity):
    """The squares (i + j) % 2 == parity of the checkered floor, facing +y."""
    verts, tris = [], []
    n = int(2 * FLOOR_HALF / SQUARE)
    for i in range(n):
        for j in range(n):
            if (i + j) % 2 != parity:
                continue
            x0, z0 = -FLOOR_HALF + i * SQUARE, -FLOOR_HALF + j * SQUARE
            base = len(verts)
            verts += [(x0, 0, z0), (x0, 0, z0 + SQUARE), (x0 + SQUARE, 0, z0 + SQUARE), (x0 + SQUARE, 0, z0)]
            tris += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return verts, [(0.0, 1.0, 0.0)] * len(verts), tris


def pedestal():
    """A closed cylinder on the floor: side (smooth normals) and top cap."""
    verts, normals, tris = [], [], []
    for k in range(SEGMENTS):
        a = 2 * math.pi * k / SEGMENTS
        c, s = math.cos(a), math.sin(a)
        verts += [(PEDESTAL_RADIUS * c, 0, PEDESTAL_RADIUS * s), (PEDESTAL_RADIUS * c, PEDESTAL_HEIGHT, PEDESTAL_RADIUS * s)]
        normals += [(c, 0, s), (c, 0, s)]
    for k in range(SEGMENTS):
        b0, b1 = 2 * k, 2 * ((k + 1) % SEGMENTS)
        # Counter-clockwise seen from outside.
        tris += [(b0, b0 + 1, b1 + 1), (b0, b1 + 1, b1)]
    centre = len(verts)
    verts.append((0, PEDESTAL_HEIGHT, 0))
    normals.append((0, 1, 0))
    rim = len(verts)
    for k in range(SEGMENTS):
        a = 2 * math.pi * k / SEGMENTS
        verts.append((PEDESTAL_RADIUS * math.cos(a), PEDESTAL_HEIGHT, PEDESTAL_RADIUS * math.sin(a)))
        normals.append((0, 1, 0))
    for k in range(SEGMENTS):
        tris.append((centre, rim + (k + 1) % SEGMENTS, rim + k))
    return verts, normals, tris


def bsdfs():
    """Every material the ball can wear, by id."""
    out = [
        """    <bsdf type="roughdielectric" id="roughglass">
        <string name="distribution" value="ggx"/>
        <float name="alpha" value="0.15"/>
        <string name="int_ior" value="bk7"/>
    </bsdf>""",
        """    <bsdf type="dielectric" id="glass">
        <string name="int_ior" value="bk7"/>
    </bsdf>""",
        """    <bsdf type="roughplastic" id="roughplastic">
        <string name="distribution" value="ggx"/>
        <float name="alpha" value="0.15"/>
        <rgb name="diffuse_reflectance" value="0.08, 0.22, 0.6"/>
    </bsdf>""",
        """    <bsdf type="plastic" id="plastic">
        <rgb name="diffuse_reflectance" value="0.08, 0.22, 0.6"/>
    </bsdf>""",
        """    <bsdf type="conductor" id="smooth_Au">
        <string name="material" value="Au"/>
    </bsdf>""",
    ]
    for metal in METALS:
        out.append(f"""    <bsdf type="roughconductor" id="{metal}">
        <string name="distribution" value="ggx"/>
        <float name="alpha" value="$alpha"/>
        <string name="material" value="{metal}"/>
    </bsdf>""")
    return "\n".join(out)


def scene():
    ball_y = PEDESTAL_HEIGHT + BALL_RADIUS
    return f"""<?xml version="1.0" encoding="utf-8"?>
<!-- Candela's material test ball. GENERATED by scenes/materials/make.py:
     edit that, not this. The ball wears <ref id="$material"/>; see make.py
     for the ids. -->
<scene version="3.0.0">
    <default name="material" value="roughplastic"/>
    <default name="alpha" value="0.1"/>
    <default name="spp" value="64"/>
    <default name="max_depth" value="10"/>
    <default name="width" value="200"/>
    <default name="height" value="150"/>

    <integrator type="path">
        <integer name="max_depth" value="$max_depth"/>
    </integrator>

    <sensor type="perspective">
        <string name="fov_axis" value="x"/>
        <float name="fov" value="40"/>
        <transform name="to_world">
            <lookat origin="0, 2.6, 6.4" target="0, 1.0, 0" up="0, 1, 0"/>
        </transform>
        <sampler type="independent">
            <integer name="sample_count" value="$spp"/>
        </sampler>
        <film type="hdrfilm">
            <integer name="width" value="$width"/>
            <integer name="height" value="$height"/>
            <rfilter type="box"/>
        </film>
    </sensor>

    <emitter type="constant">
        <rgb name="radiance" value="0.25, 0.27, 0.3"/>
    </emitter>
    <shape type="rectangle" id="light">
        <transform name="to_world">
            <lookat origin="-2.5, 4.5, 2.5" target="0, 1, 0" up="0, 1, 0"/>
        </transform>
        <bsdf type="diffuse">
            <rgb name="reflectance" value="0, 0, 0"/>
        </bsdf>
        <emitter type="area">
            <rgb name="radiance" value="12, 11.4, 10.4"/>
        </emitter>
    </shape>

{bsdfs()}
    <bsdf type="diffuse" id="floor_light">
        <rgb name="reflectance" value="0.7, 0.7, 0.7"/>
    </bsdf>
    <bsdf type="diffuse" id="floor_dark">
        <rgb name="reflectance" value="0.15, 0.15, 0.15"/>
    </bsdf>
    <bsdf type="diffuse" id="pedestal">
        <rgb name="reflectance" value="0.35, 0.33, 0.3"/>
    </bsdf>
    <bsdf type="diffuse" id="inner">
        <rgb name="reflectance" value="0.8, 0.35, 0.05"/>
    </bsdf>

    <shape type="ply">
        <string name="filename" value="floor_light.ply"/>
        <ref id="floor_light"/>
    </shape>
    <shape type="ply">
        <string name="filename" value="floor_dark.ply"/>
        <ref id="floor_dark"/>
    </shape>
    <shape type="ply">
        <string name="filename" value="pedestal.ply"/>
        <ref id="pedestal"/>
    </shape>
    <shape type="sphere" id="inner_ball">
        <point name="center" x="0" y="{ball_y}" z="0"/>
        <float name="radius" value="{INNER_RADIUS}"/>
        <ref id="inner"/>
    </shape>
    <shape type="sphere" id="ball">
        <point name="center" x="0" y="{ball_y}" z="0"/>
        <float name="radius" value="{BALL_RADIUS}"/>
        <ref id="$material"/>
    </shape>
</scene>
"""


def main():
    write_ply("floor_light.ply", *floor(0))
    write_ply("floor_dark.ply", *floor(1))
    write_ply("pedestal.ply", *pedestal())
    with open(os.path.join(HERE, "ball.xml"), "w") as fh:
        fh.write(scene())


if __name__ == "__main__":
    main()
