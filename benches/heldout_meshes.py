#!/usr/bin/env python3
"""Writes held-out ray-replay sets: meshes of 1-2M triangles unlike the two
shared ones (../shared/bench), so that BVH changes are judged on geometry
they were not tuned to. Same `.tri` / `.rays` formats as the shared sets
(../shared/bench/README.md); numpy only; deterministic (fixed seeds).

    python3 benches/heldout_meshes.py /tmp/heldout      # needs numpy (e.g. /tmp/embree-venv/bin/python)

writes, for each MESH of the list below, MESH.tri, MESH.primary.rays
(480x360 camera rays in the 4x4-tile order of the shared sets) and
MESH.diffuse.rays (1,048,576 cosine-distributed rays leaving random
triangles, chosen by index like the shared sets, offset along the normal):

* `sphere`: a displaced sphere, 1.2M small, even triangles (the issue's
  Embree figure of 1.7 Mrays/s diffuse was measured on such a sphere).
* `terrain`: a heightfield of 1.1M triangles inside a Cornell-style room
  whose floor is one huge ground quad and whose walls and ceiling are two
  triangles each: rays blocked by a wall or the ground should end near the
  root (the any-hit case the issue reported at 0.24x Embree).
* `grass`: 1.5M long thin triangles (blades) in 3,000 randomly rotated
  and placed clumps (an instancing-like soup), standing on a ground quad:
  boxes of thin diagonal triangles overlap badly.
"""

import struct
import sys
from pathlib import Path

import numpy as np

WIDTH, HEIGHT = 480, 360
DIFFUSE_RAYS = 1 << 20


def write_tri(path, verts, idx):
    verts = np.ascontiguousarray(verts, dtype="<f4")
    idx = np.ascontiguousarray(idx, dtype="<u4")
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    header = b"TRIM" + struct.pack("<3I6f", 1, len(verts), len(idx), *lo, *hi) + bytes(24)
    with open(path, "wb") as f:
        f.write(header)
        f.write(verts.tobytes())
        f.write(idx.tobytes())


def write_rays(path, origins, dirs, kind, seed):
    rays = np.concatenate([origins, dirs], axis=1).astype("<f4")
    header = b"RAYS" + struct.pack("<IQ4I2f", 1, len(rays), kind, WIDTH if kind == 0 else 0,
                                   HEIGHT if kind == 0 else 0, seed, 0.0, np.inf) + bytes(24)
    assert len(header) == 64
    with open(path, "wb") as f:
        f.write(header)
        f.write(rays.tobytes())


def grid(nu, nv):
    """Indices of an nu x nv vertex grid as two triangles per cell."""
    i = np.arange((nu - 1) * (nv - 1))
    r, c = i // (nu - 1), i % (nu - 1)
    a = r * nu + c
    t1 = np.stack([a, a + 1, a + nu + 1], axis=1)
    t2 = np.stack([a, a + nu + 1, a + nu], axis=1)
    return np.concatenate([t1, t2])


def quad(p, u, v):
    """Two triangles spanning p, p+u, p+u+v, p+v."""
    p, u, v = (np.asarray(x, dtype=np.float64) for x in (p, u, v))
    return np.array([p, p + u, p + u + v, p + v]), np.array([[0, 1, 2], [0, 2, 3]])


def merge(parts):
    verts, idx, base = [], [], 0
    for v, i in parts:
        verts.append(v)
        idx.append(i + base)
        base += len(v)
    return np.concatenate(verts), np.concatenate(idx)


def sphere():
    """Lat-long sphere of radius 1 displaced by a few octaves of sines."""
    nu, nv = 776, 776  # 2 * 775^2 = 1.2M triangles
    th = np.linspace(1e-3, np.pi - 1e-3, nv)[:, None]
    ph = np.linspace(0, 2 * np.pi, nu)[None, :]
    r = 1.0
    for k in (3, 7, 17, 41):
        r = r + (0.12 / k) * np.sin(k * th * 2.3) * np.cos(k * ph + 1.7 * k)
    p = np.stack([r * np.sin(th) * np.cos(ph), r * np.cos(th), r * np.sin(th) * np.sin(ph)], axis=-1)
    return p.reshape(-1, 3), grid(nu, nv), np.array([0.0, 0.0, 3.2]), np.zeros(3)


def terrain():
    """A 742x742 heightfield over [-1,1]^2 (y up) in a room 4 wide, 2 high."""
    n = 742  # 2 * 741^2 = 1.1M triangles
    x, z = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
    h = 0.25 * np.exp(-3 * (x * x + z * z)) * (1 + 0.3 * np.sin(9 * x) * np.cos(7 * z))
    h += 0.01 * np.sin(41 * x + 3) * np.sin(37 * z)
    field = np.stack([x, h + 0.002, z], axis=-1).reshape(-1, 3), grid(n, n)
    room = [
        quad([-2, 0, -2], [0, 0, 4], [4, 0, 0]),  # the ground
        quad([-2, 2, -2], [4, 0, 0], [0, 0, 4]),  # ceiling
        quad([-2, 0, -2], [4, 0, 0], [0, 2, 0]),  # back wall
        quad([-2, 0, -2], [0, 2, 0], [0, 0, 4]),  # left
        quad([2, 0, -2], [0, 0, 4], [0, 2, 0]),   # right
    ]
    v, i = merge([field] + room)
    return v, i, np.array([0.0, 1.2, 3.5]), np.array([0.0, 0.1, 0.0])


def grass():
    """3,000 clumps of 500 blades (long thin triangles) on a ground quad."""
    rng = np.random.default_rng(11)
    clumps, blades = 3000, 500
    base = rng.uniform(-0.04, 0.04, (blades, 2))
    lean = rng.normal(0, 0.12, (blades, 2))
    height = rng.uniform(0.15, 0.4, blades)
    width = rng.uniform(0.002, 0.006, blades)
    ang = rng.uniform(0, 2 * np.pi, blades)
    b0 = np.stack([base[:, 0], np.zeros(blades), base[:, 1]], axis=1)
    side = np.stack([np.cos(ang), np.zeros(blades), np.sin(ang)], axis=1) * width[:, None]
    tip = b0 + np.stack([lean[:, 0], np.ones(blades), lean[:, 1]], axis=1) * height[:, None]
    clump = np.stack([b0 - side, b0 + side, tip], axis=1)  # blades x 3 x 3
    centres = rng.uniform(-6, 6, (clumps, 2))
    rot = rng.uniform(0, 2 * np.pi, clumps)
    scale = rng.uniform(0.6, 1.6, clumps)
    c, s = np.cos(rot), np.sin(rot)
    # Rotate about y, scale, translate: clumps x blades x 3 x 3.
    x = clump[None, :, :, 0] * c[:, None, None] - clump[None, :, :, 2] * s[:, None, None]
    z = clump[None, :, :, 0] * s[:, None, None] + clump[None, :, :, 2] * c[:, None, None]
    y = np.broadcast_to(clump[None, :, :, 1], x.shape)
    p = np.stack([x, y, z], axis=-1) * scale[:, None, None, None]
    p[..., 0] += centres[:, None, None, 0]
    p[..., 2] += centres[:, None, None, 1]
    blades_v = p.reshape(-1, 3)
    blades_i = np.arange(len(blades_v)).reshape(-1, 3)
    v, i = merge([(blades_v, blades_i), quad([-7, 0, -7], [0, 0, 14], [14, 0, 0])])
    return v, i, np.array([0.0, 2.0, 8.0]), np.array([0.0, 0.0, 0.0])


def primary(eye, target):
    """Pinhole camera rays, 50 degrees vertical, in 4x4 tiles (README order)."""
    fwd = target - eye
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    k = np.arange(WIDTH * HEIGHT)
    tile, within = k // 16, k % 16
    ty, tx = tile // (WIDTH // 4), tile % (WIDTH // 4)
    px, py = 4 * tx + within % 4, 4 * ty + within // 4
    tan = np.tan(np.radians(25))
    sx = (2 * (px + 0.5) / WIDTH - 1) * tan * WIDTH / HEIGHT
    sy = (1 - 2 * (py + 0.5) / HEIGHT) * tan
    d = fwd + sx[:, None] * right + sy[:, None] * up
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return np.broadcast_to(eye, d.shape), d


def diffuse(verts, idx, toward, seed):
    """Cosine-distributed rays from random points of random triangles (by
    index), the normal turned towards the point `toward(p)` (None: a random
    side)."""
    rng = np.random.default_rng(seed)
    t = rng.integers(0, len(idx), DIFFUSE_RAYS)
    a, b, c = (verts[idx[t, j]].astype(np.float64) for j in range(3))
    u, v = rng.random(DIFFUSE_RAYS), rng.random(DIFFUSE_RAYS)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    p = a + u[:, None] * (b - a) + v[:, None] * (c - a)
    n = np.cross(b - a, c - a)
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
    if toward is None:
        sign = np.where(rng.random(DIFFUSE_RAYS) < 0.5, -1.0, 1.0)
    else:
        sign = np.where(np.einsum("ij,ij->i", n, toward(p) - p) < 0, -1.0, 1.0)
    n *= sign[:, None]
    # An orthonormal frame about n (Duff et al. 2017).
    s = np.where(n[:, 2] >= 0, 1.0, -1.0)
    aa = -1 / (s + n[:, 2])
    bb = n[:, 0] * n[:, 1] * aa
    x = np.stack([1 + s * n[:, 0] ** 2 * aa, s * bb, -s * n[:, 0]], axis=1)
    y = np.stack([bb, s + n[:, 1] ** 2 * aa, -n[:, 1]], axis=1)
    r, phi = np.sqrt(rng.random(DIFFUSE_RAYS)), 2 * np.pi * rng.random(DIFFUSE_RAYS)
    lz = np.sqrt(np.maximum(0, 1 - r * r))
    d = x * (r * np.cos(phi))[:, None] + y * (r * np.sin(phi))[:, None] + n * lz[:, None]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    scale = np.abs(verts).max()
    return p + n * (1e-4 * scale), d


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: heldout_meshes.py OUT_DIR")
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    meshes = {
        "sphere": (sphere, lambda p: 2 * p),  # outward, away from the centre
        "terrain": (terrain, lambda p: np.array([0.0, 1.0, 0.0])),  # into the room
        "grass": (grass, None),
    }
    for seed, (name, (make, toward)) in enumerate(meshes.items(), start=1):
        verts, idx, eye, target = make()
        write_tri(out / f"{name}.tri", verts, idx)
        write_rays(out / f"{name}.primary.rays", *primary(eye, target), 0, seed)
        write_rays(out / f"{name}.diffuse.rays", *diffuse(verts, idx, toward, seed), 1, seed)
        print(f"{name}: {len(idx)} triangles, {len(verts)} vertices -> {out}")


if __name__ == "__main__":
    main()
