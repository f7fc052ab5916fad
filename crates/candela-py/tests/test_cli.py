"""A Python render and a CLI render of the same options are the same image."""

import subprocess

import numpy as np

import candela


def test_python_render_equals_cli_render(cli_bin, spheres_path, tmp_path):
    args = ["-s", "8", "-m", "3", "-l", "2", "-r", "48", "36", "--seed", "11", "-t", "2", "-q"]
    for ext in ("exr", "png"):
        subprocess.run([cli_bin, *args, "-f", str(tmp_path / f"cli.{ext}"), spheres_path], check=True)
    film = candela.load(spheres_path).render(spp=8, max_depth=3, light_samples=2, width=48, height=36, seed=11)
    film.save(tmp_path / "py.exr")
    film.save(tmp_path / "py.png")
    cli = candela.read_image(tmp_path / "cli.exr")
    assert cli.shape == (36, 48, 3) and cli.max() > 0
    np.testing.assert_array_equal(film.image(), cli)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()


def test_python_normals_and_direct_match_cli(cli_bin, spheres_path, tmp_path):
    scene = candela.load(spheres_path)
    for flags, kwargs in [(["--normals"], dict(integrator="normals")),
                          (["--direct-only", "-H"], dict(integrator="direct", lighting="hemisphere"))]:
        out = tmp_path / "cli.exr"
        subprocess.run([cli_bin, *flags, "-s", "4", "-r", "32", "24", "-q", "-f", str(out), spheres_path], check=True)
        film = scene.render(spp=4, width=32, height=24, **kwargs)
        np.testing.assert_array_equal(film.image(), candela.read_image(out))
