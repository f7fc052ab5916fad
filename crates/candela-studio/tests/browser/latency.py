"""Measures the studio's first coarse frame after a camera stop (not a test:
`python latency.py SCENE [candela flags...]`, with CANDELA_BIN set).

Opens the page, waits for the first render to finish, then drags the camera
N times; for each stop it reports the server's time from the render request
to the coarse frame being sent (`elapsed_ms` of the coarse frame), and the
page's time from the mouse release to that frame drawn."""
import os
import statistics
import subprocess
import sys
import time

from playwright.sync_api import sync_playwright

CANDELA = os.environ.get("CANDELA_BIN", "target/release/candela")


def main(scene, *flags, stops=5):
    proc = subprocess.Popen([CANDELA, "view", "--no-browser", *flags, scene],
                            stdout=subprocess.PIPE, text=True)
    url = proc.stdout.readline().split()[-1]
    server_ms, page_ms = [], []
    try:
        with sync_playwright() as p:
            b = p.chromium.launch(executable_path="/usr/bin/chromium",
                                  args=["--use-gl=angle", "--use-angle=swiftshader",
                                        "--enable-unsafe-swiftshader"])
            pg = b.new_page(viewport={"width": 1200, "height": 700})
            pg.goto(url)
            pg.wait_for_function("window.studio && window.studio.frames >= 1", timeout=120000)
            box = pg.locator("#overlay").bounding_box()
            x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
            for k in range(stops):
                job = pg.evaluate("window.studio.job")
                pg.mouse.move(x, y)
                pg.mouse.down()
                pg.mouse.move(x + 30, y + 5, steps=5)
                t0 = time.perf_counter()
                pg.mouse.up()
                pg.wait_for_function(
                    f"window.studio.lastHeader && window.studio.lastHeader.job === {job + 1}",
                    timeout=60000)
                page_ms.append((time.perf_counter() - t0) * 1e3)
                h = pg.evaluate("window.studio.lastHeader")
                assert h["coarse"], h
                server_ms.append(h["elapsed_ms"])
                pg.wait_for_timeout(1500)  # let refinement run, so the next move cancels it
            b.close()
    finally:
        proc.terminate()
    print(f"server request->coarse frame ms: {[round(v) for v in server_ms]} median {statistics.median(server_ms):.0f}")
    print(f"page mouse-up->coarse frame drawn ms: {[round(v) for v in page_ms]} median {statistics.median(page_ms):.0f}")


if __name__ == "__main__":
    main(*sys.argv[1:])
