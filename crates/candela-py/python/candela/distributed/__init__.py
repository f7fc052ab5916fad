"""Rendering one image on a Dask cluster.

The image is cut into work units, each a pixel rectangle (a *cell*) times a
range of sample indices (a *pass*) of one seed. Every sample is a pure
function of (seed, pixel, sample index), so a unit renders the same sums on
any worker, and a unit that is lost (an exception, a killed worker) is simply
run again by Dask (``retries``). The parts are added into the film in a fixed
order -- for each cell, its passes in order -- whatever order they arrive in,
so the result is bit for bit the film of ``scene.render(passes=passes, ...)``
on one machine (and of a plain ``scene.render(...)`` when ``passes=1``).

The scene travels as a bundle of its files (``candela.distributed.bundle``):
scattered once through Dask and written out once per worker machine under
its content hash, so workers need no shared disk and never read the
client's paths. (``ship_scene=False`` sends only the path instead, for
clusters that share one.) Besides it, only the settings and the returned
sums travel; each worker process loads and builds the scene once.

With the ``checkpoint`` setting the client saves the film as units come back
(every ``checkpoint_every`` seconds, and at the end), in the CLI's checkpoint
format; a render given an existing checkpoint of the same scene and settings
submits only the units it lacks (``candela.distributed.checkpoint``), and
``python -m candela.distributed --resume PATH`` continues one.
"""

from __future__ import annotations

import os
import time
import uuid
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import candela
from candela.distributed.bundle import SceneBundle, bundle_scene, env_map_path, scene_path
from candela.distributed.checkpoint import Checkpointer, passes_done, resume_args

__all__ = ["SceneBundle", "SettingsRefused", "UNSUPPORTED", "WorkUnit", "bundle_scene", "plan", "render",
           "render_unit", "resume"]

#: Settings that decide which pixels and samples a unit renders; the planner
#: owns them.
_PLANNED = ("cell", "sample_range", "passes")

#: Settings the distributed render cannot honour yet, with the CLI flag that
#: spells each: a unit's time budget or adaptive rule would see only its own
#: part of a pixel's samples.
UNSUPPORTED = {"time": "--time", "adaptive": "-a"}


class SettingsRefused(ValueError):
    """The distributed render cannot honour a setting it was given."""


@dataclass(frozen=True)
class WorkUnit:
    """One task: the pixels ``cell = (x, y, width, height)`` and the sample
    indices ``sample_range = (start, end)`` of each of them."""

    cell_index: int
    pass_index: int
    cell: Tuple[int, int, int, int]
    sample_range: Tuple[int, int]


def _split(n: int, parts: int) -> List[Tuple[int, int]]:
    """``0..n`` cut into ``parts`` consecutive ranges whose lengths differ by
    at most one (the same rule as the native ``passes`` split)."""
    return [(n * k // parts, n * (k + 1) // parts) for k in range(parts)]


def plan(
    width: int,
    height: int,
    spp: int,
    tiles: Union[int, Tuple[int, int]] = 4,
    passes: int = 1,
) -> List[WorkUnit]:
    """The work units of a ``width`` x ``height`` render at ``spp``.

    ``tiles`` is the grid of cells: ``(nx, ny)``, or ``n`` for ``n`` x ``n``;
    ``passes`` cuts each pixel's ``spp`` samples into that many ranges.
    Units are listed pass by pass, so early passes of every cell come first
    and a progressive consumer sees the whole image early.
    """
    nx, ny = (tiles, tiles) if isinstance(tiles, int) else tiles
    if not (1 <= nx <= width and 1 <= ny <= height):
        raise ValueError(f"tiles={tiles!r}: expected 1..{width} x 1..{height} cells")
    if not 1 <= passes <= spp:
        raise ValueError(f"passes={passes}: expected 1..spp ({spp})")
    cells = [
        (x0, y0, x1 - x0, y1 - y0)
        for (y0, y1) in _split(height, ny)
        for (x0, x1) in _split(width, nx)
    ]
    return [
        WorkUnit(c, p, cell, samples)
        for p, samples in enumerate(_split(spp, passes))
        for c, cell in enumerate(cells)
    ]


_scenes: Dict[Tuple[str, bool, int, int], "candela.Scene"] = {}


def _scene(path: str, strict: bool) -> "candela.Scene":
    """The scene at ``path``, loaded once per process (and reloaded if the
    file changes); the loaded scene also keeps its built BVH between units."""
    st = os.stat(path)
    key = (path, strict, st.st_mtime_ns, st.st_size)
    scene = _scenes.get(key)
    if scene is None:
        _scenes.clear()
        scene = _scenes[key] = candela.load(path, strict=strict)
    return scene


def render_unit(
    scene: Union[str, SceneBundle],
    strict: bool,
    settings: Dict[str, Any],
    cell: Tuple[int, int, int, int],
    sample_range: Tuple[int, int],
) -> "candela.Film":
    """Renders one work unit on this process; what a Dask task runs.
    ``scene`` is a path this process can read, or a bundle (written out
    into this machine's cache on first use)."""
    if isinstance(scene, SceneBundle):
        env = env_map_path(scene)
        if env is not None:
            settings = dict(settings, env_map=env)
        scene = scene_path(scene)
    return _scene(scene, strict).render(cell=cell, sample_range=sample_range, **settings)


UnitFn = Callable[
    [Union[str, SceneBundle], bool, Dict[str, Any], Tuple[int, int, int, int], Tuple[int, int]], "candela.Film"
]


def render(
    scene: Union[str, "os.PathLike[str]", SceneBundle],
    client: Any,
    *,
    tiles: Union[int, Tuple[int, int]] = 4,
    passes: int = 1,
    retries: int = 3,
    strict: bool = False,
    ship_scene: bool = True,
    unit_fn: Optional[UnitFn] = None,
    on_unit: Optional[Callable[[WorkUnit, "candela.Film"], None]] = None,
    record: Optional[Dict[str, Any]] = None,
    **settings: Any,
) -> "candela.Film":
    """Renders ``scene`` (a path, or a ``bundle_scene`` bundle) on the Dask
    ``client``'s cluster. The scene's files are shipped to the workers
    (see the module documentation) unless ``ship_scene=False``, which sends
    the path and needs it readable on every worker.

    ``settings`` are those of ``Scene.render`` (``spp``, ``seed``, ``width``,
    ``height``, ``max_depth``, ...: ``candela.settings_help()``); ``threads``
    is per unit and defaults to 1, since Dask already runs one unit per
    worker thread. The settings travel to the workers as the settings' JSON
    (the one wire format of every front end). Returns the merged
    film, equal bit for bit to ``candela.load(scene).render(passes=passes,
    **settings)``. ``retries`` is how often Dask reruns a unit that raised;
    units lost with a dead worker are rerun by the scheduler in any case.
    ``unit_fn`` replaces ``render_unit`` (for tests that inject faults);
    ``on_unit(unit, film)`` is called as each part is added (progress).
    With ``checkpoint=PATH`` the film is saved there as parts are added
    (``checkpoint_every`` seconds apart, and at the end or on an error), and
    an existing checkpoint of the same render is continued (one of another
    render raises ValueError naming the difference); ``record`` adds fields
    to the checkpoint's record (the command line's output path).
    """
    for name in _PLANNED:
        if name in settings:
            raise SettingsRefused(f"{name}= is chosen by the planner (use tiles= and passes=)")
    refused = [f"{k} ({UNSUPPORTED[k]})" for k in UNSUPPORTED if settings.get(k) not in (None, False)]
    if refused:
        raise SettingsRefused(f"the distributed render does not support {', '.join(refused)} yet")
    settings.setdefault("threads", 1)
    if isinstance(scene, SceneBundle) or ship_scene:
        bundle = scene if isinstance(scene, SceneBundle) else bundle_scene(scene, strict, settings.get("env_map"))
        path = scene_path(bundle)  # this machine's copy, for the settings
        # A copy on every worker, so that one dying loses no scene; a fresh
        # key per render (hash=False), since a content key may still be
        # being released from a previous render of the same scene.
        source: Any = client.scatter(bundle, broadcast=True, hash=False)
    else:
        path = source = os.path.abspath(os.fspath(scene))
    # Every setting resolved here, once (defaults < the scene's suggestions
    # < the caller's), so that every unit renders the same settings.
    scene = _scene(path, strict)
    settings = scene.settings(**settings)
    settings.pop("cell")  # each unit is given its own
    width, height, spp = settings["width"], settings["height"], settings["spp"]
    units = plan(width, height, spp, tiles, passes)
    nx, ny = (tiles, tiles) if isinstance(tiles, int) else tiles
    saver = None
    if settings.get("checkpoint") is not None:
        front = dict(record or {}, scene=path, tiles=[nx, ny], passes=passes, strict=strict)
        saver = Checkpointer(os.fspath(settings["checkpoint"]), settings["checkpoint_every"], scene, settings, front)
    unit_settings = dict(settings, checkpoint=None)  # workers write no checkpoints
    merger = _OrderedMerge(width, height, len(units) // passes, passes)
    resumed = saver.resume() if saver is not None else None
    if resumed is not None:
        merger.start_from(resumed, units)
        units = [u for u in units if u.pass_index >= merger.next_pass.get(u.cell_index, 0)]
    fn = unit_fn or render_unit
    run = uuid.uuid4().hex[:12]
    start = time.perf_counter()
    futures = [
        client.submit(
            fn, source, strict, unit_settings, u.cell, u.sample_range,
            key=f"candela-unit-{run}-{i}", retries=retries, pure=False,
        )
        for i, u in enumerate(units)
    ]
    by_key = {f.key: u for f, u in zip(futures, units)}
    from distributed import as_completed

    try:
        for future, part in as_completed(futures, with_results=True):
            unit = by_key[future.key]
            merger.add(unit, part)
            if saver is not None:
                saver.maybe_save(merger.film, time.perf_counter() - start)
            if on_unit is not None:
                on_unit(unit, part)
    finally:
        client.cancel([f for f in futures if not f.done()])
        if saver is not None:
            saver.save(merger.film, time.perf_counter() - start)
    film = merger.result()
    film.set_wall_time(time.perf_counter() - start)
    return film


class _OrderedMerge:
    """Adds parts into one film in a fixed order -- per cell, pass 0, 1, ...
    -- whatever order they arrive in, so the sums are reproducible to the
    last bit. A part that arrives early waits in ``pending``."""

    def __init__(self, width: int, height: int, cells: int, passes: int) -> None:
        self.film = candela.Film.empty(width, height)
        self.cells = cells
        self.passes = passes
        self.next_pass: Dict[int, int] = {}
        self.pending: Dict[Tuple[int, int], "candela.Film"] = {}

    def start_from(self, film: "candela.Film", units: List[WorkUnit]) -> None:
        """Continues ``film`` (a checkpoint's), which holds for each cell the
        first passes its sample counts show."""
        first_pass = [u for u in units if u.pass_index == 0]
        pass_ends = [u.sample_range[1] for u in units if u.cell_index == 0]
        done = passes_done(film, [u.cell for u in first_pass], pass_ends)
        self.film = film
        self.next_pass = {c: n for c, n in enumerate(done)}

    def add(self, unit: WorkUnit, part: "candela.Film") -> None:
        key = (unit.cell_index, unit.pass_index)
        if key in self.pending or unit.pass_index < self.next_pass.get(unit.cell_index, 0):
            return  # a duplicate result of a rerun unit: already counted
        self.pending[key] = part
        nxt = self.next_pass.get(unit.cell_index, 0)
        while (unit.cell_index, nxt) in self.pending:
            self.film.add(self.pending.pop((unit.cell_index, nxt)))
            nxt += 1
        self.next_pass[unit.cell_index] = nxt

    def result(self) -> "candela.Film":
        missing = sum(self.passes - self.next_pass.get(c, 0) for c in range(self.cells))
        if self.pending or missing:
            raise RuntimeError("distributed render finished with parts missing")
        return self.film


def resume(checkpoint: Union[str, "os.PathLike[str]"], client: Any, **options: Any) -> "candela.Film":
    """Continues the distributed render saved in ``checkpoint`` on the Dask
    ``client``'s cluster (same scene, grid and settings; ``options`` are
    ``render``'s other keywords: ``retries``, ``on_unit``, ...). Returns the
    whole film, equal bit for bit to the uninterrupted render's."""
    args = resume_args(os.fspath(checkpoint))
    return render(args["scene_path"], client, tiles=args["tiles"], passes=args["passes"], strict=args["strict"],
                  **options, **args["settings"])
