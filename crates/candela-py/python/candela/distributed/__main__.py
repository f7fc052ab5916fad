"""``python -m candela.distributed scene.dae --dask local:2 --settings '{"spp": 64}'``

Renders a scene on a Dask cluster and writes the image. ``--dask`` is a
scheduler address (``tcp://host:8786``) or ``local:N`` for a cluster of N
single-threaded worker processes on this machine. The render settings come
as one JSON object with the names of ``Scene.render``'s keywords
(``candela.settings_help()``); ``candela --dask ADDRESS [flags]`` is the
command-line front that builds it from the CLI's flags. Settings it cannot
honour are refused by name with exit code 2.

With ``"checkpoint": PATH`` in the settings the film is saved there as units
come back; ``--resume PATH`` continues such a render (its scene, grid,
settings and output file come from the checkpoint).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import candela
import candela.distributed as dist

#: Exit code for settings the distributed render refuses (as the CLI's).
REFUSED = 2


def _args(argv):
    p = argparse.ArgumentParser(prog="python -m candela.distributed", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", nargs="?", help="scene file (shipped to the workers with every file it references)")
    p.add_argument("--resume", metavar="PATH", help="continue the render saved in this checkpoint")
    p.add_argument("--dask", required=True, metavar="ADDRESS", help="tcp://host:port or local:N")
    p.add_argument("--settings", default="{}", metavar="JSON", help="render settings as a JSON object")
    p.add_argument("-f", "--file", help="output .png or .exr [default: candela.png, or the checkpoint's]")
    p.add_argument("--tiles", type=int, nargs=2, default=[4, 4], metavar=("NX", "NY"), help="grid of cells")
    p.add_argument("--passes", type=int, default=1, help="sample ranges per pixel")
    p.add_argument("--retries", type=int, default=3, help="reruns of a unit that raised")
    p.add_argument("--strict", action="store_true", help="load warnings are errors")
    p.add_argument("--shared-path", action="store_true",
                   help="send workers the scene's path instead of its files (a cluster with a shared disk)")
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
    try:
        if a.resume is not None:
            # The checkpoint says what to render: the command line only how.
            r = dist.checkpoint.resume_args(a.resume)
            a.scene, a.tiles, a.passes, a.strict = r["scene_path"], list(r["tiles"]), r["passes"], r["strict"]
            a.file = a.file or r["output"]
            a.settings = json.dumps(r["settings"])
        if a.scene is None:
            raise ValueError("a scene file (or --resume PATH) is needed")
        a.file = a.file or "candela.png"
        settings = json.loads(a.settings)
        if not isinstance(settings, dict):
            raise ValueError("--settings: expected a JSON object")
        # Refuse what cannot be honoured before a cluster is started.
        candela.load(a.scene, strict=a.strict).settings(**settings)
        refused = [f"{k} ({dist.UNSUPPORTED[k]})" for k in dist.UNSUPPORTED if settings.get(k) not in (None, False)]
        if refused:
            raise dist.SettingsRefused(f"--dask does not support {', '.join(refused)} yet")
        if settings.get("denoise"):
            candela.denoiser_library()  # the client denoises: refuse now if it cannot
    except candela.DenoiseError as e:
        print(f"candela: error: --denoise: {e}", file=sys.stderr)
        return REFUSED
    except (ValueError, candela.LoadError) as e:
        print(f"candela: error: {e}", file=sys.stderr)
        return REFUSED
    output = {k: settings[k] for k in ("exposure", "tone", "denoise", "exr_compression") if k in settings}
    client, cluster = _client(a.dask)
    try:
        done = [0]
        units = a.tiles[0] * a.tiles[1] * a.passes

        def progress(unit, film):
            done[0] += 1
            if not a.quiet:
                print(f"\rcandela: {done[0]}/{units} units", end="", file=sys.stderr, flush=True)

        start = time.perf_counter()
        record = {"output": os.path.abspath(a.file), "address": a.dask}
        try:
            film = dist.render(a.scene, client, tiles=tuple(a.tiles), passes=a.passes, retries=a.retries,
                               strict=a.strict, ship_scene=not a.shared_path, on_unit=progress, record=record,
                               **settings)
        except ValueError as e:  # a checkpoint of another render
            print(f"candela: error: {e}", file=sys.stderr)
            return REFUSED
        film.save(a.file, aovs=True, **output)
        stem, ext = os.path.splitext(a.file)
        denoised = f" and {stem}.denoised{ext}" if output.get("denoise") else ""
        if not a.quiet:
            s = film.stats
            print(f"\ncandela: {s['rays']} rays in {time.perf_counter() - start:.3f} s "
                  f"on {len(client.scheduler_info()['workers'])} workers: {s['mrays_per_s']:.2f} Mrays/s; "
                  f"wrote {a.file}{denoised}", file=sys.stderr)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
