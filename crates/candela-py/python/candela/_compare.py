"""``candela.compare``: the report of ``candela compare``, from the same Rust code."""

import json
import os
from typing import Any, Dict, Optional, Union

import numpy as np

from candela._candela import compare_json

ImageLike = Union[str, "os.PathLike[str]", np.ndarray]


def _arg(image: ImageLike, name: str):
    if isinstance(image, (str, os.PathLike)):
        return os.fspath(image)
    array = np.ascontiguousarray(image, dtype=np.float32)
    if array.ndim != 3 or array.shape[2] != 3:
        raise ValueError(f"{name}: expected an array of shape (H, W, 3), got {array.shape}")
    return (array, name)


def compare(
    a: ImageLike,
    b: ImageLike,
    reference: Optional[ImageLike] = None,
    *,
    block: int = 8,
    false_alarm: float = 0.01,
    heatmap: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Dict[str, Any]:
    """Compares renders as ``candela compare --json`` does and returns its report.

    ``a``, ``b`` and ``reference`` are file paths (.exr, .png) or arrays of shape
    (H, W, 3) of linear RGB. Without a reference, ``a`` is measured against ``b``;
    with one, each of ``a`` and ``b`` against it, with their efficiencies
    1 / (relMSE x time) and the ratio when both files carry render time and sample
    counts. Each entry of ``report["comparisons"]`` has ``mse``, ``rel_mse`` (pbrt-v4's,
    epsilon 0.01), ``psnr`` (peak 1; None when infinite) and ``z_test`` (the block
    z-test: per-pixel variance from the files' variance layers when both have one,
    else from the spread of each block). ``heatmap`` writes a PNG of a's per-pixel
    relative squared error.
    """
    text = compare_json(
        _arg(a, "a"),
        _arg(b, "b"),
        None if reference is None else _arg(reference, "reference"),
        block=block,
        false_alarm=false_alarm,
        heatmap=None if heatmap is None else os.fspath(heatmap),
    )
    return json.loads(text)
