#!/usr/bin/env python3
"""Mutation fuzzing of the scene loaders and the scene build, through the CLI.

    python3 scripts/fuzz_scenes.py target/release/candela /tmp/fuzz --minutes 20 --seed 1

Takes every scene the repository ships (scenes/, the Mitsuba conformance
scenes, the loader tests' files), copies its folder, mutates the scene file
or one of the mesh files beside it, and renders the result at 16 x 12, one
sample. The project's rule for bad input is checked on every run: exit code
0 or 2, and on 2 exactly one `error:` line; never a panic (101), a signal, a
hang (60 s) or an allocation beyond 6 GiB. Every case that breaks it is kept
as a folder under OUT with the mutated files, and logged in OUT/found.log.

Mutations (one to three per case): a number replaced by an edge value
(0, -1, 1e38, nan, inf, 2^32 - 1, ...), a quoted value replaced by another
of the same file (a plugin type, a name, a reference), a line deleted or
duplicated, truncation, and random bytes; binary files (PLY, glTF buffers,
.serialized) get byte flips, truncation and overwritten words. The same
seed gives the same cases.

Standard library only.
"""

import argparse
import glob
import os
import random
import re
import resource
import shutil
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEED_GLOBS = [
    "scenes/*.dae", "scenes/cornell/*.dae", "scenes/cornell/*.obj", "scenes/cornell/*.xml",
    "scenes/cornell/*.gltf", "scenes/cornell/*.ply", "scenes/gltf/*.gltf", "scenes/manylights/*.xml",
    "scenes/materials/*.xml", "scenes/mitsuba/*.xml", "benches/mitsuba_conformance/*.xml",
    "crates/candela-scene/tests/mitsuba/*.xml", "crates/candela-scene/tests/valid_base.dae",
]
TEXT = (".xml", ".dae", ".gltf", ".obj", ".mtl")
COMPANIONS = (".ply", ".bin", ".obj", ".mtl", ".serialized")
EDGE_NUMBERS = [b"0", b"-1", b"1e38", b"-1e38", b"1e-38", b"nan", b"inf", b"-inf", b"4294967295",
                b"2147483648", b"99999999999", b"-0", b"1e400", b"", b"0.5", b"3", b"-3", b"65536",
                b"1000000000"]
EDGE_WORDS = [b"\xff\xff\xff\x7f", b"\x00\x00\x80\x7f", b"\x00\x00\xc0\x7f", b"\xff\xff\xff\xff",
              b"\x00\x00\x00\x80"]
NUMBER = re.compile(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?")
QUOTED = re.compile(rb'"[^"\n]*"')


def mutate_text(rng, b):
    kind = rng.randrange(9)
    if kind <= 2:
        found = list(NUMBER.finditer(b))
        if found:
            m = rng.choice(found)
            return b[:m.start()] + rng.choice(EDGE_NUMBERS) + b[m.end():]
    if kind in (3, 4):
        found = list(QUOTED.finditer(b))
        if len(found) >= 2:
            m, other = rng.sample(found, 2)
            return b[:m.start()] + other.group() + b[m.end():]
    lines = b.split(b"\n")
    if kind == 5 and len(lines) > 1:
        del lines[rng.randrange(len(lines))]
        return b"\n".join(lines)
    if kind == 6 and len(lines) > 1:
        lines.insert(rng.randrange(len(lines)), rng.choice(lines))
        return b"\n".join(lines)
    if kind == 7:
        return b[:rng.randrange(len(b) + 1)]
    return flip_bytes(rng, b)


def flip_bytes(rng, b):
    out = bytearray(b)
    for _ in range(rng.randrange(1, 8) if out else 0):
        out[rng.randrange(len(out))] = rng.randrange(256)
    return bytes(out)


def mutate_binary(rng, b):
    kind = rng.randrange(3)
    if kind == 0:
        return flip_bytes(rng, b)
    if kind == 1:
        return b[:rng.randrange(len(b) + 1)]
    out = bytearray(b)
    if out:
        i = rng.randrange(max(1, len(out) - 4))
        out[i:i + 4] = rng.choice(EDGE_WORDS)
    return bytes(out)


def seeds():
    found = []
    for pattern in SEED_GLOBS:
        found += sorted(glob.glob(os.path.join(ROOT, pattern)))
    return found


def memory_limit():
    resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))


def run_case(binary, scene):
    out = os.path.join(os.path.dirname(scene), "fuzz-out.exr")
    cmd = [binary, "-q", "-t", "1", "-s", "1", "-r", "16", "12", "-f", out, scene]
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=60, preexec_fn=memory_limit)
    except subprocess.TimeoutExpired:
        return "timeout", ""
    err = p.stderr.decode(errors="replace")
    errors = [line for line in err.splitlines() if "error:" in line]
    ok = p.returncode == 0 or (p.returncode == 2 and len(errors) == 1)
    return (None if ok and "panicked" not in err else f"exit {p.returncode}"), err


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("binary")
    ap.add_argument("out")
    ap.add_argument("--minutes", type=float, default=10)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    os.makedirs(args.out, exist_ok=True)
    work = os.path.join(args.out, "work")
    log = open(os.path.join(args.out, "found.log"), "a")
    pool, runs, found, start = seeds(), 0, 0, time.time()
    while time.time() - start < args.minutes * 60:
        seed = rng.choice(pool)
        shutil.rmtree(work, ignore_errors=True)
        shutil.copytree(os.path.dirname(seed), work, ignore=shutil.ignore_patterns("__pycache__"))
        scene = os.path.join(work, os.path.basename(seed))
        companions = [f for f in sorted(glob.glob(os.path.join(work, "*"))) if f.endswith(COMPANIONS)
                      and f != scene]
        target = scene if not companions or rng.random() < 0.7 else rng.choice(companions)
        with open(target, "rb") as f:
            data = f.read()
        for _ in range(rng.randrange(1, 4)):
            data = mutate_text(rng, data) if target.endswith(TEXT) else mutate_binary(rng, data)
        with open(target, "wb") as f:
            f.write(data)
        runs += 1
        problem, err = run_case(args.binary, scene)
        if problem:
            found += 1
            keep = os.path.join(args.out, f"case{found:03d}")
            shutil.rmtree(keep, ignore_errors=True)
            shutil.copytree(work, keep)
            log.write(f"case{found:03d} {problem} seed={os.path.relpath(seed, ROOT)} "
                      f"mutated={os.path.basename(target)}\n{err[-1500:]}\n---\n")
            log.flush()
    print(f"{runs} cases, {found} kept in {args.out}")


if __name__ == "__main__":
    main()
