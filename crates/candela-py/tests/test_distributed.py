"""Distributed rendering on a Dask LocalCluster gives the local film, bit for
bit, even when units fail or a worker dies."""

import os
import sys

import pytest

import candela
import candela.distributed as dist
from conftest import bits_equal

distributed = pytest.importorskip("distributed")
import cloudpickle  # noqa: E402  (a dependency of distributed)

import faults  # noqa: E402

cloudpickle.register_pickle_by_value(sys.modules["faults"])

SETTINGS = dict(spp=6, width=36, height=28, seed=5, max_depth=4)


@pytest.fixture(scope="module")
def threads_client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0") as c:
        with distributed.Client(c) as client:
            yield client


def test_plan_covers_every_pixel_and_sample_once():
    units = dist.plan(37, 29, 7, tiles=(3, 4), passes=3)
    assert len(units) == 36
    hits = {}
    for u in units:
        x0, y0, w, h = u.cell
        for y in range(y0, y0 + h):
            for x in range(x0, x0 + w):
                for s in range(*u.sample_range):
                    hits[(x, y, s)] = hits.get((x, y, s), 0) + 1
    assert len(hits) == 37 * 29 * 7 and set(hits.values()) == {1}


@pytest.mark.parametrize("passes", [1, 3])
def test_distributed_equals_local(threads_client, spheres_path, passes):
    local = candela.load(spheres_path).render(passes=passes, **SETTINGS)
    film = dist.render(spheres_path, threads_client, tiles=(3, 2), passes=passes, **SETTINGS)
    assert film.full_size == (36, 28)
    assert bits_equal(film, local)
    assert film.stats["samples"] == local.stats["samples"]


def test_a_unit_that_raises_once_is_retried(threads_client, spheres_path, tmp_path):
    marker = tmp_path / "failed"
    fn = faults.FailOnce(marker, (12, 0, 12, 14), (0, 3), "raise")
    film = dist.render(spheres_path, threads_client, tiles=(3, 2), passes=2, retries=2, unit_fn=fn, **SETTINGS)
    assert marker.exists(), "the fault was not injected"
    assert bits_equal(film, candela.load(spheres_path).render(passes=2, **SETTINGS))


def test_without_retries_the_failure_surfaces(threads_client, spheres_path, tmp_path):
    fn = faults.FailOnce(tmp_path / "failed", (0, 0, 18, 28), (0, 6), "raise")
    with pytest.raises(RuntimeError, match="injected failure"):
        dist.render(spheres_path, threads_client, tiles=(2, 1), retries=0, unit_fn=fn, **SETTINGS)


def test_a_worker_killed_mid_render_loses_nothing(spheres_path, tmp_path):
    marker = tmp_path / "killed"
    fn = faults.FailOnce(marker, (18, 14, 18, 14), (3, 6), "kill")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as c:
        with distributed.Client(c) as client:
            film = dist.render(spheres_path, client, tiles=(2, 2), passes=2, unit_fn=fn, **SETTINGS)
    assert marker.exists(), "no worker was killed"
    assert bits_equal(film, candela.load(spheres_path).render(passes=2, **SETTINGS))


def test_parts_arriving_in_any_order_are_added_in_pass_order(spheres_path):
    scene = candela.load(spheres_path)
    units = dist.plan(36, 28, 6, tiles=(2, 2), passes=3)
    parts = [(u, scene.render(cell=u.cell, sample_range=u.sample_range, **SETTINGS)) for u in units]
    merger = dist._OrderedMerge(36, 28, 4, 3)
    for u, part in reversed(parts):
        merger.add(u, part)
    merger.add(*parts[0])  # a rerun unit's duplicate result is ignored
    assert bits_equal(merger.result(), scene.render(passes=3, **SETTINGS))
    incomplete = dist._OrderedMerge(36, 28, 4, 3)
    for u, part in parts[1:]:
        incomplete.add(u, part)
    with pytest.raises(RuntimeError, match="missing"):
        incomplete.result()
