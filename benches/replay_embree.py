#!/usr/bin/env python3
"""Replays a `.tri` mesh and a `.rays` set (format: ../shared/bench/README.md)
through Intel Embree 4, one thread, and prints Mrays per CPU-second for
closest hit and any hit, in the same form as `candela bench rays`.

Installs nothing. Run it in a venv that has the `embreex` package (it bundles
Embree 4) and numpy:

    python3 -m venv /tmp/embree-venv && /tmp/embree-venv/bin/pip install embreex numpy
    /tmp/embree-venv/bin/python benches/replay_embree.py MESH.tri RAYS.rays [--hits H.hits]

Two ways of calling Embree are timed:

* batch: `EmbreeScene.run` over the whole ray array. embreex loops over the
  rays in compiled code, calling Embree's single-ray kernels (`rtcIntersect1`
  / `rtcOccluded1`) once per ray, and writes one int per ray to a numpy
  array. This is the figure to compare with Candela's single-ray
  traversal (it includes a few ns per ray of embreex's loop and output).
* one-at-a-time: `EmbreeScene.run` called from Python with one ray per call,
  on the first `--single` rays. Each call pays Python and numpy overhead of
  several microseconds, ten times Embree's own cost per ray, so this figure
  measures the Python binding, not Embree; it is printed only to show that.

Timing: the CPU time of the calling thread (`time.thread_time`), so Embree's
idle build threads and other processes on a shared machine are not
counted; the fastest of the passes run for at least `--seconds` (the
policy of `candela bench rays`).
"""

import argparse
import struct
import sys
import time

import numpy as np

try:
    from embreex import mesh_construction, rtcore, rtcore_scene
except ImportError:
    sys.exit("replay_embree.py: needs the embreex package (see the module docstring)")


def read_bytes(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        sys.exit(f"{path}: {e.strerror}")


def read_tri(path):
    data = read_bytes(path)
    if len(data) < 64 or data[:4] != b"TRIM":
        sys.exit(f"{path}: not a .tri file (no TRIM header)")
    version, nv, nt = struct.unpack_from("<3I", data, 4)
    if version != 1:
        sys.exit(f"{path}: .tri version {version}, expected 1")
    need = 64 + 12 * nv + 12 * nt
    if len(data) < need:
        sys.exit(f"{path}: {len(data)} bytes, header promises {need}")
    verts = np.frombuffer(data, "<f4", 3 * nv, 64).reshape(nv, 3)
    idx = np.frombuffer(data, "<u4", 3 * nt, 64 + 12 * nv).reshape(nt, 3)
    if nt and idx.max() >= nv:
        sys.exit(f"{path}: a triangle refers to vertex {idx.max()} of {nv}")
    return verts.astype(np.float32), idx.astype(np.int32)


def read_rays(path):
    data = read_bytes(path)
    if len(data) < 64 or data[:4] != b"RAYS":
        sys.exit(f"{path}: not a .rays file (no RAYS header)")
    (version,) = struct.unpack_from("<I", data, 4)
    (n,) = struct.unpack_from("<Q", data, 8)
    kind, _w, _h, _seed, tnear, tfar = struct.unpack_from("<4I2f", data, 16)
    if version != 1:
        sys.exit(f"{path}: .rays version {version}, expected 1")
    if len(data) < 64 + 24 * n:
        sys.exit(f"{path}: {len(data)} bytes, header promises {n} rays")
    rays = np.frombuffer(data, "<f4", 6 * n, 64).reshape(n, 6)
    origins = np.ascontiguousarray(rays[:, :3], dtype=np.float32)
    dirs = np.ascontiguousarray(rays[:, 3:], dtype=np.float32)
    return origins, dirs, kind, tnear, tfar


def read_hits(path):
    data = read_bytes(path)
    if len(data) < 32 or data[:4] != b"HITS":
        sys.exit(f"{path}: not a .hits file (no HITS header)")
    (n,) = struct.unpack_from("<I", data, 8)
    rec = np.frombuffer(data, np.dtype([("t", "<f4"), ("id", "<u4")]), n, 32)
    return rec["t"], rec["id"]


def fastest(pass_fn, n_rays, seconds):
    """Mrays per CPU-second of the calling thread: the fastest pass after a
    warm-up, passes repeated for at least `seconds`; and the last result."""
    result = pass_fn()
    best = 0.0
    start = time.perf_counter()
    while best == 0.0 or time.perf_counter() - start < seconds:
        c0 = time.thread_time()
        result = pass_fn()
        cpu = time.thread_time() - c0
        if cpu > 0:
            best = max(best, n_rays / cpu / 1e6)
    return best, result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh", help=".tri mesh")
    ap.add_argument("rays", help=".rays ray set")
    ap.add_argument("--hits", help="reference closest hits (.hits) to check the primitive ids against")
    ap.add_argument("--seconds", type=float, default=1.0, help="minimum seconds per measurement")
    ap.add_argument("--single", type=int, default=20000,
                    help="rays for the one-at-a-time (Python per call) figure; 0 skips it")
    ap.add_argument("--limit", type=int, help="replay only the first N rays")
    ap.add_argument("--write-hits", metavar="HITS",
                    help="write Embree's closest hits of the first 10,000 rays as a .hits file "
                         "(reference ids for `candela bench rays --hits`)")
    args = ap.parse_args()

    verts, idx = read_tri(args.mesh)
    origins, dirs, kind, _tnear, tfar = read_rays(args.rays)
    if args.limit:
        origins, dirs = origins[: args.limit], dirs[: args.limit]
    n = len(origins)
    print(f"{args.mesh}: {len(idx)} triangles; {args.rays}: {n} "
          f"{'primary' if kind == 0 else 'diffuse'} rays (Embree via embreex)")
    device = rtcore.EmbreeDevice()
    scene = rtcore_scene.EmbreeScene(device)
    b0 = time.perf_counter()
    mesh_construction.TriangleMesh(scene, verts, idx)
    scene.run(origins[:1], dirs[:1])  # commits (builds) the scene
    print(f"build: {1e3 * (time.perf_counter() - b0):.1f} ms wall (Embree's own threads)")
    if np.isfinite(tfar):
        sys.exit("replay_embree.py: ray sets with a finite tfar are not supported")

    if args.hits:
        t_ref, id_ref = read_hits(args.hits)
        m = min(len(id_ref), n)
        got = scene.run(origins[:m], dirs[:m]).astype(np.int64)
        want = np.where(id_ref[:m] == 0xFFFFFFFF, -1, id_ref[:m].astype(np.int64))
        print(f"check: {int((got == want).sum())} of {m} primitive ids match the reference")

    if args.write_hits:
        m = min(10000, n)
        out = scene.run(origins[:m], dirs[:m], output=1)
        miss = np.asarray(out["geomID"]).astype(np.int64) & 0xFFFFFFFF == 0xFFFFFFFF
        ids = np.where(miss, 0xFFFFFFFF, np.asarray(out["primID"]).astype(np.int64) & 0xFFFFFFFF).astype("<u4")
        t = np.where(miss, np.inf, out["tfar"]).astype("<f4")
        rec = np.empty(m, np.dtype([("t", "<f4"), ("id", "<u4")]))
        rec["t"], rec["id"] = t, ids
        with open(args.write_hits, "wb") as f:
            f.write(b"HITS" + struct.pack("<II", 1, m) + bytes(20) + rec.tobytes())
        print(f"wrote {args.write_hits}: closest hits of the first {m} rays")

    for label, query in (("closest", "INTERSECT"), ("any", "OCCLUDED")):
        rate, res = fastest(lambda: scene.run(origins, dirs, query=query), n, args.seconds)
        hits = int((res != -1).sum())
        print(f"  embree batch {label:<8} 1 thread: {rate:6.3f} Mrays per CPU-second  "
              f"({hits} of {n} hit)")
    if args.single > 0:
        k = min(args.single, n)
        for label, query in (("closest", "INTERSECT"), ("any", "OCCLUDED")):
            def one_at_a_time():
                for i in range(k):
                    scene.run(origins[i : i + 1], dirs[i : i + 1], query=query)
            rate, _ = fastest(one_at_a_time, k, min(args.seconds, 0.5))
            print(f"  embree single {label:<8} 1 thread: {rate:6.3f} Mrays per CPU-second  "
                  f"(one Python call per ray, first {k} rays: binding overhead, not Embree)")


if __name__ == "__main__":
    main()
