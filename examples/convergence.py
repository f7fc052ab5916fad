"""Convergence of Candela's path tracer, from Python.

Renders a scene at 1, 2, 4, ... samples per pixel, measures the error against
a high-sample reference, and plots error vs spp (Monte Carlo error falls as
1/sqrt(spp), so its log-log slope should be -1/2). Then renders with adaptive
sampling and shows where the samples went (CS184's sample-rate image).

    pip install ./crates/candela-py matplotlib
    python examples/convergence.py [scene.dae] [--out convergence.png]

Without matplotlib it prints the table and skips the plots.
"""

import argparse
import pathlib

import numpy as np

import candela

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # plots are optional
    plt = None

WIDTH, HEIGHT = 96, 72
REFERENCE_SPP = 1024


def rmse(image, reference):
    return float(np.sqrt(np.mean((image - reference) ** 2)))


def rel_mse(image, reference):
    """pbrt-v4's relMSE, from ``candela.compare`` (the one definition): mean of
    (x - ref)^2 / (ref + 0.01)^2, which does not let bright pixels rule."""
    return candela.compare(image, reference)["comparisons"][0]["rel_mse"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene", nargs="?", help="scene file (default: the built-in demo scene)")
    p.add_argument("--out", default="convergence.png", help="figure to write")
    a = p.parse_args()
    scene = candela.load(a.scene) if a.scene else candela.demo_scene()
    for line in scene.warnings + scene.notes:
        print("note:", line)
    # The demo scene is framed by its own camera (CS184's orbit rule sees a wall).
    size = dict(width=WIDTH, height=HEIGHT, max_depth=5, camera="cs184" if a.scene else "file")

    reference = scene.render(spp=REFERENCE_SPP, seed=1000, **size)
    print(f"reference: {REFERENCE_SPP} spp, {reference.stats['mrays_per_s']:.1f} Mrays/s")
    ref = reference.image()

    spps = [2**k for k in range(0, 8)]
    rows = []
    for spp in spps:
        film = scene.render(spp=spp, seed=1, **size)
        img = film.image()
        rows.append((spp, rmse(img, ref), rel_mse(img, ref), film.stats["wall_time_s"]))
    print(f"{'spp':>5} {'RMSE':>10} {'relMSE':>10} {'time s':>8}")
    for spp, e, r, t in rows:
        print(f"{spp:>5} {e:>10.5f} {r:>10.6f} {t:>8.3f}")
    slope = np.polyfit(np.log(spps), np.log([r[1] for r in rows]), 1)[0]
    print(f"log-log slope of RMSE vs spp: {slope:.2f} (Monte Carlo: -0.5)")

    adaptive = scene.render(spp=512, adaptive=(32, 0.05), seed=1, **size)
    counts = adaptive.sample_counts()
    s = adaptive.stats
    print(f"adaptive: mean {counts.mean():.0f} spp (of 512), {s['converged_pixels']} pixels stopped early")

    if plt is None:
        print("matplotlib is not installed: no plots")
        return
    fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(14, 4))
    e = np.array([r[1] for r in rows])
    ax0.loglog(spps, e, "o-", label="RMSE")
    ax0.loglog(spps, e[0] / np.sqrt(spps), "--", label="1/sqrt(spp)")
    ax0.set_xlabel("samples per pixel")
    ax0.set_ylabel("error vs reference")
    ax0.legend()
    ax0.set_title("convergence")
    ax1.imshow(np.clip(adaptive.image() ** (1 / 2.2), 0, 1))
    ax1.set_title("adaptive render")
    ax1.axis("off")
    rate = ax2.imshow(counts / 512, cmap="jet", vmin=0, vmax=1)
    ax2.set_title("sample rate (fraction of 512 spp)")
    ax2.axis("off")
    fig.colorbar(rate, ax=ax2)
    fig.tight_layout()
    fig.savefig(a.out, dpi=100)
    print(f"wrote {pathlib.Path(a.out).resolve()}")


if __name__ == "__main__":
    main()
