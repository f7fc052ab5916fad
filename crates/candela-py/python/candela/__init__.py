"""Candela, a physically based path tracer, from Python.

    >>> import candela
    >>> scene = candela.load("CBspheres_lambertian.dae")
    >>> film = scene.render(spp=64, width=256, height=192, seed=1)
    >>> film.image().shape
    (192, 256, 3)
    >>> film.save("spheres.exr")

A film keeps per-pixel sums (radiance, luminance, squared luminance, sample
count), so films of parts of an image -- pixel rectangles, sample ranges,
machines -- merge by addition: see ``candela.merge`` and
``candela.distributed`` (rendering on a Dask cluster).
"""

from candela._candela import (
    DenoiseError,
    Film,
    LoadError,
    Scene,
    demo_scene,
    denoiser_library,
    load,
    merge,
    read_checkpoint,
    read_image,
    scene_files,
    settings_help,
    write_checkpoint,
)

from candela._compare import compare  # noqa: E402

# After the native names it uses: ``candela.distributed`` is there with a
# plain ``import candela`` (Dask itself is imported only when used).
from candela import distributed  # noqa: E402

__all__ = ["DenoiseError", "Film", "LoadError", "Scene", "compare", "demo_scene", "denoiser_library", "load",
           "merge", "read_checkpoint", "read_image", "scene_files", "settings_help", "write_checkpoint",
           "distributed"]
__version__ = "0.1.0"
