"""Checkpoints of a distributed render: the CLI's checkpoint file (same
format, written by the native ``candela.write_checkpoint``), saved by the
client as finished units are added, so a render whose client dies resumes
without re-rendering them.

The film of a distributed render is built cell by cell, each cell's passes
added in order (``_OrderedMerge``); a checkpoint holds that film, so every
pixel's sample count tells how many of its cell's passes are in it, and a
resumed render submits only the units that are not. Adding the remaining
parts to the checkpoint's film in the same order gives the uninterrupted
render's film bit for bit. A part that arrived before an earlier pass of its
cell waits in memory until that pass arrives; it is not in a checkpoint
written meanwhile and is rendered again after a crash.
"""

from __future__ import annotations

import os
import time
from typing import Any, Dict, List, Optional, Sequence

import candela

#: The front-end name distributed renders record in their checkpoints.
FRONT = "dask"


class Checkpointer:
    """Saves the film of a distributed render every ``every`` seconds (and
    when asked), and reads back the checkpoint it continues."""

    def __init__(self, path: str, every: float, scene: "candela.Scene", settings: Dict[str, Any],
                 front: Dict[str, Any]) -> None:
        self.path = path
        self.every = every
        self.settings = settings
        self.front = dict(front, front=FRONT)
        # Hashing reads the scene's textures: once per render, not per save.
        self.scene_hash = scene.content_hash(**{k: v for k, v in settings.items() if k != "cell"})
        self.before = 0.0
        self.last = time.monotonic()

    def resume(self) -> Optional["candela.Film"]:
        """The film of the checkpoint at ``path`` if there is one (refused,
        with ValueError naming the difference, if it is of another render)."""
        if not os.path.exists(self.path):
            return None
        ck = candela.read_checkpoint(self.path, scene_hash=self.scene_hash, settings=self.settings)
        front = ck["front"]
        if front.get("front") != FRONT:
            raise ValueError(f"{self.path}: a checkpoint of a {front.get('front')!r} render, not a distributed one")
        for key in ("tiles", "passes"):
            if front.get(key) != self.front.get(key):
                raise ValueError(f"{self.path}: the checkpoint was rendered with {key}={front.get(key)}, "
                                 f"this render asks for {key}={self.front.get(key)}")
        self.before = ck["elapsed_s"]
        return ck["film"]

    def save(self, film: "candela.Film", elapsed: float) -> None:
        """Writes ``film`` (atomically), the render having run ``elapsed``
        seconds in this process."""
        candela.write_checkpoint(self.path, film, settings=self.settings, scene_hash=self.scene_hash,
                                 front=self.front, elapsed_s=self.before + elapsed)
        self.last = time.monotonic()

    def maybe_save(self, film: "candela.Film", elapsed: float) -> None:
        """Saves if the last save is ``every`` seconds ago."""
        if time.monotonic() - self.last >= self.every:
            self.save(film, elapsed)


def passes_done(film: "candela.Film", cells: Sequence, pass_ends: List[int]) -> List[int]:
    """For each cell ``(x, y, w, h)``, how many passes (ending at the sample
    counts ``pass_ends``) the film holds; ValueError if a cell's pixels
    disagree or hold a count that is no pass boundary."""
    counts = film.sample_counts()
    done = []
    for (x, y, w, h) in cells:
        block = counts[y:y + h, x:x + w]
        n = int(block.flat[0])
        if (block != n).any() or (n != 0 and n not in pass_ends):
            raise ValueError(f"the checkpoint's cell at ({x}, {y}) is not a whole number of passes "
                             f"(sample counts {int(block.min())}..{int(block.max())})")
        done.append(0 if n == 0 else pass_ends.index(n) + 1)
    return done


def resume_args(path: str) -> Dict[str, Any]:
    """What ``render`` needs to continue the distributed render of the
    checkpoint at ``path``: ``scene_path``, ``tiles``, ``passes``, ``strict``
    and the settings, with ``checkpoint=path``; plus ``output``, the file the
    command line was to write (or None)."""
    ck = candela.read_checkpoint(path)
    front = ck["front"]
    if front.get("front") != FRONT:
        raise ValueError(f"{path}: a checkpoint of a {front.get('front')!r} render: resume it with `candela resume`")
    settings = dict(ck["settings"], checkpoint=os.fspath(path))
    settings.pop("cell", None)
    return dict(scene_path=front["scene"], tiles=tuple(front["tiles"]), passes=front["passes"],
                strict=front["strict"], output=front.get("output"), address=front.get("address"),
                settings=settings)
