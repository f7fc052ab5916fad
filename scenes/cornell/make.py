#!/usr/bin/env python3
"""Writes Candela's Cornell box (the built-in demo, scenes/demo.dae) as
Wavefront OBJ + MTL and as PLY files, from the same numbers.

demo.dae is Z-up; OBJ and PLY are written Y-up (x' = -x, y' = z, z' = y,
the same rotation the COLLADA loader applies), so every format loads to the
same world. The spheres, analytic in the .dae, become UV spheres here.
A PLY file carries no materials: one file per material group. Neither
format has a camera: the .dae's (eye (0, 0.75, 3.2) in Y-up, 49.13 degree
horizontal field of view, looking down -z) must be given by the scene that
uses these meshes. Run from anywhere: `python3 scenes/cornell/make.py`.
Standard library only.
"""
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
# name -> MTL body (see the README's OBJ/MTL mapping table).
MATERIALS = {
    "white": "Kd 0.725 0.71 0.68",
    "red": "Kd 0.63 0.065 0.05",
    "green": "Kd 0.14 0.45 0.091",
    # A pure emitter, like the .dae's CGL emission (black BSDF).
    "lamp": "Kd 0 0 0\nKe 10 10 10",
    "matte": "Kd 0.8 0.8 0.8",
    "mirror": "illum 3\nKs 0.95 0.95 0.95",
}
SEGMENTS, RINGS = 32, 16


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


def groups():
    """(name, material, positions, normals, faces) in Y-up, normals per vertex."""
    out = []
    for name, mat, quad, n in WALLS:
        out.append((name, mat, [y_up(p) for p in quad], [y_up(n)] * 4, [(0, 1, 2, 3)]))
    for name, mat, center, radius in SPHERES:
        v, n, f = sphere(y_up(center), radius)
        out.append((name, mat, v, n, f))
    return out


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
        for name, body in MATERIALS.items():
            fh.write(f"newmtl {name}\n{body}\n\n")


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


if __name__ == "__main__":
    write_obj()
    write_plys()
