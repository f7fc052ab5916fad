"""Shared fixtures: scene files and the CLI binary.

Scenes: the repository's `scenes/demo.dae` always; the CS184 scenes from
`$CANDELA_SCENES` or `shared/scenes/cs184` beside the repository when present.
"""

import os
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]


def _cs184_dir():
    for d in (os.environ.get("CANDELA_SCENES"), REPO.parent / "shared/scenes/cs184", REPO.parent.parent / "shared/scenes/cs184"):
        if d and pathlib.Path(d, "CBspheres_lambertian.dae").is_file():
            return pathlib.Path(d)
    return None


@pytest.fixture(scope="session")
def demo_path():
    return str(REPO / "scenes" / "demo.dae")


@pytest.fixture(scope="session")
def spheres_path():
    d = _cs184_dir()
    if d is None:
        # A test that needs the corpus fails without it rather than passing.
        pytest.fail("CS184 scenes not found: expected shared/scenes/cs184 beside the repository "
                    "(or set CANDELA_SCENES)")
    return str(d / "CBspheres_lambertian.dae")


@pytest.fixture(scope="session")
def cli_bin():
    """The `candela` binary: $CANDELA_BIN, else target/{release,debug}/candela.
    Missing is a skip on a developer's machine and a failure under CI."""
    for p in (os.environ.get("CANDELA_BIN"), REPO / "target/release/candela", REPO / "target/debug/candela"):
        if p and pathlib.Path(p).is_file():
            return str(p)
    if os.environ.get("CI"):
        pytest.fail("candela binary not built (ci-steps.sh builds it and sets CANDELA_BIN)")
    pytest.skip("candela binary not built (cargo build --release -p candela-cli)")


def bits_equal(a, b):
    """Exact equality of two films' raw sums, float bits included."""
    fa, fb = a.arrays(), b.arrays()
    assert (a.width, a.height, a.origin) == (b.width, b.height, b.origin)
    for k in ("radiance", "lum", "lum_sq"):
        if fa[k].tobytes() != fb[k].tobytes():
            return False
    return fa["count"].tobytes() == fb["count"].tobytes()
