"""Checkpoints of distributed renders: a render whose client process is
killed resumes from its checkpoint, re-rendering only the units it lacks, to
the uninterrupted film bit for bit; a checkpoint of another render is
refused by name."""

import json
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import candela
import candela.distributed as dist
from conftest import bits_equal

distributed = pytest.importorskip("distributed")

SETTINGS = dict(spp=48, width=48, height=36, seed=9, max_depth=4)
TILES, PASSES = (4, 4), 2


def _wait_for_units(ck, proc, timeout=120.0):
    """Polls until the checkpoint holds some finished units (no fixed sleep)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        assert proc.poll() is None, "the render ended before a checkpoint with units was written"
        if ck.exists():
            try:
                counts = candela.read_checkpoint(ck)["film"].sample_counts()
            except ValueError:  # replaced while read: try again
                counts = None
            if counts is not None and counts.any():
                return counts
        time.sleep(0.02)
    pytest.fail("no checkpoint after 120 s")


@pytest.fixture(scope="module")
def cluster():
    """Two worker threads in this process, reachable over TCP by client
    processes: the cluster outlives a client that is killed."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp://",
                                  dashboard_address=":0") as c:
        with distributed.Client(c) as client:
            yield client


def test_a_killed_client_resumes_to_the_uninterrupted_film(cluster, spheres_path, tmp_path):
    ck, out = tmp_path / "ck", tmp_path / "out.exr"
    address = cluster.scheduler.address
    settings = dict(SETTINGS, checkpoint=str(ck), checkpoint_every=0)
    cmd = [sys.executable, "-m", "candela.distributed", spheres_path, "--dask", address, "-q",
           "--tiles", *map(str, TILES), "--passes", str(PASSES), "--settings", json.dumps(settings), "-f", str(out)]
    proc = subprocess.Popen(cmd, stderr=subprocess.PIPE)
    try:
        _wait_for_units(ck, proc)
    finally:
        proc.kill()  # SIGKILL: the client dies without a word
        proc.wait()
    assert proc.returncode == -signal.SIGKILL, "killed, not finished"
    assert not out.exists()
    partial = candela.read_checkpoint(ck)["film"].sample_counts()
    full = SETTINGS["spp"] * SETTINGS["width"] * SETTINGS["height"]
    assert 0 < int(partial.sum()) < full, "the checkpoint holds some units, not all"

    # `candela resume` hands a distributed checkpoint to this same command.
    resumed = subprocess.run([sys.executable, "-m", "candela.distributed", "--resume", str(ck), "--dask", address],
                             capture_output=True, text=True, timeout=300)
    assert resumed.returncode == 0, resumed.stderr
    # Only the missing units ran: the progress line counts them.
    units = TILES[0] * TILES[1] * PASSES
    done_before = sum(1 for _ in _finished_units(partial))
    ran = max(int(n) for n in re.findall(r"(\d+)/\d+ units", resumed.stderr))
    assert ran == units - done_before, resumed.stderr

    local = candela.load(spheres_path).render(passes=PASSES, **SETTINGS)
    final = candela.read_checkpoint(ck)["film"]
    assert bits_equal(final, local)
    assert np.array_equal(candela.read_image(out), local.image()), "the output image is the local render's"


def _finished_units(counts):
    """(cell, pass) pairs a film's sample counts show as done."""
    units = dist.plan(SETTINGS["width"], SETTINGS["height"], SETTINGS["spp"], TILES, PASSES)
    for u in units:
        x, y, w, h = u.cell
        if counts[y, x] >= u.sample_range[1]:
            yield u


def test_a_checkpoint_of_another_render_is_refused(cluster, spheres_path, tmp_path):
    ck = tmp_path / "ck"
    small = dict(SETTINGS, spp=2, checkpoint=str(ck))
    first = dist.render(spheres_path, cluster, tiles=(2, 2), **small)
    # The same render again continues the finished checkpoint: nothing to do.
    again = dist.render(spheres_path, cluster, tiles=(2, 2), on_unit=lambda u, f: pytest.fail("re-rendered"),
                        **small)
    assert bits_equal(again, first)
    with pytest.raises(ValueError, match="seed = 9 in the checkpoint, 10 here"):
        dist.render(spheres_path, cluster, tiles=(2, 2), **dict(small, seed=10))
    with pytest.raises(ValueError, match="tiles"):
        dist.render(spheres_path, cluster, tiles=(1, 2), **small)
    ck.write_bytes(ck.read_bytes()[:100])
    with pytest.raises(ValueError, match="truncated"):
        dist.render(spheres_path, cluster, tiles=(2, 2), **small)


def test_scene_render_writes_and_continues_checkpoints(spheres_path, tmp_path):
    ck = tmp_path / "ck"
    scene = candela.load(spheres_path)
    small = dict(SETTINGS, spp=4)
    plain = scene.render(**small)
    film = scene.render(checkpoint=ck, **small)
    assert bits_equal(film, plain)
    assert bits_equal(candela.read_checkpoint(ck)["film"], plain)
    again = scene.render(checkpoint=ck, **small)  # finished: continues with nothing left to do
    assert bits_equal(again, plain) and again.stats["samples"] == 0
    with pytest.raises(ValueError, match="seed = 9 in the checkpoint, 10 here"):
        scene.render(checkpoint=ck, **dict(small, seed=10))
    with pytest.raises(ValueError, match="sample_range or passes"):
        scene.render(checkpoint=ck, passes=2, **small)


def test_candela_resume_hands_a_distributed_checkpoint_to_the_dask_front(cli_bin, cluster, spheres_path, tmp_path):
    ck, out = tmp_path / "ck", tmp_path / "out.exr"
    small = dict(SETTINGS, spp=4, checkpoint=str(ck))
    half = dist.plan(SETTINGS["width"], SETTINGS["height"], 4, (2, 2), 2)[:4]  # pass 0 of every cell
    # A checkpoint with only the first pass, as a client killed half-way leaves.
    scene = candela.load(spheres_path)
    first = candela.Film.empty(SETTINGS["width"], SETTINGS["height"])
    for u in half:
        first.add(scene.render(cell=u.cell, sample_range=u.sample_range, **dict(SETTINGS, spp=4)))
    resolved = scene.settings(**dict(small, threads=1))
    resolved.pop("cell")
    front = {"front": "dask", "scene": spheres_path, "tiles": [2, 2], "passes": 2, "strict": False,
             "output": str(out), "address": cluster.scheduler.address}
    candela.write_checkpoint(ck, first, settings=resolved, scene_hash=scene.content_hash(**resolved), front=front,
                             elapsed_s=1.0)
    env = dict(os.environ, CANDELA_PYTHON=sys.executable)
    # How a CLI render runs is the CLI's; the cluster runs this one as saved.
    for flag in (["-s", "8"], ["-t", "1"], ["--time", "5"], ["--checkpoint-every", "1"]):
        refused = subprocess.run([cli_bin, "resume", str(ck), *flag], env=env, capture_output=True, text=True,
                                 timeout=60)
        assert refused.returncode == 2, refused.stderr
        assert len(refused.stderr.strip().splitlines()) == 1, refused.stderr
        assert f"{flag[0]} applies to a checkpoint rendered by `candela`" in refused.stderr, refused.stderr
    done = subprocess.run([cli_bin, "resume", str(ck)], env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "4/8 units" in done.stderr and "5/8 units" not in done.stderr, done.stderr
    local = scene.render(passes=2, **dict(SETTINGS, spp=4))
    assert bits_equal(candela.read_checkpoint(ck)["film"], local)
    assert np.array_equal(candela.read_image(out), local.image())
