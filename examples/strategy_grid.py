#!/usr/bin/env python3
"""Veach's strategy grid and the CS184 bounce strip from Candela's EXR layers.

    candela --integrator bdpt --technique-layers -m 3 -s 256 -f bdpt.exr scene.dae
    candela --bounce-layers 4 -m 4 -s 256 -f bounces.exr scene.dae
    python3 examples/strategy_grid.py bdpt.exr --out grid.png            # MIS-weighted
    python3 examples/strategy_grid.py bdpt.exr --unweighted --out raw.png
    python3 examples/strategy_grid.py bounces.exr --bounces --out strip.png

The grid has one row per path length k = s + t - 2 bounces (top: direct
light) and one column per number of light vertices s, as in Veach's thesis
(fig. 10.3); each cell is tone-mapped with one exposure for the whole grid,
so brightness compares across cells (the weighted cells add up to the
image). The strip is bounce_0 ... bounce_K side by side.

Needs the `OpenEXR`, `numpy` and `Pillow` Python packages
(`pip install OpenEXR numpy pillow`).
"""

import argparse
import re
import sys

import numpy as np


def read_layers(path):
    """Every RGB layer of an EXR as {name: (H, W, 3) float32}."""
    import OpenEXR

    with OpenEXR.File(path) as f:
        layers, parts = {}, {}
        for name, channel in f.channels().items():
            pixels = np.asarray(channel.pixels, dtype=np.float32)
            if pixels.ndim == 3 and pixels.shape[2] >= 3:  # grouped as name (R, G, B)
                layers[name] = pixels[:, :, :3]
                continue
            stem, _, component = name.rpartition(".")  # one channel each: name.R ...
            if component in ("R", "G", "B"):
                parts.setdefault(stem, {})[component] = pixels
        for stem, v in parts.items():
            if len(v) == 3:
                layers[stem] = np.stack([v["R"], v["G"], v["B"]], axis=-1)
        return layers


def shrink(rgb, n):
    """Each n x n block of pixels averaged into one (edges cropped)."""
    if n <= 1:
        return rgb
    h, w = rgb.shape[0] // n * n, rgb.shape[1] // n * n
    return rgb[:h, :w].reshape(h // n, n, w // n, n, 3).mean(axis=(1, 3))


def to_srgb8(rgb, scale):
    """Linear RGB times `scale` through the sRGB curve, as 8-bit."""
    x = np.clip(rgb * scale, 0.0, 1.0)
    srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (srgb * 255 + 0.5).astype(np.uint8)


def tile(cells, rows, cols, h, w, gap=4):
    """Cells {(row, col): image} on a dark canvas."""
    canvas = np.full((rows * (h + gap) + gap, cols * (w + gap) + gap, 3), 24, dtype=np.uint8)
    for (r, c), image in cells.items():
        y, x = gap + r * (h + gap), gap + c * (w + gap)
        canvas[y:y + h, x:x + w] = image
    return canvas


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("exr")
    p.add_argument("--out", required=True)
    p.add_argument("--unweighted", action="store_true", help="the unweighted strategies instead")
    p.add_argument("--bounces", action="store_true", help="a strip of the bounce_k layers")
    p.add_argument("--exposure", type=float, default=0.0, help="stops, for every cell alike")
    p.add_argument("--shrink", type=int, default=1, help="average N x N pixels into one")
    a = p.parse_args()
    layers = {k: shrink(v, a.shrink) for k, v in read_layers(a.exr).items()}
    scale = 2.0 ** a.exposure
    if a.bounces:
        names = sorted((n for n in layers if re.fullmatch(r"bounce_\d+", n)), key=lambda n: int(n[7:]))
        if not names:
            sys.exit(f"{a.exr}: no bounce_k layers (render with --bounce-layers K)")
        h, w, _ = layers[names[0]].shape
        cells = {(0, i): to_srgb8(layers[n], scale) for i, n in enumerate(names)}
        canvas = tile(cells, 1, len(names), h, w)
    else:
        suffix = "_unweighted" if a.unweighted else ""
        pattern = re.compile(r"s(\d+)_t(\d+)" + suffix)
        found = {}
        for name in layers:
            m = pattern.fullmatch(name)
            if m:
                found[(int(m.group(1)), int(m.group(2)))] = layers[name]
        if not found:
            sys.exit(f"{a.exr}: no s*_t* layers (render with --integrator bdpt --technique-layers)")
        lengths = sorted({s + t - 2 for s, t in found})
        max_s = max(s for s, _ in found)
        h, w, _ = next(iter(found.values())).shape
        cells = {(lengths.index(s + t - 2), s): to_srgb8(img, scale) for (s, t), img in found.items()}
        canvas = tile(cells, len(lengths), max_s + 1, h, w)
    from PIL import Image

    Image.fromarray(canvas).save(a.out)
    print(f"wrote {a.out} ({canvas.shape[1]}x{canvas.shape[0]})")


if __name__ == "__main__":
    main()
