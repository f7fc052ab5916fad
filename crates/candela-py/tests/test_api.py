"""The Python API against the renderer's own guarantees: a render is a pure
function of (seed, pixel, sample index), so cells, sample ranges and merges
must reproduce the full render exactly."""

import os
import pickle
import signal
import threading
import time

import numpy as np
import pytest

import candela
from conftest import bits_equal

SMALL = dict(spp=4, width=40, height=30, seed=7, max_depth=4)


@pytest.fixture(scope="module")
def scene(spheres_path):
    return candela.load(spheres_path)


@pytest.fixture(scope="module")
def full(scene):
    return scene.render(**SMALL)


def test_load_reports_the_merged_lamp_as_a_note(scene):
    assert scene.warnings == []
    assert any("counted once" in n for n in scene.notes), scene.notes


def test_load_error_is_located(tmp_path):
    bad = tmp_path / "bad.dae"
    bad.write_text("<COLLADA>\n  <library_geometries>\n</COLLADA>\n")
    with pytest.raises(candela.LoadError, match=r"bad\.dae:\d+"):
        candela.load(bad)
    with pytest.raises(candela.LoadError):
        candela.load(tmp_path / "missing.dae")


def test_film_shapes_counts_and_stats(full):
    img = full.image()
    assert img.shape == (30, 40, 3) and img.dtype == np.float32
    assert np.isfinite(img).all() and img.max() > 0
    assert (full.sample_counts() == 4).all()
    s = full.stats
    assert s["samples"] == 40 * 30 * 4 == s["camera_rays"]
    assert s["rays"] == s["camera_rays"] + s["shadow_rays"] + s["bounce_rays"]
    assert s["invalid_samples"] == 0


def test_image_is_the_mean_of_the_sums(full):
    a = full.arrays()
    mean = (a["radiance"] / a["count"][..., None]).astype(np.float32)
    np.testing.assert_array_equal(full.image(), mean)


def test_depth_and_cost_sums_agree_with_the_counts_and_statistics(full):
    a, s = full.arrays(), full.stats
    assert a["depth_count"].dtype == np.uint32 and a["nodes"].dtype == np.uint64
    assert (a["depth_count"] <= a["count"]).all()
    hit = a["depth_count"] > 0
    assert hit.mean() > 0.5  # the box fills most of the frame
    assert (a["depth"][~hit] == 0).all()
    mean_depth = a["depth"][hit] / a["depth_count"][hit]
    assert np.isfinite(mean_depth).all() and (mean_depth > 0).all()
    # The film's per-pixel BVH work adds up to the render's totals.
    assert a["nodes"].sum() == pytest.approx(s["nodes_per_ray"] * s["rays"], rel=1e-9)
    assert a["prim_tests"].sum() == pytest.approx(s["tests_per_ray"] * s["rays"], rel=1e-9)
    assert a["nodes"].sum() > 0 and a["prim_tests"].sum() > 0


def test_a_cell_is_the_same_pixels_of_the_full_render(scene, full):
    cell = scene.render(cell=(13, 5, 18, 17), **SMALL)
    assert (cell.origin, cell.width, cell.height, cell.full_size) == ((13, 5), 18, 17, (40, 30))
    for k, v in cell.arrays().items():
        assert v.tobytes() == full.arrays()[k][5:22, 13:31].tobytes(), k


def test_cells_merge_to_the_full_render(scene, full):
    cells = [(0, 0, 17, 30), (17, 0, 23, 11), (17, 11, 23, 19)]
    parts = [scene.render(cell=c, **SMALL) for c in cells]
    assert bits_equal(candela.merge(parts), full)
    assert candela.merge(parts).stats["samples"] == full.stats["samples"]


def test_sample_ranges_merge_to_the_passes_render(scene, full):
    two = scene.render(passes=2, **SMALL)
    parts = [scene.render(sample_range=r, **SMALL) for r in [(0, 2), (2, 4)]]
    assert bits_equal(candela.merge(parts), two)
    # Same samples, other addition order: equal up to rounding.
    np.testing.assert_allclose(two.arrays()["radiance"], full.arrays()["radiance"], rtol=1e-12)
    assert (two.sample_counts() == 4).all()


def test_thread_count_does_not_change_the_film(scene, full):
    assert bits_equal(scene.render(threads=1, **SMALL), full)


def test_bytes_and_pickle_round_trip_exactly(scene):
    part = scene.render(cell=(3, 4, 17, 5), **SMALL)
    for back in (candela.Film.from_bytes(part.to_bytes()), pickle.loads(pickle.dumps(part))):
        assert bits_equal(back, part)
        assert back.full_size == part.full_size and back.stats == part.stats
    with pytest.raises(ValueError):
        candela.Film.from_bytes(b"not a film")
    with pytest.raises(ValueError):
        candela.Film.from_bytes(part.to_bytes()[:-1])


def test_adding_a_film_that_does_not_fit_is_refused(scene):
    part = scene.render(cell=(0, 0, 8, 8), **SMALL)
    small = scene.render(cell=(8, 8, 8, 8), **SMALL)
    with pytest.raises(ValueError):
        part.add(small)
    other = scene.render(spp=1, width=20, height=10)
    with pytest.raises(ValueError):
        candela.merge([part, other])


@pytest.mark.parametrize(
    "bad",
    [
        dict(cell=(0, 0, 41, 30)),
        dict(cell=(5, 5, 0, 9)),
        dict(cell=(30, 0, 11, 30)),
        dict(sample_range=(2, 5)),
        dict(sample_range=(3, 3)),
        dict(passes=5),
        dict(integrator="whitted"),
        dict(sampler="halton"),
        dict(adaptive="yes"),
        dict(adaptive=(0, 0.05)),
    ],
)
def test_impossible_requests_raise_value_error(scene, bad):
    with pytest.raises(ValueError):
        scene.render(**{**SMALL, **bad})


def test_save_png_and_exr(full, tmp_path):
    full.save(tmp_path / "a.exr")
    full.save(tmp_path / "a.png")
    np.testing.assert_array_equal(candela.read_image(tmp_path / "a.exr"), full.image())
    png = candela.read_image(tmp_path / "a.png")
    assert png.shape == (30, 40, 3)
    with pytest.raises(ValueError):
        full.save(tmp_path / "a.jpg")


def test_the_gil_is_released_while_rendering(scene):
    done = threading.Event()
    t = threading.Thread(target=lambda: (scene.render(spp=64, width=64, height=48, threads=1), done.set()))
    spins = 0
    t.start()
    while not done.is_set():
        spins += 1
        time.sleep(0)
    t.join()
    # With the GIL held for the whole render, this loop could not run.
    assert spins > 100


def test_ctrl_c_interrupts_a_render(scene):
    # About a minute of work on 2 cores if it were not interrupted.
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(spp=4096, width=128, height=96)
    assert time.perf_counter() - start < 5.0


def test_adaptive_sampling_stops_converged_pixels_at_batch_boundaries(scene):
    film = scene.render(spp=256, adaptive=(16, 0.2), width=24, height=18, seed=2)
    counts = film.sample_counts()
    assert counts.min() >= 16 and counts.max() <= 256
    assert ((counts % 16 == 0) | (counts == 256)).all()
    assert film.stats["converged_pixels"] == int((counts < 256).sum()) > 0
    again = scene.render(spp=256, adaptive=(16, 0.2), width=24, height=18, seed=2, threads=1)
    assert bits_equal(again, film)
