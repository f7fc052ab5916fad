#!/usr/bin/env python3
"""Writes one ~1M-triangle mesh as a binary PLY and as a glTF binary (.glb)
for `candela bench load` (see BENCHMARKS.md, "Scene loading (formats)").

The mesh is a rippled N x N grid of vertices (positions and unit normals,
float32; 2 (N-1)^2 triangles, 32-bit indices): the same vertices and
triangles in both files, so the two loaders read the same data.
Usage: `python3 examples/make_big_mesh.py OUT_STEM [N]` writes
OUT_STEM.ply and OUT_STEM.glb (N = 708 gives 999,698 triangles).
Standard library only.
"""
import array
import json
import math
import struct
import sys


def grid(n):
    """Positions, normals (flat float arrays) and triangle indices."""
    pos, nor, idx = array.array("f"), array.array("f"), array.array("I")
    for j in range(n):
        z = j / (n - 1)
        for i in range(n):
            x = i / (n - 1)
            # y = a sin(kx) cos(kz); normal = (-dy/dx, 1, -dy/dz), normalised.
            a, k = 0.02, 12.0
            y = a * math.sin(k * x) * math.cos(k * z)
            dx, dz = a * k * math.cos(k * x) * math.cos(k * z), -a * k * math.sin(k * x) * math.sin(k * z)
            inv = 1.0 / math.sqrt(dx * dx + 1.0 + dz * dz)
            pos.extend((x, y, z))
            nor.extend((-dx * inv, inv, -dz * inv))
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            idx.extend((a, a + n, a + 1, a + 1, a + n, a + n + 1))
    return pos, nor, idx


def little(a):
    if sys.byteorder == "big":
        a = array.array(a.typecode, a)
        a.byteswap()
    return a.tobytes()


def write_ply(path, pos, nor, idx):
    nv, nt = len(pos) // 3, len(idx) // 3
    header = "\n".join([
        "ply", "format binary_little_endian 1.0", "comment written by examples/make_big_mesh.py",
        f"element vertex {nv}",
        "property float x", "property float y", "property float z",
        "property float nx", "property float ny", "property float nz",
        f"element face {nt}", "property list uchar int vertex_indices", "end_header", ""])
    vert = array.array("f", bytes(4 * 6 * nv))
    for k in range(3):
        vert[k::6] = pos[k::3]
        vert[3 + k::6] = nor[k::3]
    face = struct.Struct("<B3i")
    with open(path, "wb") as fh:
        fh.write(header.encode("ascii"))
        fh.write(little(vert))
        buf = bytearray(face.size * nt)
        for t in range(nt):
            face.pack_into(buf, t * face.size, 3, idx[3 * t], idx[3 * t + 1], idx[3 * t + 2])
        fh.write(buf)


def write_glb(path, pos, nor, idx):
    nv = len(pos) // 3
    parts = [little(pos), little(nor), little(idx)]
    views, offset = [], 0
    for p, target in zip(parts, [34962, 34962, 34963]):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(p), "target": target})
        offset += len(p)
    blob = b"".join(parts)
    lo = [min(pos[k::3]) for k in range(3)]
    hi = [max(pos[k::3]) for k in range(3)]
    doc = {
        "asset": {"version": "2.0", "generator": "examples/make_big_mesh.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": len(blob)}], "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}],
    }
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    blob += b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(js) + 8 + len(blob)
    with open(path, "wb") as fh:
        fh.write(b"glTF" + struct.pack("<II", 2, total))
        fh.write(struct.pack("<I", len(js)) + b"JSON" + js)
        fh.write(struct.pack("<I", len(blob)) + b"BIN\0" + blob)


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: make_big_mesh.py OUT_STEM [N]")
    n = int(sys.argv[2]) if len(sys.argv) == 3 else 708
    if n < 2:
        sys.exit("N must be at least 2")
    pos, nor, idx = grid(n)
    write_ply(sys.argv[1] + ".ply", pos, nor, idx)
    write_glb(sys.argv[1] + ".glb", pos, nor, idx)
    print(f"{len(idx) // 3} triangles, {len(pos) // 3} vertices: {sys.argv[1]}.ply, {sys.argv[1]}.glb")


if __name__ == "__main__":
    main()
