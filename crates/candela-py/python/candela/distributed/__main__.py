"""``python -m candela.distributed scene.dae --dask local:2 ...``

Renders a scene on a Dask cluster and writes the image. ``--dask`` is a
scheduler address (``tcp://host:8786``) or ``local:N`` for a cluster of N
single-threaded worker processes on this machine.
"""

from __future__ import annotations

import argparse
import sys
import time

import candela
import candela.distributed as dist


def _args(argv):
    p = argparse.ArgumentParser(prog="python -m candela.distributed", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", help="scene file (.dae), readable by every worker")
    p.add_argument("--dask", required=True, metavar="ADDRESS", help="tcp://host:port or local:N")
    p.add_argument("-s", "--spp", type=int, default=16, help="samples per pixel")
    p.add_argument("-m", "--max-depth", type=int, default=5, help="maximum bounces")
    p.add_argument("-l", "--light-samples", type=int, default=1, help="light samples per vertex")
    p.add_argument("-r", "--resolution", type=int, nargs=2, default=[800, 600], metavar=("W", "H"))
    p.add_argument("-f", "--file", default="candela.png", help="output .png or .exr")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--integrator", default="path", choices=["path", "normals", "direct", "indirect"])
    p.add_argument("--tiles", type=int, nargs=2, default=[4, 4], metavar=("NX", "NY"), help="grid of cells")
    p.add_argument("--passes", type=int, default=1, help="sample ranges per pixel")
    p.add_argument("--retries", type=int, default=3, help="reruns of a unit that raised")
    p.add_argument("-t", "--threads", type=int, default=1, help="render threads per unit")
    p.add_argument("-q", "--quiet", action="store_true")
    return p.parse_args(argv)


def _client(address: str):
    from distributed import Client, LocalCluster

    if address.startswith("local:"):
        n = int(address.split(":", 1)[1])
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0")
        return Client(cluster), cluster
    return Client(address), None


def main(argv=None) -> int:
    a = _args(argv)
    client, cluster = _client(a.dask)
    try:
        done = [0]
        units = a.tiles[0] * a.tiles[1] * a.passes

        def progress(unit, film):
            done[0] += 1
            if not a.quiet:
                print(f"\rcandela: {done[0]}/{units} units", end="", file=sys.stderr, flush=True)

        start = time.perf_counter()
        film = dist.render(
            a.scene, client, tiles=tuple(a.tiles), passes=a.passes, retries=a.retries,
            on_unit=progress, spp=a.spp, max_depth=a.max_depth, light_samples=a.light_samples,
            width=a.resolution[0], height=a.resolution[1], seed=a.seed, integrator=a.integrator,
            threads=a.threads,
        )
        film.save(a.file)
        if not a.quiet:
            s = film.stats
            print(f"\ncandela: {s['rays']} rays in {time.perf_counter() - start:.3f} s "
                  f"on {len(client.scheduler_info()['workers'])} workers: {s['mrays_per_s']:.2f} Mrays/s; "
                  f"wrote {a.file}", file=sys.stderr)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
