"""Candela Studio in a real browser (Debian's chromium through Playwright).

Every test opens the page on `candela view -r 160 120 -s 4` of the demo
scene and waits for its first render to finish."""
import os
import shlex
import statistics
import subprocess
import urllib.error
import urllib.request

import pytest

from conftest import CANDELA, canvas_png, last_png, screenshot, wait_done
from pngio import read_png


def cli_render(command, path, **replace):
    """Runs the page's "copy command line" with the output at `path`,
    replacing flags given as `replace` (e.g. seed="7")."""
    words = shlex.split(command)
    assert words[0] == "candela" and words[-2] == "-f", command
    words[0], words[-1] = CANDELA, str(path)
    for flag, value in replace.items():
        flag = "--" + flag.replace("_", "-")
        if flag in words:
            words[words.index(flag) + 1] = value
        else:
            words[-2:-2] = [flag, value]
    subprocess.run(words + ["-q"], check=True, timeout=60)
    return read_png(path.read_bytes())


def block_z_max(a, b, block=8):
    """The largest |z| of the block means of two images, per channel, with
    each block mean's variance estimated from the pixels of its block (image
    structure inflates it, so the test errs on the side of passing) plus the
    8-bit rounding's 1/12. Returns (max |z|, Bonferroni threshold for a
    false alarm rate of 1e-3 over all blocks and channels)."""
    (w, h, ra), (_, _, rb) = a, b
    worst, tests = 0.0, 0
    for by in range(0, h - block + 1, block):
        for bx in range(0, w - block + 1, block):
            for c in range(3):
                va = [ra[y][x][c] for y in range(by, by + block) for x in range(bx, bx + block)]
                vb = [rb[y][x][c] for y in range(by, by + block) for x in range(bx, bx + block)]
                n = len(va)
                var = (statistics.pvariance(va) + statistics.pvariance(vb) + 2 / 12) / n
                worst = max(worst, abs(statistics.fmean(va) - statistics.fmean(vb)) / var ** 0.5)
                tests += 1
    threshold = statistics.NormalDist().inv_cdf(1 - 1e-3 / (2 * tests))
    return worst, threshold


def test_the_first_frame_equals_the_cli_render(page, tmp_path):
    header = page.evaluate("window.studio.lastHeader")
    assert (header["width"], header["height"], header["spp"]) == (160, 120, 4)
    studio = read_png(last_png(page))
    # The same seed takes the same samples (a pure function of seed, pixel
    # and index): only the f64 order of adding the refinement passes differs.
    same = cli_render(header["command"], tmp_path / "same.png")
    diff = max(abs(p - q) for ra, rb in zip(studio[2], same[2])
               for pa, pb in zip(ra, rb) for p, q in zip(pa, pb))
    assert diff <= 1, f"largest 8-bit difference {diff}"
    # Another seed: the same image up to noise, by a block z-test ...
    other = cli_render(header["command"], tmp_path / "other.png", seed="7")
    z, threshold = block_z_max(studio, other)
    assert z < threshold, (z, threshold)
    # ... which does reject another camera.
    moved = cli_render(header["command"], tmp_path / "moved.png", seed="7", fov="30")
    z, threshold = block_z_max(studio, moved)
    assert z > threshold, (z, threshold)
    screenshot(page, "render")


def drag(page, dx, dy, start=(0.5, 0.5)):
    """Drags by (dx, dy), fractions of the view's size, from `start`."""
    box = page.locator("#overlay").bounding_box()
    x, y = box["x"] + box["width"] * start[0], box["y"] + box["height"] * start[1]
    dx, dy = dx * box["width"], dy * box["height"]
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 9):
        page.mouse.move(x + dx * k / 8, y + dy * k / 8)
    page.mouse.up()


def test_dragging_moves_the_camera_and_the_image(page):
    before_camera = page.evaluate("window.studio.camera()")
    before = read_png(last_png(page))
    done = page.evaluate("window.studio.done")
    drag(page, 0.2, 0.05)
    wait_done(page, done)
    after_camera = page.evaluate("window.studio.camera()")
    assert after_camera["look_at"] == before_camera["look_at"], "orbiting keeps the look-at point"
    assert after_camera["eye"] != before_camera["eye"]
    after = read_png(last_png(page))
    changed = sum(pa != pb for ra, rb in zip(before[2], after[2]) for pa, pb in zip(ra, rb))
    assert changed > 0.3 * 160 * 120, f"only {changed} pixels changed"
    assert f"--eye" in page.evaluate("window.studio.lastHeader.command")


def test_bvh_mode_shows_the_root_and_its_two_children(page):
    # Step back, so that the whole box of the scene is in view.
    box = page.locator("#overlay").bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.wheel(0, 700)
    page.keyboard.press("b")
    page.wait_for_function("window.studio.bvh.node() && window.studio.bvh.node().node.index === 0")
    root = page.evaluate("window.studio.bvh.node()")
    assert len(root["children"]) == 2
    left, right = root["children"]
    assert left["primitives"] + right["primitives"] == root["node"]["primitives"] == len(root["prims"])
    assert root["node"]["sah_cost"] > 1
    # The boxes are drawn: the left child in red, the right one in green
    # (the mesh itself is grey in this mode).
    _, _, rows = read_png(canvas_png(page, "gl"))
    red = sum(1 for row in rows for r, g, b in row if r > 200 and g < 120 and b < 120)
    green = sum(1 for row in rows for r, g, b in row if g > 200 and r < 120 and b < 120)
    assert red > 20 and green > 20, (red, green)
    screenshot(page, "bvh")
    page.keyboard.press("l")
    page.wait_for_function(f"window.studio.bvh.node().node.index === {left['index']}")
    page.keyboard.press("u")
    page.wait_for_function("window.studio.bvh.node().node.index === 0")
    page.keyboard.press("r")
    page.wait_for_function(f"window.studio.bvh.node().node.index === {right['index']}")


def test_a_cell_render_changes_only_the_cell(page):
    before = read_png(last_png(page))
    done = page.evaluate("window.studio.done")
    page.keyboard.press("c")
    # The cell is rendered with other settings (normals), so it shows.
    page.evaluate("Panel.changes.integrator = 'normals'")
    drag(page, 0.35, 0.35, start=(0.25, 0.25))
    wait_done(page, done)
    command = page.evaluate("window.studio.lastHeader.command").split()
    i = command.index("-p")
    x, y, w, h = map(int, command[i + 1:i + 5])
    assert w > 20 and h > 20, (x, y, w, h)
    after = read_png(last_png(page))
    inside = outside_changed = inside_changed = 0
    for py in range(120):
        for px in range(160):
            changed = before[2][py][px] != after[2][py][px]
            if x <= px < x + w and y <= py < y + h:
                inside += 1
                inside_changed += changed
            else:
                outside_changed += changed
    assert outside_changed == 0
    assert inside_changed > 0.9 * inside, (inside_changed, inside)
    screenshot(page, "cell")


def test_requests_without_the_token_are_refused(server, page):
    base = server.split("?")[0]
    for path in ["", "static/app.js", "api/scene", "api/mesh", "api/bvh?node=0", "ws"]:
        try:
            urllib.request.urlopen(base + path, timeout=10)
            raise AssertionError(f"/{path} answered without the token")
        except urllib.error.HTTPError as e:
            assert e.code == 403, (path, e.code)
    response = page.goto(base)
    assert response.status == 403


def test_the_path_inspector_agrees_with_the_render(page):
    page.keyboard.press("i")
    page.fill("#inspect-n", "4")
    page.evaluate("window.studio.inspect(80, 70)")
    page.wait_for_function("window.studio.paths")
    reply = page.evaluate("window.studio.paths")
    assert reply["film_samples"] == 4 and len(reply["paths"]) == 4
    for path in reply["paths"]:
        for c in range(3):
            total = sum(t["value"][c] for t in path["contributions"])
            r = path["radiance"][c]
            assert abs(total - r) <= 1e-5 * max(1.0, abs(r)), (total, r)
    # The traced samples are the render's: their mean is the pixel's value.
    for c in range(3):
        mean = sum(p["value"][c] for p in reply["paths"]) / 4
        assert abs(mean - reply["film_mean"][c]) <= 1e-6 * max(1.0, abs(mean)), c
    assert any(p["vertices"] for p in reply["paths"])
    screenshot(page, "inspect")


def frame_of_layer(page, layer):
    page.wait_for_function(
        f"window.studio.lastHeader.layer === '{layer}' && window.studio.lastHeader.done")
    _, _, rows = read_png(last_png(page))
    return len({p for row in rows for p in row})


def test_layers_show_the_film_and_the_integrator_views(page, out_dir):
    for layer in ["albedo", "normal", "samples", "std_error", "depth", "cost", "cost_nodes", "cost_tests"]:
        page.select_option("#layer", layer)
        colours = frame_of_layer(page, layer)
        # Without adaptive sampling every pixel has the same count: one colour.
        assert colours >= 1 if layer == "samples" else colours > 20, (layer, colours)
        if layer in ("normal", "cost"):
            screenshot(page, f"layer-{layer}")
    for view, k in [("direct", None), ("indirect", None), ("bounce", 2)]:
        done = page.evaluate("window.studio.done")
        page.evaluate(f"window.studio.setLayer('{view}', {k if k is not None else 'undefined'})")
        wait_done(page, done)
        command = page.evaluate("window.studio.lastHeader.command")
        assert (f"--bounce {k}" if k else f"--integrator {view}") in command, command
    # Save writes through the film-to-file path into --out-dir only.
    for fmt in ["png", "exr"]:
        page.click(f"#save-{fmt}")
    page.wait_for_function("window.studio.saved.length >= 2")
    for path in page.evaluate("window.studio.saved"):
        assert os.path.dirname(path) == str(out_dir) and os.path.getsize(path) > 0, path


def test_a_bad_setting_shows_its_error_and_the_page_goes_on(page):
    page.fill("#settings input[name=spp]", "0")
    page.press("#settings input[name=spp]", "Enter")
    page.wait_for_function("window.studio.errors.length > 0")
    assert "spp (-s) 0" in page.evaluate("window.studio.errors[0]")
    assert "spp (-s) 0" in page.inner_text("#message")
    done = page.evaluate("window.studio.done")
    page.fill("#settings input[name=spp]", "2")
    page.press("#settings input[name=spp]", "Enter")
    wait_done(page, done)
    assert page.evaluate("window.studio.lastHeader.spp") == 2
