#!/usr/bin/env python3
"""Mitsuba 3 references for Candela, and Candela's error against them.

    reference SCENE.xml --spp 4096 -o OUT.exr
        Renders SCENE.xml with Mitsuba 3 in independent passes of <= 64 spp
        (seeds seed_base + k) and writes OUT.exr: the mean in R, G, B and the
        per-pixel standard error of that mean in stderr.R/G/B (from the
        spread of the passes, so the reference carries its own noise), and
        OUT.json: the exact command, versions, spp, passes, time.

    compare REFERENCE.exr --spp 4096 [--batches 16] [--png SIDE.png]
        Renders the reference's scene with Candela (`cargo run --release`,
        the same file, in --batches runs of seeds --seed, --seed + 1, ...;
        their spread gives Candela's per-pixel error), and reports
        the mean relative 8x8-block error, per region too, next to the
        value noise alone would give, and a per-block z-test.

Mitsuba's `max_depth` is kept in the file; Candela maps it to -m = max_depth - 1.
Run from a venv that has Mitsuba (setup printed if it is missing). The
`scalar_rgb` variant needs nothing else; `llvm_ad_rgb` needs LLVM (set
DRJIT_LIBLLVM_PATH, see ../shared/bench/README.md).
"""

import argparse
import datetime
import json
import math
import os
import platform
import shlex
import subprocess
import sys
import time
from pathlib import Path

SETUP = """mitsuba_reference.py needs Mitsuba 3 and numpy in a venv:
    python3 -m venv /tmp/mitsuba-venv
    /tmp/mitsuba-venv/bin/pip install 'mitsuba>=3.9,<3.10' numpy
    /tmp/mitsuba-venv/bin/python benches/mitsuba_reference.py ...
(for --variant llvm_ad_rgb also: apt-get install libllvm19 and
 export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1)"""

try:
    import numpy as np
    import drjit as dr
    import mitsuba as mi
except ImportError as err:
    sys.exit(f"{SETUP}\n(import failed: {err})")

REPO = Path(__file__).resolve().parent.parent
PASS_SPP = 64
BLOCK = 8

# Pixel rectangles (x0, y0, x1, y1, end exclusive) inside each object of a
# scene at its default 128x96 film, for per-object error figures.
REGIONS = {
    "cornell-materials": {
        "diffuse box": (38, 46, 50, 62),
        "gold (roughconductor)": (62, 62, 74, 76),
        "glass (dielectric)": (28, 72, 46, 88),
        "rough glass (roughdielectric)": (84, 72, 102, 88),
        "back wall": (52, 14, 76, 38),
        "light": (52, 5, 76, 11),
    },
    "cornell-coated": {
        "rough plastic box (roughplastic, nonlinear)": (38, 46, 50, 62),
        "copper (conductor)": (62, 62, 74, 76),
        "red plastic (roughplastic)": (28, 72, 46, 88),
        "aluminium (roughconductor)": (84, 72, 102, 88),
        "back wall": (52, 14, 76, 38),
        "light": (52, 5, 76, 11),
    },
}


def scene_regions(scene):
    """The regions of `scene`: the table above, or a regions.json beside the
    scene (written by the scene folder's generator) keyed by the scene's stem."""
    stem = Path(scene).stem
    if stem in REGIONS:
        return REGIONS[stem]
    path = Path(scene).parent / "regions.json"
    if path.is_file():
        return {k: tuple(v) for k, v in json.loads(path.read_text()).get(stem, {}).items()}
    return {}


def defines(items):
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep:
            sys.exit(f"mitsuba_reference: -D {item}: expected name=value")
        out[name] = value
    return out


def cpu_model():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def reference(args):
    mi.set_variant(args.variant)
    if args.threads:
        dr.set_thread_count(args.threads)
    if args.spp % PASS_SPP and args.spp > PASS_SPP:
        sys.exit(f"mitsuba_reference: --spp must be a multiple of {PASS_SPP}")
    per_pass = min(args.spp, PASS_SPP)
    passes = args.spp // per_pass
    if passes < 2:
        sys.exit("mitsuba_reference: at least two passes are needed for a standard error")
    scene = mi.load_file(str(args.scene), **defines(args.define))
    start = time.time()
    total = None
    total_sq = None
    for k in range(passes):
        img = np.array(mi.render(scene, spp=per_pass, seed=args.seed_base + k), dtype=np.float64)
        total = img if total is None else total + img
        total_sq = img * img if total_sq is None else total_sq + img * img
        print(f"pass {k + 1}/{passes}", end="\r", file=sys.stderr, flush=True)
    seconds = time.time() - start
    mean = total / passes
    var = np.maximum(total_sq / passes - mean * mean, 0.0) * passes / (passes - 1)
    stderr = np.sqrt(var / passes)
    out = Path(args.output)
    channels = ["R", "G", "B", "stderr.R", "stderr.G", "stderr.B"]
    data = np.concatenate([mean, stderr], axis=2).astype(np.float32)
    mi.Bitmap(data, mi.Bitmap.PixelFormat.MultiChannel, channels).write(str(out))
    sidecar = {
        "scene": os.path.relpath(Path(args.scene).resolve(), REPO),
        "command": shlex.join([Path(sys.executable).name, *sys.argv]),
        "renderer": f"Mitsuba {mi.__version__} (Dr.Jit {dr.__version__}), variant {args.variant}",
        "spp": passes * per_pass,
        "passes": passes,
        "spp_per_pass": per_pass,
        "seeds": f"{args.seed_base}..{args.seed_base + passes - 1}",
        "defines": defines(args.define),
        "layers": "R,G,B: mean; stderr.R/G/B: standard error of the mean from the passes' spread",
        "seconds": round(seconds, 1),
        "threads": dr.thread_count(),
        "machine": cpu_model(),
        "date": datetime.date.today().isoformat(),
    }
    out.with_suffix(".json").write_text(json.dumps(sidecar, indent=2) + "\n")
    print(f"wrote {out} and {out.with_suffix('.json')} ({passes * per_pass} spp, {seconds:.0f} s)")


def read_layers(path):
    """An EXR's beauty and, if present, its stderr layer, as float64 arrays."""
    bmp = mi.Bitmap(str(path))
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    arr = np.array(bmp, dtype=np.float64)

    def pick(prefix):
        idx = [names.index(prefix + c) for c in "RGB" if prefix + c in names]
        return arr[:, :, idx] if len(idx) == 3 else None

    return pick(""), pick("stderr.")


def blocks(img, block=BLOCK):
    """Means of block x block tiles (partial tiles at the edges dropped)."""
    h, w = img.shape[0] // block * block, img.shape[1] // block * block
    t = img[:h, :w].reshape(h // block, block, w // block, block, -1)
    return t.mean(axis=(1, 3))


def block_errors(test, test_se, ref, ref_se):
    """Mean relative block error, the mean noise alone would give, and the
    largest |z| over blocks and channels."""
    bt, br = blocks(test), blocks(ref)
    # Variance of a block mean: sum of its pixels' se^2 over n^2.
    var = (blocks(test_se**2) + blocks(ref_se**2)) / BLOCK**2
    keep = br > 1e-3 * max(br.max(), 1e-12)
    rel = np.abs(bt - br)[keep] / br[keep]
    # E|N(0, s)| = s * sqrt(2 / pi): the error of an unbiased pair.
    floor = (np.sqrt(var[keep]) * math.sqrt(2 / math.pi)) / br[keep]
    # Blocks both renderers compute exactly (sky seen directly: every
    # sample of a pixel gives the same value) have zero variance, and the
    # last-bit differences of their float32 means (Mitsuba and Candela sum
    # in different orders) would give |z| of 1e9. Their variance is floored
    # at the float32 rounding of the block means, so such blocks count as
    # agreeing, while a real difference there (larger than rounding) still
    # shows as a large |z|.
    rounding = (4 * np.finfo(np.float32).eps * np.maximum(np.abs(bt), np.abs(br))) ** 2
    z = np.abs(bt - br)[keep] / np.sqrt(np.maximum(var, rounding)[keep] + 1e-30)
    return rel.mean(), floor.mean(), z.max(), keep.sum()


def pixel_errors(test, ref, rect):
    """Relative error of the mean over a pixel rectangle, per channel."""
    x0, y0, x1, y1 = rect
    t = test[y0:y1, x0:x1].mean(axis=(0, 1))
    r = ref[y0:y1, x0:x1].mean(axis=(0, 1))
    return (t - r) / r


def render_candela(args, scene):
    """Candela's mean and per-pixel standard error, from --batches runs of
    the CLI with seeds seed, seed + 1, ... (its EXR has no error layer)."""
    per = args.spp // args.batches
    if per < 1 or args.batches < 2:
        sys.exit("mitsuba_reference: need --batches >= 2 and --spp >= --batches")
    imgs, cmds = [], []
    start = time.time()
    for b in range(args.batches):
        out = Path(args.workdir) / f"mitsuba_reference.candela.{b}.exr"
        cmd = ["cargo", "run", "--release", "-q", "-p", "candela-cli", "--", str(scene),
               "-s", str(per), "--seed", str(args.seed + b), "-f", str(out), "-q"]
        cmd += [a for k, v in defines_of(args).items() for a in ("-D", f"{k}={v}")]
        if args.threads:
            cmd += ["-t", str(args.threads)]
        subprocess.run(cmd, cwd=REPO, check=True)
        imgs.append(read_layers(out)[0])
        cmds.append(shlex.join(cmd))
        print(f"batch {b + 1}/{args.batches}", end="\r", file=sys.stderr, flush=True)
    stack = np.stack(imgs)
    se = stack.std(axis=0, ddof=1) / math.sqrt(len(imgs))
    return stack.mean(axis=0), se, cmds[0] + f"  (x{args.batches}, seeds {args.seed}..)", time.time() - start


def defines_of(args):
    """The reference's own -D defines (from its sidecar), so that Candela
    renders the same variant of the scene."""
    meta = json.loads(Path(args.reference).with_suffix(".json").read_text())
    return meta.get("defines", {})


def compare(args):
    mi.set_variant("scalar_rgb")
    ref_path = Path(args.reference)
    meta = json.loads(ref_path.with_suffix(".json").read_text())
    ref, ref_se = read_layers(ref_path)
    if ref_se is None:
        sys.exit(f"mitsuba_reference: {ref_path} has no stderr layer")
    test, test_se, cmd, secs = render_candela(args, REPO / meta["scene"])
    if args.save:
        channels = ["R", "G", "B", "stderr.R", "stderr.G", "stderr.B"]
        data = np.concatenate([test, test_se], axis=2).astype(np.float32)
        mi.Bitmap(data, mi.Bitmap.PixelFormat.MultiChannel, channels).write(args.save)
    rel, floor, zmax, n = block_errors(test, test_se, ref, ref_se)
    print(f"reference: {ref_path.name}, {meta['renderer']}, {meta['spp']} spp")
    print(f"candela:   {cmd}, {args.spp} spp in all ({secs:.0f} s)")
    print(f"mean relative {BLOCK}x{BLOCK}-block error: {100 * rel:.2f}% "
          f"(noise alone: {100 * floor:.2f}%), {n} block-channels, max |z| {zmax:.1f}")
    for name, rect in scene_regions(REPO / meta["scene"]).items():
        e = pixel_errors(test, ref, rect)
        se = np.sqrt(
            (test_se[rect[1]:rect[3], rect[0]:rect[2]] ** 2).sum(axis=(0, 1))
            + (ref_se[rect[1]:rect[3], rect[0]:rect[2]] ** 2).sum(axis=(0, 1))
        ) / ((rect[2] - rect[0]) * (rect[3] - rect[1]))
        r = ref[rect[1]:rect[3], rect[0]:rect[2]].mean(axis=(0, 1))
        print(f"  {name:32s} rect {rect}: Candela/Mitsuba - 1 = "
              + " ".join(f"{100 * v:+.2f}%" for v in e)
              + "  (±" + " ".join(f"{100 * s / x:.2f}" for s, x in zip(se, r)) + "% 1σ)")
    if args.png:
        side = np.concatenate([ref, test], axis=1)
        mi.Bitmap(side.astype(np.float32)).convert(
            mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(args.png)
        print(f"wrote {args.png} (Mitsuba left, Candela right)")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="mode", required=True)
    r = sub.add_parser("reference", help="render a Mitsuba reference")
    r.add_argument("scene", type=Path)
    r.add_argument("-o", "--output", required=True)
    r.add_argument("--spp", type=int, default=1024)
    r.add_argument("--seed-base", type=int, default=0)
    r.add_argument("--variant", default="scalar_rgb")
    r.add_argument("--threads", type=int, default=2)
    r.add_argument("-D", "--define", action="append", metavar="NAME=VALUE")
    c = sub.add_parser("compare", help="Candela against a stored reference")
    c.add_argument("reference")
    c.add_argument("--spp", type=int, default=1024)
    c.add_argument("--seed", type=int, default=1)
    c.add_argument("--batches", type=int, default=16, help="Candela runs (seeds) the spp is split into")
    c.add_argument("--save", help="write Candela's mean and stderr as an EXR")
    c.add_argument("--workdir", default="/tmp")
    c.add_argument("--threads", "-t", type=int, default=0, help="Candela's -t (0: its default)")
    c.add_argument("--png", help="write a side-by-side PNG (Mitsuba left)")
    args = p.parse_args()
    reference(args) if args.mode == "reference" else compare(args)


if __name__ == "__main__":
    main()
