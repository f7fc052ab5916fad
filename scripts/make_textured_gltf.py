#!/usr/bin/env python3
"""Writes scenes/gltf/textured.gltf: a brick sphere with a base-colour
texture, a tangent-space normal map and alpha cut-outs (MASK), beside a
rough gold sphere on a grey floor under an emissive lamp, seen by two
cameras ("front", the default, and "side", `--camera 1`).

Everything is generated here, so the project owns it: textured.bin
(positions, normals, UVs, indices), albedo.png (RGBA: brick colours, alpha 0
over the faces of one brick in four) and normal.png (bevelled brick edges:
+X right, +Y up, the glTF convention). Sphere UVs follow glTF: u = phi/2pi
around +Y, v = theta/pi from the top (v = 0 is the image's top row).

Run from anywhere: `python3 scripts/make_textured_gltf.py`. Standard
library only; the output is byte-identical on every run.
"""
import json
import math
import os
import struct
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "scenes", "gltf")

TEX_W, TEX_H = 128, 64
BRICK_W, BRICK_H = 16, 8  # texels
MORTAR = 1.5  # texels of groove each side


def png(path, width, height, channels, pixel):
    """Writes an 8-bit PNG (RGB or RGBA) of pixel(x, y) -> tuple of ints."""
    color_type = {3: 2, 4: 6}[channels]
    rows = b"".join(
        b"\x00" + bytes(v for x in range(width) for v in pixel(x, y)) for y in range(height)
    )

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", header))
        f.write(chunk(b"IDAT", zlib.compress(rows, 9)))
        f.write(chunk(b"IEND", b""))


def brick_of(x, y):
    """(column, row, distance to the nearest brick edge) at texel centre (x, y)."""
    row = int(y // BRICK_H)
    shift = (BRICK_W / 2) * (row % 2)
    col = int(((x - shift) % TEX_W) // BRICK_W)
    local_x = (x - shift) % BRICK_W
    local_y = y % BRICK_H
    edge = min(local_x, BRICK_W - local_x, local_y, BRICK_H - local_y)
    return col, row, edge


def height(x, y):
    """1 on a brick's face, falling to 0 in the mortar over a short bevel."""
    _, _, edge = brick_of(x, y)
    return max(0.0, min(1.0, (edge - 0.5) / MORTAR))


def holed(col, row):
    return (col * 3 + row * 5) % 4 == 0


def albedo(x, y):
    cx, cy = x + 0.5, y + 0.5
    col, row, edge = brick_of(cx, cy)
    if edge < 0.5 + MORTAR * 0.5:
        rgb = (200, 196, 186)
    else:
        k = (col * 7 + row * 13) % 5
        rgb = (150 + 12 * k, 62 + 6 * k, 40 + 3 * k)
    # Bricks of the holed pattern are missing: their faces are cut out,
    # the mortar around them stays.
    alpha = 0 if holed(col, row) and edge >= 0.5 + MORTAR * 0.5 else 255
    return (*rgb, alpha)


def normal(x, y):
    cx, cy = x + 0.5, y + 0.5
    dx = (height(cx + 0.5, cy) - height(cx - 0.5, cy)) * 1.2
    drow = (height(cx, cy + 0.5) - height(cx, cy - 0.5)) * 1.2
    # Tangent space: x right (+column), y up (-row).
    n = (-dx, drow, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(int(round((c / length * 0.5 + 0.5) * 255)) for c in n)


def sphere(center, radius, slices=48, stacks=24):
    pos, nrm, uv, idx = [], [], [], []
    for j in range(stacks + 1):
        theta = math.pi * j / stacks
        for i in range(slices + 1):
            phi = 2 * math.pi * i / slices
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            pos.append(tuple(c + radius * d for c, d in zip(center, n)))
            nrm.append(n)
            uv.append((i / slices, j / stacks))
    for j in range(stacks):
        for i in range(slices):
            a = j * (slices + 1) + i
            b = a + slices + 1
            # Counter-clockwise seen from outside.
            idx += [a, a + 1, b, a + 1, b + 1, b]
    return pos, nrm, uv, idx


def quad(corners, n):
    return list(corners), [n] * 4, [(0, 0), (1, 0), (1, 1), (0, 1)], [0, 1, 2, 0, 2, 3]


def look_at(eye, target):
    """A glTF node rotation (x, y, z, w) pointing local -Z from eye to target."""
    f = [t - e for t, e in zip(target, eye)]
    fl = math.sqrt(sum(c * c for c in f))
    f = [c / fl for c in f]
    up = (0.0, 1.0, 0.0)
    r = (f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0])
    rl = math.sqrt(sum(c * c for c in r))
    r = [c / rl for c in r]
    u = (r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0])
    z = [-c for c in f]
    m = [[r[0], u[0], z[0]], [r[1], u[1], z[1]], [r[2], u[2], z[2]]]
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    return [
        round((m[2][1] - m[1][2]) / (4 * w), 6),
        round((m[0][2] - m[2][0]) / (4 * w), 6),
        round((m[1][0] - m[0][1]) / (4 * w), 6),
        round(w, 6),
    ]


def main():
    os.makedirs(OUT, exist_ok=True)
    png(os.path.join(OUT, "albedo.png"), TEX_W, TEX_H, 4, albedo)
    png(os.path.join(OUT, "normal.png"), TEX_W, TEX_H, 3, normal)

    meshes = [
        ("bricks", 0, sphere((0.0, 0.55, 0.0), 0.55)),
        ("gold", 1, sphere((0.85, 0.25, 0.35), 0.25, 32, 16)),
        ("floor", 2, quad([(-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)], (0, 1, 0))),
        ("lamp", 3, quad([(-0.6, 2.4, -0.6), (0.6, 2.4, -0.6), (0.6, 2.4, 0.6), (-0.6, 2.4, 0.6)], (0, -1, 0))),
    ]
    blob = bytearray()
    views, accessors, gl_meshes = [], [], []

    def add(data, fmt, count, kind, comp, target, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        for item in data:
            blob.extend(struct.pack("<" + fmt, *(item if isinstance(item, tuple) else (item,))))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": kind}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    for name, material, (pos, nrm, uv, idx) in meshes:
        pos = [tuple(round(c, 6) for c in p) for p in pos]
        nrm = [tuple(round(c, 6) for c in n) for n in nrm]
        lo = [min(p[k] for p in pos) for k in range(3)]
        hi = [max(p[k] for p in pos) for k in range(3)]
        p_acc = add(pos, "3f", len(pos), "VEC3", 5126, 34962, (lo, hi))
        n_acc = add(nrm, "3f", len(nrm), "VEC3", 5126, 34962)
        t_acc = add(uv, "2f", len(uv), "VEC2", 5126, 34962)
        i_acc = add(idx, "I", len(idx), "SCALAR", 5125, 34963)
        gl_meshes.append({
            "name": name,
            "primitives": [{
                "attributes": {"POSITION": p_acc, "NORMAL": n_acc, "TEXCOORD_0": t_acc},
                "indices": i_acc,
                "material": material,
            }],
        })
    with open(os.path.join(OUT, "textured.bin"), "wb") as f:
        f.write(blob)

    cameras = [("front", (0.0, 1.1, 2.7), (0.2, 0.45, 0.0)), ("side", (2.4, 1.5, 1.4), (0.2, 0.4, 0.0))]
    nodes = [{"name": name, "mesh": i} for i, (name, _, _) in enumerate(meshes)]
    for k, (name, eye, target) in enumerate(cameras):
        nodes.append({"name": name, "camera": k, "translation": list(eye), "rotation": look_at(eye, target)})
    gltf = {
        "asset": {"version": "2.0", "generator": "candela scripts/make_textured_gltf.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [
            {"type": "perspective", "perspective": {"yfov": math.radians(38), "znear": 0.05}}
            for _ in cameras
        ],
        "meshes": gl_meshes,
        "materials": [
            {
                "name": "bricks",
                "pbrMetallicRoughness": {
                    "baseColorTexture": {"index": 0},
                    "metallicFactor": 0.0,
                    "roughnessFactor": 0.55,
                },
                "normalTexture": {"index": 1, "scale": 1.0},
                "alphaMode": "MASK",
                "alphaCutoff": 0.5,
                "doubleSided": True,
            },
            {
                "name": "gold",
                "pbrMetallicRoughness": {
                    "baseColorFactor": [1.0, 0.78, 0.34, 1.0],
                    "metallicFactor": 1.0,
                    "roughnessFactor": 0.35,
                },
            },
            {
                "name": "floor",
                "pbrMetallicRoughness": {
                    "baseColorFactor": [0.55, 0.57, 0.6, 1.0],
                    "metallicFactor": 0.0,
                    "roughnessFactor": 0.8,
                },
            },
            {
                "name": "lamp",
                "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                "emissiveFactor": [1.0, 0.95, 0.85],
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 12.0}},
            },
        ],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "samplers": [{"wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": "albedo.png"}, {"uri": "normal.png"}],
        "buffers": [{"uri": "textured.bin", "byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(os.path.join(OUT, "textured.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
