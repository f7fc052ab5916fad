"""``candela.compare`` against an independent NumPy computation of every number
it reports: MSE, pbrt-v4's relMSE, PSNR, the block z-test (from the variance
layers and from the block spread) and the efficiency ratio."""

import math
from statistics import NormalDist

import numpy as np
import pytest

import candela

SIZE = dict(width=36, height=20, max_depth=3)  # 20 rows: the last block row is partial
BLOCK = 8


@pytest.fixture(scope="module")
def scene():
    return candela.demo_scene()


def render(scene, spp, seed):
    return scene.render(spp=spp, seed=seed, **SIZE)


def mean_and_variance(film):
    """Per-pixel mean and variance of the mean, straight from the film's sums
    (n - 1 denominator)."""
    a = film.arrays()
    n = a["count"][..., None].astype(np.float64)
    mean = a["radiance"] / n
    var = (a["radiance_sq"] - a["radiance"] * mean) / (n - 1) / n
    return mean, np.maximum(var, 0.0)


def blocks(image):
    h, w = image.shape[:2]
    for by in range(0, h, BLOCK):
        for bx in range(0, w, BLOCK):
            yield image[by:by + BLOCK, bx:bx + BLOCK].reshape(-1, 3)


def z_test(ma, va, mb, vb, false_alarm=0.01):
    """Block z-scores, whole-image z and the Bonferroni threshold; `va`, `vb`
    are per-pixel variances of the mean, or None for the block spread."""
    def block_stats(m, v):
        out = []
        for i, px in enumerate(blocks(m)):
            k = len(px)
            if v is None:
                var = px.var(axis=0, ddof=1) / k
            else:
                var = list(blocks(v))[i].sum(axis=0) / k**2
            out.append((px.mean(axis=0), var))
        return out
    za = block_stats(ma, va)
    zb = block_stats(mb, vb)
    def z_score(diff, var):
        # The documented convention: equal means give z = 0 even with zero variance (a black block).
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(diff == 0, 0.0, diff / np.sqrt(var))
    z = np.array([z_score(a[0] - b[0], a[1] + b[1]) for a, b in zip(za, zb)])
    n = ma.shape[0] * ma.shape[1]
    if va is None:
        gva = sum(len(px) * px.var(axis=0, ddof=1) for px in blocks(ma)) / n**2
        gvb = sum(len(px) * px.var(axis=0, ddof=1) for px in blocks(mb)) / n**2
    else:
        gva, gvb = va.reshape(-1, 3).sum(axis=0) / n**2, vb.reshape(-1, 3).sum(axis=0) / n**2
    gz = z_score(ma.reshape(-1, 3).mean(axis=0) - mb.reshape(-1, 3).mean(axis=0), gva + gvb)
    tests = 3 * len(z) + 3
    threshold = NormalDist().inv_cdf(1 - false_alarm / tests / 2)
    return np.abs(z).max(), np.abs(gz).max(), threshold, int((np.abs(z) > threshold).sum())


def check_metrics(entry, test, ref):
    err = (test.astype(np.float64) - ref) ** 2
    mse = err.mean()
    assert entry["mse"] == pytest.approx(mse, rel=1e-6)
    assert entry["rel_mse"] == pytest.approx((err / (ref + 0.01) ** 2).mean(), rel=1e-6)
    assert entry["psnr"] == pytest.approx(10 * math.log10(1 / mse), rel=1e-6)


def test_compare_matches_numpy_with_variance_layers(scene, tmp_path):
    fa, fb = render(scene, 16, 1), render(scene, 16, 2)
    fa.save(tmp_path / "a.exr")
    fb.save(tmp_path / "b.exr")
    report = candela.compare(tmp_path / "a.exr", tmp_path / "b.exr", heatmap=tmp_path / "heat.png")
    (entry,) = report["comparisons"]
    (ma, va), (mb, vb) = mean_and_variance(fa), mean_and_variance(fb)
    # The files hold float32 values; compare against the float32 image.
    ma32, mb32 = ma.astype(np.float32), mb.astype(np.float32)
    check_metrics(entry, ma32, mb32.astype(np.float64))
    z = entry["z_test"]
    assert z["variance_source"] == "pixel variance"
    max_z, global_z, threshold, over = z_test(ma32.astype(np.float64), va, mb32.astype(np.float64), vb)
    assert z["max_abs_z"] == pytest.approx(max_z, rel=1e-5)
    assert z["global_abs_z"] == pytest.approx(global_z, rel=1e-5)
    assert z["threshold"] == pytest.approx(threshold, rel=1e-6)
    assert z["tests_over_threshold"] == over
    assert z["blocks"] == 5 * 3
    assert entry["spp"] == {"min": 16, "mean": 16.0, "max": 16}
    assert candela.read_image(tmp_path / "heat.png").shape == (20, 36, 3)


def test_compare_of_arrays_uses_the_block_spread(scene):
    a, b = render(scene, 4, 3).image(), render(scene, 4, 4).image() * 1.05
    report = candela.compare(a, b)
    (entry,) = report["comparisons"]
    check_metrics(entry, a, b.astype(np.float64))
    z = entry["z_test"]
    assert z["variance_source"] == "block spread"
    max_z, global_z, threshold, over = z_test(a.astype(np.float64), None, b.astype(np.float64), None)
    assert z["max_abs_z"] == pytest.approx(max_z, rel=1e-5)
    assert z["global_abs_z"] == pytest.approx(global_z, rel=1e-5)
    assert z["tests_over_threshold"] == over
    assert report["efficiency_ratio"] is None


def test_efficiency_ratio_against_a_reference(scene, tmp_path):
    for name, spp, seed in (("r", 64, 5), ("a", 4, 6), ("b", 16, 7)):
        film = render(scene, spp, seed)
        film.set_wall_time(spp / 100)  # a stand-in time, so the check does not depend on the machine
        film.save(tmp_path / f"{name}.exr")
    report = candela.compare(tmp_path / "a.exr", tmp_path / "b.exr", reference=tmp_path / "r.exr")
    ea, eb = report["comparisons"]
    assert ea["time_seconds"] == pytest.approx(0.04) and eb["time_seconds"] == pytest.approx(0.16)
    eff_a, eff_b = 1 / (ea["rel_mse"] * 0.04), 1 / (eb["rel_mse"] * 0.16)
    assert ea["efficiency"] == pytest.approx(eff_a, rel=1e-6)
    assert report["efficiency_ratio"] == pytest.approx(eff_a / eff_b, rel=1e-6)


def test_bad_input_names_the_file(tmp_path):
    with pytest.raises(OSError, match="missing.exr"):
        candela.compare(tmp_path / "missing.exr", np.zeros((2, 2, 3)))
    with pytest.raises(ValueError, match="a is 2x2 but b is 3x2"):
        candela.compare(np.zeros((2, 2, 3)), np.zeros((2, 3, 3)))
    with pytest.raises(ValueError, match=r"shape \(H, W, 3\)"):
        candela.compare(np.zeros((2, 2)), np.zeros((2, 2, 3)))
