"""Candela Studio's interactivity, measured through the real page.

    CANDELA_BIN=target/release/candela python3 benches/studio_interactivity.py \
        [--scene ../shared/scenes/cs184/CBbunny.dae] [--stops 10] [--spp 32] \
        [--threads 2] [--rounds 4]

Starts `candela view --no-browser -r 800 600 -s SPP -t THREADS SCENE`, opens
the page in Debian's chromium (Playwright, the system browser), and measures:

1. Camera stop to first coarse frame, over `--stops` drags: the page's time
   from the mouse release to the coarse frame drawn, and the server's time
   from the render request to the coarse frame sent (`elapsed_ms` of the
   frame). Each drag starts ~1 s into the previous refinement, so it also
   pays for cancelling a running render.
2. Steady-state throughput, interleaved over `--rounds` (A B, B A, ...): the server's
   samples per second of the refinement (pixels x spp over the time from the
   coarse frame sent to the last frame sent, so frame encoding and film
   merging count), then the CLI rendering the same camera and settings
   (the page's own "copy command line", same thread count), whose
   `samples/s` line times the render alone (no load or BVH build).

Around each studio render it also reads CPU seconds from /proc
(benches/proc_cpu.py), which a loaded machine does not distort: the render
threads', the server's overhead (every other server thread: the worker that
builds and encodes frames, the async threads that send them) and chromium's
(decoding and drawing frames). The CLI's CPU seconds (load and BVH build
included) are printed beside.

The load average is read at each measurement: the machine is shared, so the
figures are only comparable within one sitting. The last line is a
ready-to-paste row for BENCHMARKS.md.
"""
import argparse
import os
import resource
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

from playwright.sync_api import sync_playwright

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from proc_cpu import cpu_delta, cpu_snapshot  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CANDELA = os.environ.get("CANDELA_BIN", os.path.join(ROOT, "target", "release", "candela"))
CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")
WIDTH, HEIGHT = 800, 600


def percentile(values, q):
    """The q-quantile by linear interpolation between order statistics."""
    v = sorted(values)
    pos = (len(v) - 1) * q
    lo = int(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def load():
    return os.getloadavg()[0]


def wait_job(pg, what, timeout=600000, polling=500):
    """Waits until the newest drawn frame is of the page's newest request and
    satisfies `what`, checking every `polling` ms: Playwright's default
    polls on every animation frame, which keeps chromium compositing (in
    software here) and takes CPU from the render being measured."""
    pg.wait_for_function(
        f"(() => {{ const h = window.studio.lastHeader; return h && h.job === window.studio.job && ({what}); }})()",
        timeout=timeout, polling=polling)


def camera_stops(pg, stops):
    box = pg.locator("#overlay").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page_ms, server_ms, loads = [], [], []
    for k in range(stops):
        pg.mouse.move(x, y)
        pg.mouse.down()
        step = 25 if k % 2 == 0 else -25  # back and forth: the view stays on the scene
        pg.mouse.move(x + step, y + 3, steps=5)
        t0 = time.perf_counter()
        pg.mouse.up()
        wait_job(pg, "h.coarse", timeout=60000, polling=10)
        page_ms.append((time.perf_counter() - t0) * 1e3)
        server_ms.append(pg.evaluate("window.studio.lastHeader.elapsed_ms"))
        loads.append(load())
        pg.wait_for_timeout(1000)  # a refinement is running when the next drag starts
    return page_ms, server_ms, loads


def server_throughput(pg, server_pid):
    """Samples/s of one full render of the current camera, refinement only,
    and the CPU seconds it cost (see proc_cpu.cpu_delta)."""
    before = cpu_snapshot(server_pid)
    pg.evaluate("window.studio.headers = []; window.studio.render()")
    wait_job(pg, "h.done")
    cpu = cpu_delta(cpu_snapshot(server_pid), before)
    headers = [h for h in pg.evaluate("window.studio.headers") if h["job"] == pg.evaluate("window.studio.job")]
    coarse = next(h for h in headers if h["coarse"])
    last = headers[-1]
    seconds = (last["elapsed_ms"] - coarse["elapsed_ms"]) / 1e3
    rendering = (last["render_ms"] - coarse["render_ms"]) / 1e3
    # Where the gap to the CLI would be: the server's own work between
    # passes (summing the film, encoding and sending frames).
    own = seconds - rendering
    timeline = ", ".join(f"{h['spp']}@{h['elapsed_ms'] / 1e3:.1f}s" for h in headers if not h["coarse"])
    print(f"  frames {timeline}; server's own work {own:.2f} s of {seconds:.1f} s ({100 * own / seconds:.1f}%)")
    threads = ", ".join(f"{n} {v:.2f}" for n, v in sorted(cpu["per_thread"].items()))
    print(f"  CPU s: rendering {cpu['rendering']:.2f}, server overhead {cpu['overhead']:.2f} ({threads}), "
          f"chromium {cpu['chromium']:.2f}")
    return WIDTH * HEIGHT * last["spp"] / seconds, last["command"], last["elapsed_ms"] / 1e3, cpu


def cli_throughput(command, out):
    words = shlex.split(command)
    words[0], words[-1] = CANDELA, out
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run(words, capture_output=True, text=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    # The CLI's CPU seconds (load and BVH build included): of the children
    # waited for, only it ended in between.
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    for line in run.stderr.splitlines():
        if line.endswith("samples/s"):
            seconds = float(line.split(" in ")[1].split(" s ")[0])
            print(f"  CPU s: CLI process {cpu:.2f}")
            return float(line.split()[-2]), seconds
    raise SystemExit(f"no samples/s line from the CLI:\n{run.stderr}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default=os.path.join(ROOT, "..", "shared", "scenes", "cs184", "CBbunny.dae"))
    ap.add_argument("--stops", type=int, default=10)
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=4)
    a = ap.parse_args()
    if not os.path.exists(a.scene):
        sys.exit(f"studio_interactivity: no scene at {a.scene}")
    proc = subprocess.Popen(
        [CANDELA, "view", "--no-browser", "-r", str(WIDTH), str(HEIGHT), "-s", str(a.spp),
         "-t", str(a.threads), a.scene],
        stdout=subprocess.PIPE, text=True)
    url = proc.stdout.readline().split()[-1]
    try:
        with sync_playwright() as p, tempfile.TemporaryDirectory() as tmp:
            b = p.chromium.launch(executable_path=CHROMIUM,
                                  args=["--use-gl=angle", "--use-angle=swiftshader",
                                        "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"])
            pg = b.new_page(viewport={"width": 1200, "height": 700})
            pg.goto(url)
            pg.wait_for_function("window.studio && window.studio.ready && window.studio.frames >= 1",
                                 timeout=300000)
            page_ms, server_ms, stop_loads = camera_stops(pg, a.stops)
            wait_job(pg, "h.done")
            studio, cli, ab_loads, cpus = [], [], [], []
            command = pg.evaluate("window.studio.lastHeader.command")
            for r in range(a.rounds):
                # A B, then B A: a load that drifts during a round favours neither.
                for side in ("studio", "cli") if r % 2 == 0 else ("cli", "studio"):
                    if side == "studio":
                        rate, command, wall, cpu = server_throughput(pg, proc.pid)
                        studio.append(rate)
                        cpus.append(cpu)
                    else:
                        rate, wall = cli_throughput(command, os.path.join(tmp, "cli.png"))
                        cli.append(rate)
                    ab_loads.append(load())
                    print(f"round {r + 1}: {side:6} {rate:,.0f} samples/s ({wall:.1f} s, load {ab_loads[-1]:.1f})",
                          flush=True)
            b.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)

    def ms(v):
        return ", ".join(f"{x:.0f}" for x in v)
    print(f"page: mouse-up -> coarse frame drawn (ms): {ms(page_ms)}")
    print(f"server: request -> coarse frame sent (ms): {ms(server_ms)}")
    pm, p90 = statistics.median(page_ms), percentile(page_ms, 0.9)
    sm, s90 = statistics.median(server_ms), percentile(server_ms, 0.9)
    ratios = [s / c for s, c in zip(studio, cli)]
    ratio = statistics.median(ratios)
    loads = stop_loads + ab_loads
    print(f"first coarse frame: page median {pm:.0f} ms, p90 {p90:.0f} ms; server median {sm:.0f} ms, p90 {s90:.0f} ms")
    print(f"steady state: studio / CLI per round {', '.join(f'{r:.3f}' for r in ratios)}, median {ratio:.3f}")
    print(f"load average {min(loads):.1f}-{max(loads):.1f}")
    share = statistics.median(c["overhead"] / c["rendering"] for c in cpus)
    chromium = statistics.median(c["chromium"] / c["rendering"] for c in cpus)
    print(f"CPU per refinement, median over rounds: server overhead {100 * share:.1f}% and chromium "
          f"{100 * chromium:.1f}% of the render threads' CPU")
    print("| date | scene | threads | load | coarse frame, page median / p90 | server median / p90 "
          "| studio samples/s | CLI samples/s | studio / CLI | server overhead / chromium CPU |")
    print(f"| {time.strftime('%Y-%m-%d')} | {os.path.basename(a.scene)} {WIDTH}×{HEIGHT}, {a.spp} spp "
          f"| {a.threads} | {min(loads):.1f}–{max(loads):.1f} | {pm:.0f} / {p90:.0f} ms | {sm:.0f} / {s90:.0f} ms "
          f"| {statistics.median(studio):,.0f} | {statistics.median(cli):,.0f} | {ratio:.2f} "
          f"| {100 * share:.1f}% / {100 * chromium:.1f}% |")


if __name__ == "__main__":
    main()
