#!/usr/bin/env python3
"""Candela against Mitsuba 3 at equal error: relMSE x seconds, one sitting.

    equal_error.py CBbunny --spp 16,64,256 --runs 3 --reference-spp 16384

1. A reference, made once with Candela (cached in --workdir with the exact
   commands in a JSON sidecar; remade only if its settings change): the
   --reference-spp samples split into --reference-parts independent renders
   (seeds 1000, 1001, ...). Its mean is the reference r; the spread of the
   parts gives each pixel's variance of r, v_r = s^2 / parts.
2. For every spp level, --runs renders by each renderer, interleaved
   (Candela first in even rounds, Mitsuba first in odd ones), each a fresh
   process timed as a whole (wall clock, and user + system CPU from
   wait4): Candela's CLI, and a Python child that imports Mitsuba, loads
   the scene and renders it in passes of at most 64 spp (distinct seeds),
   merged by their spp. One untimed warm-up run of each comes first
   (Dr.Jit's kernel cache, the page cache).
3. relMSE of a render x: the mean over pixels and channels of
   ((x - r)^2 - v_r) / (r^2 + 0.01). E[(x - r)^2] = MSE(x) + Var(r) for a
   reference independent of x, so subtracting the unbiased estimate v_r
   leaves the render's own error; the share removed is printed (it should
   be small beside the errors measured, or the reference needs more spp).
   The 0.01 keeps black pixels from dominating (Rousselle et al. 2011).
4. Efficiency = relMSE x seconds (constant in spp for an unbiased Monte
   Carlo renderer once start-up is amortised); the ratio printed is
   Mitsuba's over Candela's (> 1: Candela needs less time for the same
   error), per level, by wall and by CPU time, and the asymptotic ratio from
   the marginal seconds per spp (a least-squares line through the times).
5. Like with like: the mean brightness of each renderer's runs against the
   reference at every level (relative difference and its standard error),
   and a block z-test of the mean of the runs at the highest level against
   the reference (16x16-pixel blocks, per-pixel variances from the runs'
   and the parts' spread; Bonferroni threshold at a 1e-3 false-alarm rate).
   A different camera, an image flip or a missing light fails it loudly. At
   a few spp the block means are too skewed for a z-test (a 2-run, 4-spp
   trial gave |z| 5.9 against 5.3 for both renderers alike), so only the
   highest level is tested; give it at least 16 spp.

Settings: unlimited path depth in both by default (Mitsuba max_depth -1,
Candela -m 1000 with its Russian roulette: 0.6^1000 of the light is
beyond reach), 2 threads each, Mitsuba's llvm_ad_rgb variant with its
independent sampler and the `path` integrator as the scene file sets them;
Candela's own defaults (Sobol, MIS, -l 1) unless --candela-args says more.
On a CPU with AVX-512, Dr.Jit compiles 16-wide AVX-512 kernels; --mitsuba-isa
avx2 makes it compile the 8-wide AVX2 kernels it uses on machines without
AVX-512 (the kind issue 13 names), for figures comparable across them.

Run with a Python that has Mitsuba 3 and numpy (setup in
../shared/bench/README.md); the scene pairs are ../shared/scenes/cs184/NAME.dae
and ../shared/bench/mitsuba/NAME.xml (--dae and --xml override).
"""

import argparse
import datetime
import json
import math
import os
import platform
import shlex
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SHARED = REPO.parent / "shared"
LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
PASS_SPP = 64
BLOCK = 16
EPSILON = 0.01
ALPHA = 1e-3
CANDELA_UNLIMITED = 1000

SETUP = """equal_error.py needs Mitsuba 3 and numpy:
    python3 -m venv /tmp/mitsuba-venv
    /tmp/mitsuba-venv/bin/pip install 'mitsuba>=3.9,<3.10' numpy
    apt-get install -y libllvm19        # for the llvm_ad_rgb variant
    /tmp/mitsuba-venv/bin/python benches/equal_error.py ..."""


def mitsuba_child(args):
    """The timed Mitsuba process: render in passes, write the merged mean."""
    import numpy as np
    import drjit as dr
    import mitsuba as mi

    if args.isa == "avx2":
        limit_llvm_to_avx2(dr)
    mi.set_variant(args.variant)
    dr.set_thread_count(args.threads)
    per = min(args.spp, PASS_SPP)
    scene = mi.load_file(args.xml, spp=per, max_depth=args.max_depth)
    total, done, k = None, 0, 0
    while done < args.spp:
        n = min(PASS_SPP, args.spp - done)
        img = np.array(mi.render(scene, spp=n, seed=args.seed * 1000 + k), dtype=np.float64)
        total = img * n if total is None else total + img * n
        done += n
        k += 1
    np.save(args.out, (total / done).astype(np.float32))


def limit_llvm_to_avx2(dr):
    """Makes Dr.Jit's LLVM back end compile 8-wide AVX2 kernels on a CPU with
    AVX-512, where it would otherwise pick 16-wide AVX-512 ones (1.6-1.7x faster
    per sample on the Zen 4 VMs): the peer as it runs on the issue's machine
    kind (AVX2, no AVX-512). The Embree inside Mitsuba keeps its own choice
    (its single-ray kernels gain little from AVX-512: BENCHMARKS.md).
    `jit_llvm_set_target` is Dr.Jit's C++ entry point, not in its Python API."""
    import ctypes

    core = ctypes.CDLL(str(Path(dr.__file__).parent / "libdrjit-core.so"))
    set_target = core._Z19jit_llvm_set_targetPKcS0_j
    set_target.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint32]
    features = "+avx2,+fma,+f16c,+bmi,+bmi2,+lzcnt,+popcnt," + ",".join(
        "-" + f for f in ("avx512f", "avx512vl", "avx512bw", "avx512dq", "avx512cd", "avx512bf16",
                          "avx512vnni", "avx512vbmi", "avx512vbmi2", "avx512bitalg", "avx512vpopcntdq",
                          "avx512ifma", "avx512fp16"))
    set_target(b"znver3", features.encode(), 8)


# ---------------------------------------------------------------- runs


def load():
    return Path("/proc/loadavg").read_text().split()[0] if Path("/proc/loadavg").exists() else "?"


def timed(cmd, env=None):
    """Runs cmd as a fresh process: (wall seconds, user + system CPU seconds)."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"equal_error: failed ({os.waitstatus_to_exitcode(status)}): {shlex.join(cmd)}")
    return wall, usage.ru_utime + usage.ru_stime


class Renderers:
    def __init__(self, args):
        self.args = args
        self.work = Path(args.workdir)
        self.work.mkdir(parents=True, exist_ok=True)
        self.env = dict(os.environ)
        if args.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in self.env and Path(LLVM).exists():
            self.env["DRJIT_LIBLLVM_PATH"] = LLVM

    def candela_cmd(self, spp, seed, out):
        a = self.args
        depth = CANDELA_UNLIMITED if a.max_depth < 0 else a.max_depth - 1
        # An uncompressed EXR, as Mitsuba's child writes a raw .npy: ZIP would
        # charge Candela ~0.3 s of CPU per run that Mitsuba does not pay.
        return [str(a.candela), "-q", "-t", str(a.threads), "-s", str(spp), "--seed", str(seed),
                "-m", str(depth), "-r", "480", "360", "--exr-compression", "none",
                *shlex.split(a.candela_args), "-f", str(out), str(a.dae)]

    def mitsuba_cmd(self, spp, seed, out):
        a = self.args
        return [sys.executable, str(Path(__file__).resolve()), "_mitsuba", "--xml", str(a.xml),
                "--spp", str(spp), "--seed", str(seed), "--out", str(out), "--threads",
                str(a.threads), "--variant", a.variant, "--max-depth", str(a.max_depth),
                "--isa", a.mitsuba_isa]

    def candela(self, spp, seed, tag):
        out = self.work / f"{tag}.exr"
        cmd = self.candela_cmd(spp, seed, out)
        wall, cpu = timed(cmd)
        return read_exr(out), wall, cpu, cmd

    def mitsuba(self, spp, seed, tag):
        import numpy as np

        out = self.work / f"{tag}.npy"
        cmd = self.mitsuba_cmd(spp, seed, out)
        wall, cpu = timed(cmd, self.env)
        return np.load(out).astype(np.float64), wall, cpu, cmd


def read_exr(path):
    import numpy as np
    import mitsuba as mi

    bmp = mi.Bitmap(str(path))
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    arr = np.array(bmp, dtype=np.float64)
    return arr[:, :, [names.index(c) for c in "RGB"]]


# ---------------------------------------------------------------- reference


def reference(args, r):
    """The reference mean and its per-pixel variance, made once and cached."""
    import numpy as np

    parts, per = args.reference_parts, args.reference_spp // args.reference_parts
    settings = {"dae": str(args.dae), "spp_per_part": per, "parts": parts,
                "max_depth": args.max_depth, "candela_args": args.candela_args,
                "threads": args.threads}
    stem = Path(args.workdir) / f"{args.scene}.reference"
    meta_path = stem.with_suffix(".json")
    if meta_path.exists() and stem.with_suffix(".npz").exists():
        meta = json.loads(meta_path.read_text())
        if meta["settings"] == settings:
            data = np.load(stem.with_suffix(".npz"))
            return data["mean"], data["var"], meta
    imgs, seconds, cmds = [], 0.0, []
    for k in range(parts):
        img, wall, _, cmd = r.candela(per, 1000 + k, f"{args.scene}.reference.{k}")
        imgs.append(img)
        seconds += wall
        cmds.append(shlex.join(cmd))
        print(f"reference part {k + 1}/{parts}: {wall:.1f} s", file=sys.stderr)
    stack = np.stack(imgs)
    mean = stack.mean(axis=0)
    var = stack.var(axis=0, ddof=1) / parts
    meta = {"settings": settings, "commands": cmds, "spp": per * parts,
            "seconds": round(seconds, 1), "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes"),
            "load": load()}
    np.savez(stem.with_suffix(".npz"), mean=mean, var=var)
    meta_path.write_text(json.dumps(meta, indent=2) + "\n")
    return mean, var, meta


# ---------------------------------------------------------------- measures


def rel_mse(x, ref, ref_var):
    """(relMSE with the reference's variance subtracted, the share removed)."""
    import numpy as np

    denom = ref * ref + EPSILON
    raw = np.mean((x - ref) ** 2 / denom)
    removed = np.mean(ref_var / denom)
    return raw - removed, removed


def block_means(img):
    h, w = img.shape[0] // BLOCK * BLOCK, img.shape[1] // BLOCK * BLOCK
    return img[:h, :w].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK, -1).mean(axis=(1, 3))


def agreement(imgs, ref, ref_var):
    """Mean brightness difference (relative, ±1σ) and the block z-test of the
    mean of `imgs` (independent runs) against the reference."""
    import numpy as np

    stack = np.stack(imgs)
    mean = stack.mean(axis=0)
    var = stack.var(axis=0, ddof=1) / len(imgs) + ref_var
    diff = mean.mean() / ref.mean() - 1
    diff_se = math.sqrt(var.sum()) / var.size / ref.mean()
    bm, br = block_means(mean), block_means(ref)
    bvar = block_means(var) / BLOCK**2
    keep = br > 1e-3 * br.max()
    z = np.abs(bm - br)[keep] / np.sqrt(np.maximum(bvar[keep], 1e-30))
    threshold = statistics.NormalDist().inv_cdf(1 - ALPHA / (2 * keep.sum()))
    return diff, diff_se, float(z.max()), threshold, int(keep.sum())


def slope(levels, times):
    """Least-squares seconds per spp through (spp, seconds)."""
    n = len(levels)
    mx, my = sum(levels) / n, sum(times) / n
    sxx = sum((x - mx) ** 2 for x in levels)
    return sum((x - mx) * (y - my) for x, y in zip(levels, times)) / sxx if sxx > 0 else float("nan")


# ---------------------------------------------------------------- main


def machine():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                flags = Path("/proc/cpuinfo").read_text()
                isa = "AVX-512" if " avx512f" in flags else "AVX2" if " avx2" in flags else "no AVX2"
                return f"{line.split(':', 1)[1].strip()}, {os.cpu_count()} cores, {isa}"
    except OSError:
        pass
    return platform.machine()


def run(args):
    try:
        import numpy as np  # noqa: F401
        import mitsuba as mi
    except ImportError as err:
        sys.exit(f"{SETUP}\n(import failed: {err})")
    mi.set_variant("scalar_rgb")  # the parent only reads images
    args.dae = args.dae or SHARED / "scenes" / "cs184" / f"{args.scene}.dae"
    args.xml = args.xml or SHARED / "bench" / "mitsuba" / f"{args.scene}.xml"
    for path in (args.dae, args.xml, args.candela):
        if not Path(path).exists():
            sys.exit(f"equal_error: {path}: no such file")
    levels = sorted(int(s) for s in args.spp.split(","))
    if args.runs < 2:
        sys.exit("equal_error: --runs must be at least 2 (the block test needs the runs' spread)")
    r = Renderers(args)
    started = datetime.datetime.now(datetime.timezone.utc)
    loads = [load()]
    ref, ref_var, meta = reference(args, r)
    loads.append(load())
    # Warm-up, untimed.
    r.candela(levels[0], 1, "warmup.candela")
    r.mitsuba(levels[0], 1, "warmup.mitsuba")
    res = {name: {spp: [] for spp in levels} for name in ("candela", "mitsuba")}
    cmds = {}
    for k in range(args.runs):
        for i, spp in enumerate(levels):
            order = ["candela", "mitsuba"] if (k + i) % 2 == 0 else ["mitsuba", "candela"]
            for name in order:
                seed = 10 + 100 * k + i
                img, wall, cpu, cmd = getattr(r, name)(spp, seed, f"{args.scene}.{name}.{spp}.{k}")
                err, removed = rel_mse(img, ref, ref_var)
                res[name][spp].append({"img": img, "wall": wall, "cpu": cpu, "relmse": err,
                                       "removed": removed, "load": load()})
                cmds.setdefault(name, shlex.join(cmd))
                print(f"round {k + 1}/{args.runs} {name:7s} {spp:5d} spp: {wall:6.1f} s wall "
                      f"{cpu:6.1f} s CPU  relMSE {err:.3e}  (load {load()})",
                      file=sys.stderr)
        loads.append(load())
    report(args, levels, res, ref, ref_var, meta, cmds, started, loads)


def report(args, levels, res, ref, ref_var, meta, cmds, started, loads):
    med = statistics.median
    print(f"\n### {args.scene}: Candela against Mitsuba 3 at equal error "
          f"({started:%Y-%m-%d %H:%M} UTC)\n")
    print(f"Machine: {machine()}; load average (1 min) over the sitting: {', '.join(loads)}.")
    print(f"Mitsuba's LLVM kernels: {args.mitsuba_isa} (--mitsuba-isa).")
    print(f"Reference: Candela, {meta['spp']} spp in {meta['settings']['parts']} parts "
          f"({meta['seconds']} s, made {meta['date']}, load {meta['load']}):")
    print("```\n" + "\n".join(meta["commands"]) + "\n```")
    print(f"Runs ({args.runs} per level, interleaved; seeds differ per run):")
    print("```\n" + cmds["candela"] + "\n" + cmds["mitsuba"] + "\n```")
    print("| spp | Candela wall / CPU (s) | Candela relMSE | Mitsuba wall / CPU (s) | Mitsuba relMSE "
          "| efficiency ratio, wall | CPU | reference share |")
    print("|---:|---|---:|---|---:|---:|---:|---:|")
    eff = {}
    for spp in levels:
        row = {}
        for name in ("candela", "mitsuba"):
            runs = res[name][spp]
            row[name] = (med([x["wall"] for x in runs]), med([x["cpu"] for x in runs]),
                         statistics.mean([x["relmse"] for x in runs]))
        (cw, cc, ce), (mw, mc, me) = row["candela"], row["mitsuba"]
        eff[spp] = ((me * mw) / (ce * cw), (me * mc) / (ce * cc))
        removed = res["candela"][spp][0]["removed"]
        print(f"| {spp} | {cw:.2f} / {cc:.2f} | {ce:.3e} | {mw:.2f} / {mc:.2f} | {me:.3e} "
              f"| **{eff[spp][0]:.2f}** | {eff[spp][1]:.2f} | {removed / min(ce, me):.1%} |")
    if len(levels) >= 2:
        # Asymptote: relMSE x spp (constant for unbiased MC) x marginal seconds per spp.
        parts = []
        for clock in ("wall", "cpu"):
            e = {}
            for name in ("candela", "mitsuba"):
                s = slope(levels, [med([x[clock] for x in res[name][spp]]) for spp in levels])
                v = statistics.mean(statistics.mean(x["relmse"] for x in res[name][spp]) * spp
                                    for spp in levels)
                e[name] = s * v
            parts.append(f"{clock} {e['mitsuba'] / e['candela']:.2f}")
        print(f"\nMarginal efficiency ratio (start-up excluded: least-squares seconds per spp "
              f"times the mean relMSE x spp): {', '.join(parts)}.")
    print("\nLike with like (mean of the runs at each level against the reference):\n")
    print("| spp | renderer | mean brightness vs reference | block max abs z (threshold, blocks) |")
    print("|---:|---|---|---|")
    worst = 0.0
    for spp in levels:
        for name in ("candela", "mitsuba"):
            d, se, zmax, thr, n = agreement([x["img"] for x in res[name][spp]], ref, ref_var)
            tested = spp == levels[-1]
            if tested:
                worst = max(worst, zmax / thr)
            block = f"{zmax:.2f} ({thr:.2f}, {n})" if tested else "(not tested)"
            print(f"| {spp} | {name} | {100 * d:+.2f} % ± {100 * se:.2f} % | {block} |")
    verdict = "pass" if worst <= 1 else "FAIL: the renderers do not show the same image"
    print(f"\nBlock test at {levels[-1]} spp: {verdict} (largest z / threshold {worst:.2f}).")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    if len(sys.argv) > 1 and sys.argv[1] == "_mitsuba":
        c = argparse.ArgumentParser()
        c.add_argument("_mode")
        for name in ("--xml", "--out", "--variant", "--isa"):
            c.add_argument(name, required=True)
        for name in ("--spp", "--seed", "--threads", "--max-depth"):
            c.add_argument(name, type=int, required=True)
        return mitsuba_child(c.parse_args())
    p.add_argument("scene", help="CBbunny or CBspheres_lambertian (a NAME.dae / NAME.xml pair)")
    p.add_argument("--spp", default="16,64,256", help="comma-separated spp levels")
    p.add_argument("--runs", type=int, default=3, help="runs per renderer and level (>= 2)")
    p.add_argument("--reference-spp", type=int, default=16384)
    p.add_argument("--reference-parts", type=int, default=4)
    p.add_argument("--max-depth", type=int, default=-1,
                   help="Mitsuba max_depth (-1 unlimited); Candela gets -m max_depth - 1")
    p.add_argument("--candela", type=Path, default=REPO / "target" / "release" / "candela")
    p.add_argument("--candela-args", default="", help="extra Candela flags, e.g. '-l 4'")
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--mitsuba-isa", choices=("native", "avx2"), default="native",
                   help="native: Dr.Jit's LLVM kernels for this CPU (16-wide AVX-512 where it has it); "
                        "avx2: 8-wide AVX2 kernels, as on a machine without AVX-512")
    p.add_argument("--dae", type=Path)
    p.add_argument("--xml", type=Path)
    p.add_argument("--workdir", default="/tmp/equal_error")
    run(p.parse_args())


if __name__ == "__main__":
    main()
