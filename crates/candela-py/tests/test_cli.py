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


def test_cli_dask_front_equals_local_cli_render(cli_bin, spheres_path, tmp_path):
    """`candela --dask local:2` hands the render to Dask and writes the same image."""
    args = ["-s", "4", "-m", "2", "-r", "40", "30", "--seed", "3", "-q"]
    local, distributed = tmp_path / "local.exr", tmp_path / "dask.exr"
    subprocess.run([cli_bin, *args, "-t", "1", "-f", str(local), spheres_path], check=True)
    subprocess.run([cli_bin, *args, "--dask", "local:2", "--tiles", "2", "2", "-f", str(distributed), spheres_path],
                   check=True)
    np.testing.assert_array_equal(candela.read_image(local), candela.read_image(distributed))


def test_cli_dask_front_refuses_flags_it_cannot_honour(cli_bin, spheres_path, tmp_path):
    done = subprocess.run([cli_bin, "--dask", "local:2", "-a", "64", "0.05", "-f", str(tmp_path / "x.png"),
                           spheres_path], capture_output=True, text=True)
    assert done.returncode == 2
    assert "-a" in done.stderr and not (tmp_path / "x.png").exists()


def test_python_lens_and_environment_match_cli(cli_bin, spheres_path, tmp_path):
    out = tmp_path / "cli.exr"
    subprocess.run([cli_bin, "-s", "4", "-r", "32", "24", "-b", "0.1", "-d", "4", "-e", "sky", "-q", "-f", str(out),
                    spheres_path], check=True)
    film = candela.load(spheres_path).render(spp=4, width=32, height=24, aperture=0.1, focal_distance=4.0,
                                             env_map="sky")
    np.testing.assert_array_equal(film.image(), candela.read_image(out))
