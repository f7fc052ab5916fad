"""Denoising from Python: ``Film.denoise()`` and ``Film.save(denoise=True)``
through Intel Open Image Denoise (the ``pyoidn`` wheel ships it). Without
the library these tests skip with the reason, unless CANDELA_REQUIRE_OIDN=1
(set by ci-steps.sh, which installs it): then they fail."""

import os
import subprocess
import sys

import numpy as np
import pytest

import candela


@pytest.fixture(scope="module")
def oidn():
    try:
        return candela.denoiser_library()
    except candela.DenoiseError as e:
        if os.environ.get("CANDELA_REQUIRE_OIDN") == "1":
            pytest.fail(f"CANDELA_REQUIRE_OIDN=1 but: {e}")
        pytest.skip(str(e))


def _rel_mse(a, b):
    return float(np.mean((a - b) ** 2 / (b * b + 1e-2)))


def test_denoise_brings_a_noisy_render_closer_to_the_reference(oidn, demo_path):
    scene = candela.load(demo_path)
    kw = dict(width=40, height=30, max_depth=5)
    reference = scene.render(spp=256, seed=1, **kw).image()
    noisy = scene.render(spp=4, seed=2, **kw)
    denoised = noisy.denoise()
    assert denoised.shape == (30, 40, 3) and denoised.dtype == np.float32
    before, after = _rel_mse(noisy.image(), reference), _rel_mse(denoised, reference)
    # An unchanged image gives `before`, a black one about 1 per lit pixel.
    assert after < before / 3, (before, after)


def test_save_writes_the_denoised_image_beside_the_raw_one(oidn, tmp_path):
    film = candela.demo_scene().render(spp=2, width=24, height=18)
    film.save(tmp_path / "out.exr", denoise=True)
    raw = candela.read_image(tmp_path / "out.exr")
    den = candela.read_image(tmp_path / "out.denoised.exr")
    assert np.array_equal(raw, film.image())
    assert np.array_equal(den, film.denoise())


def test_a_missing_library_is_a_clear_error_and_nothing_else_breaks(tmp_path):
    # In a fresh interpreter: the library, once loaded, stays for the process.
    code = (
        "import candela, sys\n"
        "film = candela.demo_scene().render(spp=1, width=8, height=6)\n"
        f"film.save({str(tmp_path / 'raw.png')!r})\n"
        "try:\n"
        f"    film.save({str(tmp_path / 'x.png')!r}, denoise=True)\n"
        "except candela.DenoiseError as e:\n"
        "    print(e)\n"
        "    sys.exit(3)\n"
    )
    env = dict(os.environ, CANDELA_OIDN_LIB=str(tmp_path / "nowhere.so"))
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert run.returncode == 3, run.stderr
    assert run.stdout.startswith("CANDELA_OIDN_LIB="), run.stdout
    assert (tmp_path / "raw.png").is_file()
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "x.denoised.png").exists()
