"""A cluster without a shared disk: the scene and every file it references
travel to the workers through Dask, and the render equals the local one bit
for bit although no worker can see the scene's folder."""

import importlib.util
import os
import shutil

import pytest

import candela
import candela.distributed as dist
from candela.distributed import bundle as scene_bundle
from conftest import REPO, bits_equal

distributed = pytest.importorskip("distributed")

SETTINGS = dict(spp=4, width=32, height=24, seed=3, max_depth=3)


def _textured_scene(folder):
    """scripts/make_textured_gltf.py's scene (glTF + .bin + two PNG
    textures: base colour and normal map) written into ``folder``."""
    spec = importlib.util.spec_from_file_location("make_textured_gltf", REPO / "scripts/make_textured_gltf.py")
    make = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make)
    folder.mkdir(parents=True)
    make.OUT = str(folder)
    make.main()
    return folder / "textured.gltf"


def test_the_bundle_holds_the_scene_and_every_file_it_references(tmp_path):
    scene = _textured_scene(tmp_path / "src")
    b = dist.bundle_scene(scene)
    assert b.scene == "textured.gltf"
    assert sorted(name for name, _ in b.files) == ["albedo.png", "normal.png", "textured.bin", "textured.gltf"]
    assert b.digest == dist.bundle_scene(scene).digest  # named by content
    with pytest.raises(ValueError, match="outside the bundle"):
        scene_bundle._safe("../etc/passwd")


def test_workers_that_cannot_see_the_scene_render_it_bit_for_bit(tmp_path, monkeypatch):
    # The workers' cache is their own folder (as on another machine).
    monkeypatch.setenv("CANDELA_SCENE_CACHE", str(tmp_path / "worker-cache"))
    scene = _textured_scene(tmp_path / "src")
    loaded = candela.load(scene)
    assert not loaded.warnings, loaded.warnings  # the textures were found
    local = loaded.render(**SETTINGS)
    b = dist.bundle_scene(scene)
    shutil.rmtree(scene.parent)  # nobody can read the scene's folder now
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as c:
        with distributed.Client(c) as client:
            client.run(os.chdir, str(elsewhere))
            film = dist.render(b, client, tiles=(2, 2), **SETTINGS)
            cwds = set(client.run(os.getcwd).values())
    assert cwds == {str(elsewhere)}
    assert bits_equal(film, local)
    # Written out once, under its hash, in the workers' cache.
    assert os.listdir(tmp_path / "worker-cache") == [b.digest]


def test_a_path_is_shipped_too(tmp_path, monkeypatch):
    monkeypatch.setenv("CANDELA_SCENE_CACHE", str(tmp_path / "cache"))
    scene = _textured_scene(tmp_path / "src")
    local = candela.load(scene).render(**SETTINGS)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=":0") as c:
        with distributed.Client(c) as client:
            film = dist.render(scene, client, tiles=(2, 1), **SETTINGS)
    assert bits_equal(film, local)
    assert os.listdir(tmp_path / "cache") == [dist.bundle_scene(scene).digest]
