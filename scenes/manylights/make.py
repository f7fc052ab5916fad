#!/usr/bin/env python3
"""Writes the many-lights benchmark scenes (BENCHMARKS.md, "Many lights:
the light BVH"): a long hall lit by 10,240 small emissive triangles
(manylights.xml), and a city block at night lit by about 11,000 string
lights over its streets (city.xml, see `city()`).

The hall:

- the ceiling: a 64 x 64 grid of small lamps facing down (8,192 triangles),
  in three colours and a spread of brightness;
- both long walls: a 32 x 16 grid of tiny lamps each, high up, facing into
  the hall (2,048 triangles);
- a few boxes on the floor (occluders), a grey floor, walls and ceiling.

From any point only the lamps nearby and facing it matter, so choosing a
lamp by distance and orientation (the light tree) beats choosing by power
or uniformly. The camera looks down at the floor, the boxes and the lower
walls and sees no lamp directly: the image is all lighting, none of it
the pixel-coverage noise of tiny bright lamps, which no light selection
changes. Output beside this script: manylights.xml (Mitsuba 3, with
the camera) and the lamp meshes as binary PLY (quads; the loader fans
them). Standard library only; deterministic.

Usage: python3 scenes/manylights/make.py
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
W, H, D = 8.0, 3.0, 16.0  # hall: x in [-W/2, W/2], y in [0, H], z in [-D, 0]


def emissive_ply(name, rgb):
    """A black, area-emitting shape read from NAME.ply beside the scene."""
    return (f'    <shape type="ply" id="{name}">\n'
            f'      <string name="filename" value="{name}.ply"/>\n'
            f'      <ref id="black"/>\n'
            f'      <emitter type="area"><rgb name="radiance" value="{rgb}"/></emitter>\n'
            f'    </shape>\n')


def write_scene(filename, xml, body, emissive_triangles):
    """Closes the scene document and writes it beside this script."""
    xml.append(body.rstrip("\n"))
    xml.append("</scene>\n")
    with open(os.path.join(HERE, filename), "w") as fh:
        fh.write("\n".join(xml))
    print(f"{filename}: {emissive_triangles} emissive triangles")


def write_ply(path, quads):
    """Binary little-endian PLY of quads or triangles (each 4 or 3 corners,
    counter-clockwise seen from the emitting side)."""
    n = len(quads[0])
    header = "\n".join([
        "ply",
        "format binary_little_endian 1.0",
        "comment written by scenes/manylights/make.py",
        f"element vertex {n * len(quads)}",
        "property float x",
        "property float y",
        "property float z",
        f"element face {len(quads)}",
        "property list uchar int vertex_indices",
        "end_header",
    ]) + "\n"
    with open(path, "wb") as fh:
        fh.write(header.encode())
        for q in quads:
            for p in q:
                fh.write(struct.pack("<3f", *p))
        for k in range(len(quads)):
            fh.write(struct.pack(f"<B{n}i", n, *range(n * k, n * k + n)))


def ceiling_lamps():
    """64 x 64 lamps just below the ceiling, facing down, in 3 groups."""
    groups = [[], [], []]
    n, size = 64, 0.04
    for j in range(n):
        for i in range(n):
            x = -W / 2 + (i + 0.5) * W / n
            z = -D + (j + 0.5) * D / n
            y = H - 0.01
            s = size * (1.0 + 0.5 * ((i * 7 + j * 13) % 5) / 4.0)
            # Seen from below (normal -y): counter-clockwise in x-z.
            quad = [(x - s, y, z - s), (x + s, y, z - s), (x + s, y, z + s), (x - s, y, z + s)]
            groups[(i + 2 * j) % 3].append(quad)
    return groups


def wall_lamps(side):
    """32 x 16 tiny lamps on the wall at x = side * W/2, facing inward."""
    quads = []
    nz, ny, s = 32, 16, 0.015
    x = side * (W / 2 - 0.01)
    for j in range(ny):
        for i in range(nz):
            z = -D + (i + 0.5) * D / nz
            y = 2.2 + (j + 0.5) * (H - 2.3) / ny
            a, b = (x, y - s, z - s), (x, y + s, z - s)
            c, d = (x, y + s, z + s), (x, y - s, z + s)
            # Normal -side * x: order so that (b - a) x (d - a) points inward.
            quads.append([a, d, c, b] if side > 0 else [a, b, c, d])
    return quads


def box(cx, cz, sx, sy, sz):
    return (f'    <shape type="cube">\n'
            f'      <transform name="to_world"><scale value="{sx} {sy} {sz}"/>'
            f'<translate value="{cx} {sy} {cz}"/></transform>\n'
            f'      <ref id="grey"/>\n    </shape>\n')


def rect(name, transform, material):
    return (f'    <shape type="rectangle" id="{name}">\n'
            f'      <transform name="to_world">{transform}</transform>\n'
            f'      <ref id="{material}"/>\n    </shape>\n')


def hall():
    lamps = {}
    for k, quads in enumerate(ceiling_lamps()):
        lamps[f"ceiling{k}"] = quads
    lamps["wall_left"] = wall_lamps(-1)
    lamps["wall_right"] = wall_lamps(+1)
    for name, quads in lamps.items():
        write_ply(os.path.join(HERE, f"{name}.ply"), quads)
    radiance = {
        "ceiling0": "1.6, 1.3, 1.0",
        "ceiling1": "1.0, 1.3, 1.6",
        "ceiling2": "1.3, 1.3, 1.3",
        "wall_left": "40, 12, 6",
        "wall_right": "6, 18, 40",
    }
    triangles = 2 * sum(len(q) for q in lamps.values())
    xml = [
        '<?xml version="1.0" encoding="utf-8"?>',
        f"<!-- The many-lights hall: {triangles} emissive triangles. Written by make.py. -->",
        '<scene version="3.0.0">',
        '  <sensor type="perspective">',
        '    <float name="fov" value="60"/>',
        '    <transform name="to_world"><lookat origin="0.3 1.7 -0.5" target="-0.2 0 -4.1" up="0, 1, 0"/></transform>',
        '    <film type="hdrfilm"><integer name="width" value="640"/><integer name="height" value="360"/></film>',
        '  </sensor>',
        '  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf>',
        '  <bsdf type="diffuse" id="dark"><rgb name="reflectance" value="0.2, 0.2, 0.2"/></bsdf>',
        '  <bsdf type="diffuse" id="black"><rgb name="reflectance" value="0"/></bsdf>',
    ]
    body = ""
    # Rectangles are [-1, 1]^2 in z = 0 facing +z before their transform.
    body += rect("floor", f'<scale value="{W / 2} {D / 2} 1"/><rotate x="1" angle="-90"/>'
                 f'<translate value="0 0 {-D / 2}"/>', "grey")
    body += rect("ceiling", f'<scale value="{W / 2} {D / 2} 1"/><rotate x="1" angle="90"/>'
                 f'<translate value="0 {H} {-D / 2}"/>', "dark")
    body += rect("back", f'<scale value="{W / 2} {H / 2} 1"/>'
                 f'<translate value="0 {H / 2} {-D}"/>', "grey")
    body += rect("left", f'<scale value="{D / 2} {H / 2} 1"/><rotate y="1" angle="90"/>'
                 f'<translate value="{-W / 2} {H / 2} {-D / 2}"/>', "grey")
    body += rect("right", f'<scale value="{D / 2} {H / 2} 1"/><rotate y="1" angle="-90"/>'
                 f'<translate value="{W / 2} {H / 2} {-D / 2}"/>', "grey")
    for cx, cz, sx, sy, sz in [(-1.5, -4, 0.4, 0.6, 0.4), (1.8, -7, 0.6, 0.9, 0.3),
                               (-2.0, -10, 0.5, 0.4, 0.8), (0.8, -12.5, 0.3, 1.2, 0.3)]:
        body += box(cx, cz, sx, sy, sz)
    for name, rgb in radiance.items():
        body += emissive_ply(name, rgb)
    write_scene("manylights.xml", xml, body, triangles)


CITY = 64.0     # the city: x and z in [-CITY/2, CITY/2]
PITCH = 8.0     # one block per PITCH x PITCH cell: a building and its streets
FOOTPRINT = 5.0  # building side; streets are PITCH - FOOTPRINT = 3 m wide
LAMP_PITCH = 0.45  # jittered grid of string lights over the streets


def city_buildings():
    """(centre x, centre z, half side, height): one per block, 3 to 15 m
    tall, a deterministic spread."""
    n = int(CITY / PITCH)
    out = []
    for j in range(n):
        for i in range(n):
            cx = -CITY / 2 + (i + 0.5) * PITCH
            cz = -CITY / 2 + (j + 0.5) * PITCH
            height = 3.0 + ((i * 37 + j * 91 + i * j * 11) % 13)
            out.append((cx, cz, FOOTPRINT / 2, height))
    return out


def city_lamps():
    """Small triangles facing down, 2 to 3 m above the streets on a jittered
    grid (none over a roof), in three colour groups; each lamp's size, and
    so its power, spreads over a factor of 4."""
    groups = [[], [], []]
    n = int(CITY / LAMP_PITCH)
    state = 12345

    def rand():  # a small LCG: deterministic without the random module
        nonlocal state
        state = (state * 1103515245 + 12345) % (1 << 31)
        return state / (1 << 31)

    for j in range(n):
        for i in range(n):
            x = -CITY / 2 + (i + rand()) * LAMP_PITCH
            z = -CITY / 2 + (j + rand()) * LAMP_PITCH
            y = 2.0 + rand()
            s = 0.03 * (1.0 + 3.0 * rand()) ** 0.5
            cell = lambda v: (v + CITY / 2) % PITCH - PITCH / 2
            if abs(cell(x)) < FOOTPRINT / 2 + 0.2 and abs(cell(z)) < FOOTPRINT / 2 + 0.2:
                continue
            # Seen from below (normal -y): counter-clockwise in x-z.
            tri = [(x - s, y, z - s), (x + s, y, z - s), (x, y, z + s)]
            groups[int(3 * rand()) % 3].append(tri)
    return groups


def city():
    """The city block at night: a 64 x 64 m ground, an 8 x 8 grid of
    buildings 3 to 15 m tall with 3 m streets between them, and about
    11,000 string lights (small triangles facing down, 2-3 m up) over the
    streets. Each point of a street is lit by the lamps within a few metres
    (a lamp h above the ground facing down gives irradiance in proportion
    to h^2 / d^4 at distance d), and the buildings hide the other
    streets, so almost all of the 11,000 lamps are dark at any given
    point: the case a light tree is for, unlike the hall, where every lamp
    of the ceiling reaches most of the floor. The camera looks along a
    street from 6 m up at its end; it sees the lamps' dark backs only."""
    groups = city_lamps()
    colours = ["60, 40, 20", "30, 40, 60", "50, 50, 50"]
    for k, tris in enumerate(groups):
        write_ply(os.path.join(HERE, f"city_lamps{k}.ply"), tris)
    count = sum(len(g) for g in groups)
    xml = [
        '<?xml version="1.0" encoding="utf-8"?>',
        f"<!-- A city block at night: {count} emissive triangles. Written by make.py. -->",
        '<scene version="3.0.0">',
        '  <sensor type="perspective">',
        '    <float name="fov" value="50"/>',
        '    <transform name="to_world"><lookat origin="1.2 6 34" target="-0.5 0 4" up="0, 1, 0"/></transform>',
        '    <film type="hdrfilm"><integer name="width" value="640"/><integer name="height" value="360"/></film>',
        '  </sensor>',
        '  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf>',
        '  <bsdf type="diffuse" id="black"><rgb name="reflectance" value="0"/></bsdf>',
    ]
    body = rect("ground", f'<scale value="{CITY / 2} {CITY / 2} 1"/><rotate x="1" angle="-90"/>',
                "grey")
    for cx, cz, half, height in city_buildings():
        body += box(cx, cz, half, height / 2, half)
    for k, rgb in enumerate(colours):
        body += emissive_ply(f"city_lamps{k}", rgb)
    write_scene("city.xml", xml, body, count)


def main():
    hall()
    city()


if __name__ == "__main__":
    main()
