#!/usr/bin/env python3
"""Light selection at equal error on the many-lights scenes
(scenes/manylights/: the hall, or --scene .../city.xml; BENCHMARKS.md
"Many lights: the light BVH").

    many_lights.py [--candela target/release/candela] [--spp 16] [--runs 2]
                   [--scene scenes/manylights/city.xml] [--workdir DIR]

Use one --workdir per scene (the reference parts are kept there).

1. A reference: --ref-parts renders of --ref-spp samples each (seeds 1000,
   1001, ...; light tree selection, any unbiased strategy would do), added
   by `candela merge`.
2. For each strategy (uniform, power, bvh), --runs renders at --spp (seeds
   1, 2, ...), each a fresh process timed by its user + system CPU
   (os.wait4) and wall clock.
3. relMSE as benches/equal_error.py defines it, from `candela compare
   --json` (mean over pixels and channels of (x - r)^2 / (r^2 + 0.01)),
   minus the reference's own share: two reference parts differ by twice a
   part's variance, so the share is relMSE(part 0, part 1) / (2 parts).
4. Efficiency = 1 / (relMSE x CPU seconds): equal time, since relMSE falls
   as 1/time for an unbiased estimator. Ratios are against uniform.
Prints a Markdown table and the load average. Standard library only.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes/manylights/manylights.xml"
STRATEGIES = ["uniform", "power", "bvh"]


def timed(cmd):
    """Runs cmd; (wall seconds, user + system CPU seconds)."""
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    if status != 0:
        sys.exit(f"failed ({status}): {shlex.join(cmd)}")
    return wall, usage.ru_utime + usage.ru_stime


def rel_mse(candela, a, b):
    out = subprocess.run([candela, "compare", "--json", str(a), str(b)],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["comparisons"][0]["rel_mse"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--candela", default=str(ROOT / "target/release/candela"))
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--ref-spp", type=int, default=256)
    ap.add_argument("--ref-parts", type=int, default=4)
    ap.add_argument("--size", default="320 180")
    ap.add_argument("--depth", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scene", default=str(SCENE),
                    help="scenes/manylights/manylights.xml (the hall) or city.xml")
    ap.add_argument("--workdir", default="/tmp/many_lights")
    a = ap.parse_args()
    work = Path(a.workdir)
    work.mkdir(parents=True, exist_ok=True)

    def cmd(strategy, spp, seed, out):
        return [a.candela, "-q", "-t", str(a.threads), "-s", str(spp), "--seed", str(seed),
                "-m", str(a.depth), "-r", *a.size.split(), "--camera", "file",
                "--light-selection", strategy, "-f", str(out), a.scene]

    parts = [work / f"ref.{k}.exr" for k in range(a.ref_parts)]
    for k, part in enumerate(parts):
        if not part.exists():
            c = cmd("bvh", a.ref_spp, 1000 + k, part)
            wall, cpu = timed(c)
            print(f"reference part {k}: {wall:.1f} s wall, {cpu:.1f} s CPU: {shlex.join(c)}",
                  file=sys.stderr)
    ref = work / "ref.exr"
    subprocess.run([a.candela, "merge", "-q", *map(str, parts), "-o", str(ref)], check=True)
    ref_share = rel_mse(a.candela, parts[0], parts[1]) / (2 * a.ref_parts)
    print(f"reference: {a.ref_parts} x {a.ref_spp} spp, its relMSE share {ref_share:.2e}",
          file=sys.stderr)

    rows = {}
    for strategy in STRATEGIES:
        errs, cpus, walls = [], [], []
        for run in range(a.runs):
            out = work / f"{strategy}.{run}.exr"
            c = cmd(strategy, a.spp, 1 + run, out)
            wall, cpu = timed(c)
            errs.append(rel_mse(a.candela, out, ref) - ref_share)
            cpus.append(cpu)
            walls.append(wall)
            print(f"{strategy} run {run}: relMSE {errs[-1]:.3e}, {cpu:.1f} s CPU, {wall:.1f} s wall"
                  f"  {shlex.join(c)}", file=sys.stderr)
        rows[strategy] = (sum(errs) / len(errs), sum(cpus) / len(cpus), sum(walls) / len(walls))

    base = rows["uniform"][0] * rows["uniform"][1]
    print(f"\nload average: {os.getloadavg()}, {os.cpu_count()} CPUs\n")
    print(f"| selection | relMSE at {a.spp} spp | CPU s | wall s | relMSE x CPU s | efficiency vs uniform |")
    print("|---|---:|---:|---:|---:|---:|")
    for s, (err, cpu, wall) in rows.items():
        print(f"| {s} | {err:.3e} | {cpu:.1f} | {wall:.1f} | {err * cpu:.3e} | {base / (err * cpu):.1f}x |")


if __name__ == "__main__":
    main()
