"""Throughput of a distributed render on a LocalCluster vs one process.

    python crates/candela-py/benches/dask_throughput.py SCENE [--spp 256]
        [-r 200 150] [--workers 2] [--tiles 4 4] [--passes 1]

Both sides render the same image after a warm-up (scene loaded and BVH built
on every worker), so the ratio is the cost of the Dask path itself: task
scheduling, moving the parts, and merging them. Also checks the two films are
bit-identical.
"""

import argparse
import time

import candela
import candela.distributed as dist


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("-r", "--resolution", type=int, nargs=2, default=[200, 150])
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--tiles", type=int, nargs=2, default=[4, 4])
    p.add_argument("--passes", type=int, default=1)
    a = p.parse_args()
    from distributed import Client, LocalCluster

    w, h = a.resolution
    settings = dict(spp=a.spp, width=w, height=h, seed=1)
    scene = candela.load(a.scene)
    scene.render(spp=1, width=w, height=h)  # builds the BVH
    t0 = time.perf_counter()
    local = scene.render(passes=a.passes, threads=a.workers, **settings)
    t_local = time.perf_counter() - t0

    with LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=":0") as c:
        with Client(c) as client:
            # Warm-up: every worker loads the scene and builds the BVH.
            dist.render(a.scene, client, tiles=(a.workers, 1), spp=1, width=w, height=h)
            t0 = time.perf_counter()
            film = dist.render(a.scene, client, tiles=tuple(a.tiles), passes=a.passes, **settings)
            t_dask = time.perf_counter() - t0

    same = all(film.arrays()[k].tobytes() == local.arrays()[k].tobytes() for k in local.arrays())
    units = a.tiles[0] * a.tiles[1] * a.passes
    rays = local.stats["rays"]
    part_bytes = len(film.to_bytes()) / units
    print(f"{a.scene} {w}x{h} {a.spp} spp, {units} units, ~{part_bytes / 1024:.0f} KiB per unit result")
    print(f"single process, {a.workers} threads: {t_local:.2f} s, {rays / t_local / 1e6:.2f} Mrays/s")
    print(f"dask, {a.workers} workers x 1 thread: {t_dask:.2f} s, {rays / t_dask / 1e6:.2f} Mrays/s")
    print(f"efficiency {t_local / t_dask * 100:.1f}%, bit-identical: {same}")


if __name__ == "__main__":
    main()
