#!/usr/bin/env python3
"""Two Candela builds at equal spp on one scene: relMSE and relMSE x CPU s.

    lamp_sampling.py --old OLD --new NEW --scene CBbunny --lights 1 \
        --spp 16 --runs 2 --reference-spp 1024 --workdir /tmp/lamps

Written for solid-angle sampling of lamps (BENCHMARKS.md, "Solid-angle
sampling of lamps"), usable for any change that should leave the image's
expectation alone and change its noise or cost.

1. Reference (cached in --workdir): the OLD build at --reference-spp, split
   into --reference-parts renders with seeds 1000, 1001, ...; r is their
   mean, v_r = s^2 / parts per pixel, and `candela merge` keeps the merged
   EXR (with its variance layer) for the z-test.
2. --runs rounds of OLD and NEW (order alternating), seeds 1, 2, ...,
   each a fresh process timed by user + system CPU (wait4).
3. relMSE as benches/equal_error.py defines it: the mean over pixels and
   channels of ((x - r)^2 - v_r) / (r^2 + 0.01); efficiency relMSE x CPU s
   (lower is better).
4. Agreement: `candela compare --json` of every NEW run against the merged
   reference (block z-test with the variance layers).

EXRs are read with Mitsuba's Bitmap, as equal_error.py does: run it with the
Python that has Mitsuba and numpy (../shared/bench/README.md).
"""

import argparse
import json
import os
import subprocess
import time
from pathlib import Path


def timed(cmd):
    start = time.time()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"failed: {' '.join(map(str, cmd))}")
    return time.time() - start, usage.ru_utime + usage.ru_stime


def read_exr(path):
    import mitsuba as mi
    import numpy as np

    mi.set_variant("scalar_rgb")
    bmp = mi.Bitmap(str(path))
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    arr = np.array(bmp, dtype=np.float64)
    return arr[:, :, [names.index(c) for c in "RGB"]]


def render(binary, args, spp, seed, out, lights):
    cmd = [binary, "-q", "-t", str(args.threads), "-s", str(spp), "-l", str(lights),
           "--seed", str(seed), "-r", "480", "360", "-f", str(out), str(args.dae)]
    wall, cpu = timed(cmd)
    return wall, cpu, cmd


def main():
    import numpy as np

    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--old", required=True)
    ap.add_argument("--new", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--dae")
    ap.add_argument("--lights", type=int, default=1)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--reference-parts", type=int, default=4)
    ap.add_argument("--workdir", default="/tmp/lamp_sampling")
    args = ap.parse_args()
    here = Path(__file__).resolve().parent
    args.dae = Path(args.dae or here.parent.parent / "shared/scenes/cs184" / f"{args.scene}.dae")
    work = Path(args.workdir)
    work.mkdir(parents=True, exist_ok=True)

    parts = []
    per = args.reference_spp // args.reference_parts
    for i in range(args.reference_parts):
        out = work / f"{args.scene}.ref{per}.{i}.exr"
        if not out.exists():
            wall, cpu, cmd = render(args.old, args, per, 1000 + i, out, 1)
            print(f"reference part {i}: {cpu:.1f} s CPU, {wall:.1f} s wall: {' '.join(map(str, cmd))}")
        parts.append(out)
    merged = work / f"{args.scene}.ref{args.reference_spp}.exr"
    if not merged.exists():
        subprocess.run([args.new, "merge", *map(str, parts), "-o", str(merged)], check=True,
                       stdout=subprocess.DEVNULL)
    imgs = np.stack([read_exr(p) for p in parts])
    r = imgs.mean(axis=0)
    v_r = imgs.var(axis=0, ddof=1) / len(parts)

    def relmse(x):
        return float(np.mean(((x - r) ** 2 - v_r) / (r * r + 0.01)))

    results = {"old": [], "new": []}
    for run in range(args.runs):
        order = ["old", "new"] if run % 2 == 0 else ["new", "old"]
        for which in order:
            out = work / f"{args.scene}.l{args.lights}.s{args.spp}.{which}.{run}.exr"
            wall, cpu, cmd = render(getattr(args, which), args, args.spp, run + 1, out, args.lights)
            e = relmse(read_exr(out))
            results[which].append((e, cpu, wall, out))
            print(f"{which} run {run}: relMSE {e:.5f}, {cpu:.1f} s CPU, {wall:.1f} s wall")
    summary = {}
    for which, rows in results.items():
        e = float(np.mean([x[0] for x in rows]))
        cpu = float(np.mean([x[1] for x in rows]))
        summary[which] = (e, cpu, e * cpu)
        print(f"{which}: relMSE {e:.5f}, CPU {cpu:.1f} s, relMSE x CPU {e * cpu:.4f}")
    (eo, co, fo), (en, cn, fn) = summary["old"], summary["new"]
    print(f"{args.scene} -l {args.lights} {args.spp} spp: relMSE new/old {en / eo:.3f}, "
          f"CPU new/old {cn / co:.3f}, efficiency gain (old/new relMSE x CPU) {fo / fn:.3f}")
    for e, cpu, wall, out in results["new"]:
        rep = subprocess.run([args.new, "compare", "--json", str(out), str(merged)],
                             capture_output=True, text=True)
        try:
            z = json.loads(rep.stdout)
        except json.JSONDecodeError:
            z = rep.stdout + rep.stderr
        print(f"z-test {out.name} vs reference: {json.dumps(z)[:600]}")
    print(f"load: {os.getloadavg()}")


if __name__ == "__main__":
    main()
