"""Type stubs of the native module ``candela._candela``."""

from os import PathLike
from typing import Any, Dict, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike[str]]

class LoadError(ValueError):
    """A scene file could not be loaded; the message locates the problem."""

class DenoiseError(RuntimeError):
    """Open Image Denoise is missing or failed; the message says what is
    missing and how to get it (``pip install pyoidn``)."""

class Stats(TypedDict):
    """Render statistics; counters add up when films merge."""

    rays: int
    camera_rays: int
    shadow_rays: int
    bounce_rays: int
    samples: int
    path_segments: int
    invalid_samples: int
    threads: int
    converged_pixels: int
    render_time_s: float
    wall_time_s: float
    mrays_per_s: float
    samples_per_s: float
    mean_path_length: float
    nodes_per_ray: float
    tests_per_ray: float

class FilmArrays(TypedDict):
    """The raw per-pixel sums of a film."""

    radiance: npt.NDArray[np.float64]
    radiance_sq: npt.NDArray[np.float64]
    albedo: npt.NDArray[np.float64]
    normal: npt.NDArray[np.float64]
    lum: npt.NDArray[np.float64]
    lum_sq: npt.NDArray[np.float64]
    depth: npt.NDArray[np.float64]
    count: npt.NDArray[np.uint32]
    depth_count: npt.NDArray[np.uint32]
    nodes: npt.NDArray[np.uint64]
    prim_tests: npt.NDArray[np.uint64]

class Film:
    """Per-pixel sums over a rectangle of an image; merges by addition."""

    @staticmethod
    def empty(width: int, height: int) -> Film:
        """A film of zeros covering a whole image, to add parts into."""
    @staticmethod
    def from_bytes(data: bytes) -> Film:
        """A film from ``Film.to_bytes`` output."""
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def origin(self) -> Tuple[int, int]:
        """(x, y) of the film's top-left pixel in the full image."""
    @property
    def full_size(self) -> Tuple[int, int]:
        """(width, height) of the full image."""
    @property
    def stats(self) -> Stats: ...
    def set_wall_time(self, seconds: float) -> None:
        """Records the elapsed time of a render whose parts ran concurrently."""
    def image(self) -> npt.NDArray[np.float32]:
        """Mean linear radiance, shape (H, W, 3)."""
    def denoise(self) -> npt.NDArray[np.float32]:
        """The image denoised by Open Image Denoise (guided by the film's
        albedo and normal), shape (H, W, 3); raises ``DenoiseError``
        without the library."""
    def sample_counts(self) -> npt.NDArray[np.uint32]:
        """Samples per pixel, shape (H, W)."""
    def arrays(self) -> FilmArrays:
        """The raw sums as NumPy arrays (``depth`` over ``depth_count``,
        the rest over ``count``, give the means)."""
    def save(self, path: _Path, *, samples: bool = False, aovs: bool = False, **settings: Any) -> None:
        """Writes .png (tone-mapped sRGB with the ``exposure`` and ``tone``
        settings) or .exr (linear; optional samples, albedo and normal
        layers); ``denoise=True`` also writes ``<stem>.denoised.<ext>``."""
    def add(self, other: Film) -> None:
        """Adds a part of the same image lying inside this film, in place."""
    def to_bytes(self) -> bytes:
        """The sums, placement and statistics as bytes (exact)."""
    def __reduce__(self) -> tuple: ...

class Scene:
    """A loaded scene and what the loader reported."""

    @property
    def source(self) -> str: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def notes(self) -> list[str]: ...
    def render(
        self,
        *,
        sample_range: Optional[Tuple[int, int]] = None,
        passes: int = 1,
        **settings: Any,
    ) -> Film:
        """Renders the scene. The keywords are the render settings, named as
        the CLI's long flags (``settings_help()`` lists them with their help:
        ``spp``, ``max_depth``, ``integrator``, ``width``, ``cell``,
        ``adaptive``, ...); settings not given take the scene's suggestion,
        else the default. Ctrl-C raises KeyboardInterrupt."""
    def settings(self, **settings: Any) -> Dict[str, Any]:
        """Every setting a ``render`` with these keywords would use."""
    def content_hash(self, **settings: Any) -> str:
        """Content hash (32 hex digits) of the scene, its textures and the
        environment map of these settings, as checkpoints record it."""

def load(path: _Path, *, strict: bool = False) -> Scene:
    """Loads a COLLADA (.dae) scene."""

def scene_files(path: _Path, *, strict: bool = False) -> list[str]:
    """Every file the scene needs (scene file first): meshes, material
    libraries, buffers, textures, environment map."""
def demo_scene() -> Scene:
    """The built-in demo scene."""

def merge(films: Sequence[Film]) -> Film:
    """Adds films of one image, in order, into a film of the whole image."""

def read_image(path: _Path) -> npt.NDArray[np.float32]:
    """Reads a PNG (as linear RGB) or an EXR, shape (H, W, 3)."""

def denoiser_library() -> str:
    """The Open Image Denoise library ``Film.denoise`` uses; raises
    ``DenoiseError`` without one."""
def settings_help() -> Dict[str, str]:
    """The help of every render setting, by name (as ``candela --help``)."""

def write_checkpoint(path: _Path, film: Film, *, settings: Dict[str, Any], scene_hash: str,
                     front: Dict[str, Any], elapsed_s: float) -> None:
    """Writes a checkpoint (the CLI's format) atomically."""

def read_checkpoint(path: _Path, *, scene_hash: Optional[str] = None,
                    settings: Optional[Dict[str, Any]] = None) -> Dict[str, Any]:
    """Reads a checkpoint: ``settings``, ``front``, ``elapsed_s``, ``scene_hash``
    and ``film``; with ``scene_hash`` and ``settings``, raises ValueError
    naming what differs if it is of another render."""

def compare_json(
    a: Any,
    b: Any,
    reference: Any = None,
    *,
    block: int = 8,
    false_alarm: float = 0.01,
    heatmap: Optional[str] = None,
) -> str:
    """The report of ``candela compare --json`` as text (see ``candela.compare``)."""
