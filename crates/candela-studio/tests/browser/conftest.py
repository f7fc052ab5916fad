"""Fixtures: a `candela view` server on a small render, and a page in
Debian's chromium (WebGL through SwiftShader) driven by Playwright."""
import base64
import os
import pathlib
import subprocess
import sys

import pytest
from playwright.sync_api import sync_playwright

sys.path.insert(0, os.path.dirname(__file__))

ROOT = pathlib.Path(__file__).resolve().parents[4]
CANDELA = os.environ.get("CANDELA_BIN", str(ROOT / "target" / "release" / "candela"))
CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")
# Screenshots for the README, taken only when asked for:
# STUDIO_SCREENSHOTS=docs/studio bash crates/candela-studio/ci-steps.sh
SHOTS = os.environ.get("STUDIO_SCREENSHOTS")
# The render every test looks at: small, so each frame takes milliseconds.
WIDTH, HEIGHT, SPP = 160, 120, 4


@pytest.fixture(scope="session")
def out_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("studio-out")


@pytest.fixture(scope="session")
def server(out_dir):
    """The URL of a `candela view` of the demo scene."""
    assert os.access(CANDELA, os.X_OK), f"no candela binary at {CANDELA}"
    proc = subprocess.Popen(
        [CANDELA, "view", "--no-browser", "--out-dir", str(out_dir),
         "-r", str(WIDTH), str(HEIGHT), "-s", str(SPP)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    assert "http://127.0.0.1:" in line, f"no URL printed: {line!r} {proc.stderr.read() if proc.poll() is not None else ''}"
    yield line.split()[-1]
    proc.terminate()
    proc.wait(timeout=10)


@pytest.fixture(scope="session")
def browser():
    with sync_playwright() as p:
        b = p.chromium.launch(
            executable_path=CHROMIUM,
            args=["--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                  "--ignore-gpu-blocklist"])
        yield b
        b.close()


@pytest.fixture
def page(browser, server):
    """The studio page once its first render is done."""
    pg = browser.new_page(viewport={"width": 1000, "height": 520})
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(server)
    pg.wait_for_function("window.studio && window.studio.ready && window.studio.done >= 1",
                         timeout=30000)
    yield pg
    assert not errors, errors
    pg.close()


def wait_done(pg, after):
    """Waits for a completed render later than `after` finished ones."""
    pg.wait_for_function(f"window.studio.done > {after} && window.studio.lastHeader.done",
                         timeout=30000)


def last_png(pg):
    """The last frame's PNG bytes."""
    b64 = pg.evaluate("""async () => {
        const buf = new Uint8Array(await window.studio.lastPng.arrayBuffer());
        let s = ""; for (const b of buf) s += String.fromCharCode(b);
        return btoa(s);
    }""")
    return base64.b64decode(b64)


def canvas_png(pg, canvas_id):
    """A canvas's pixels as PNG bytes."""
    url = pg.evaluate(f"document.getElementById('{canvas_id}').toDataURL('image/png')")
    return base64.b64decode(url.split(",", 1)[1])


def screenshot(pg, name):
    if SHOTS:
        folder = ROOT / SHOTS
        folder.mkdir(parents=True, exist_ok=True)
        pg.screenshot(path=str(folder / f"{name}.png"))
