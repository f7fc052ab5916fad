"""Compares a Candela render with a Cycles render of the same glTF scene.

    python compare.py CANDELA.exr CYCLES.exr SIDE_BY_SIDE.png [REGIONS.json]

Reads both linear EXRs' RGB (the `OpenEXR` package; Candela's AOV layers
are not read),
prints the mean of the whole image, of its top and bottom rows (the wall
and the floor of the conformance scene) and of each disc named in
REGIONS.json (`make_scene.py` writes one per sphere, so per material), as
Candela / Cycles ratios per channel, and writes the two images side by side (sRGB) with their
difference below for the eye.
"""

import json
import os
import sys

import bpy
import numpy as np
import OpenEXR


def read(path):
    """The RGB layer, top row first."""
    return OpenEXR.File(path).channels()["RGB"].pixels.astype(np.float64)


def srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def ratio(a, b, mask):
    ma, mb = a[mask].mean(axis=0), b[mask].mean(axis=0)
    per = " ".join(f"{x:.3f}" for x in ma / np.maximum(mb, 1e-9))
    return f"{per}   (means {ma.mean():.4f} / {mb.mean():.4f}, {mask.sum()} px)"


def main(candela, cycles, out, regions):
    a, b = read(candela), read(cycles)
    if a.shape != b.shape:
        sys.exit(f"compare.py: sizes differ: {a.shape} and {b.shape}")
    h, w, _ = a.shape
    ys, xs = np.mgrid[0:h, 0:w]
    print("Candela / Cycles, per channel:")
    print(f"  whole image  {ratio(a, b, np.ones((h, w), bool))}")
    print(f"  top rows     {ratio(a, b, ys < h // 10)}")
    print(f"  bottom rows  {ratio(a, b, ys >= h - h // 10)}")
    if regions:
        with open(regions) as f:
            spec = json.load(f)
        for name, (cx, cy, r) in spec["regions"].items():
            mask = (xs + 0.5 - cx) ** 2 + (ys + 0.5 - cy) ** 2 < r * r
            print(f"  {name:<12} {ratio(a, b, mask)}")
    diff = np.abs(a - b)
    top = np.concatenate([srgb(a), srgb(b)], axis=1)
    bottom = np.concatenate([srgb(4 * diff), np.zeros_like(a)], axis=1)
    both = np.concatenate([top, bottom], axis=0)
    H, W, _ = both.shape
    img = bpy.data.images.new("side", W, H)
    rgba = np.concatenate([both[::-1], np.ones((H, W, 1))], axis=2)
    img.pixels = rgba.ravel().tolist()
    img.filepath_raw = os.path.abspath(out)
    img.file_format = "PNG"
    img.save()


if __name__ == "__main__":
    a = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    main(a[0], a[1], a[2], a[3] if len(a) > 3 else None)
