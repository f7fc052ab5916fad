"""A scene and every file it references, as bytes: how a scene reaches Dask
workers that share no disk with the client.

The client reads the files once (``bundle_scene``: the scene file, and what
``candela.scene_files`` lists -- meshes, material libraries, buffers,
textures -- plus an environment map given as a setting) and keeps their
layout relative to their common folder, so the references inside the scene
(relative to the scene file) resolve the same way wherever the folder is
rebuilt. The bundle is named by a hash of its contents; it travels to the
workers once through Dask (``client.scatter``), and each worker process
writes it out once, into ``$CANDELA_SCENE_CACHE`` (default: the temporary
folder's ``candela-scenes``), under that hash (``materialise``). Loading
then goes through the usual per-process scene cache, so each worker loads
and builds the scene once.

A scene file that names another file by an absolute path is shipped with
it, but the reference inside the file still points at that absolute path on
the worker: use relative references for clusters without a shared disk.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import tempfile
import uuid
from dataclasses import dataclass
from pathlib import PurePosixPath
from typing import Optional, Tuple

import candela

__all__ = ["SceneBundle", "bundle_scene", "cache_dir", "materialise"]


@dataclass(frozen=True)
class SceneBundle:
    """The files of one scene, by path relative to their common folder."""

    #: SHA-256 of the paths and contents: the bundle's name in worker caches.
    digest: str
    #: The scene file's path inside the bundle.
    scene: str
    #: ``(relative POSIX path, bytes)`` of every file, the scene first.
    files: Tuple[Tuple[str, bytes], ...]
    #: The environment-map setting's file inside the bundle, if it is one.
    env_map: Optional[str] = None

    def __repr__(self) -> str:
        size = sum(len(b) for _, b in self.files)
        return f"<SceneBundle {self.scene} ({len(self.files)} files, {size} bytes) {self.digest[:12]}>"


def bundle_scene(path, strict: bool = False, env_map: Optional[str] = None) -> SceneBundle:
    """Reads the scene at ``path`` and every file it references (and the
    image ``env_map`` names, if it is a file) into a bundle."""
    scene = os.path.abspath(os.fspath(path))
    files = [os.path.abspath(f) for f in candela.scene_files(scene, strict=strict)]
    env = os.path.abspath(env_map) if env_map and os.path.isfile(env_map) else None
    if env is not None and env not in files:
        files.append(env)
    root = os.path.commonpath([os.path.dirname(f) for f in files])
    rel = lambda f: PurePosixPath(*os.path.relpath(f, root).split(os.sep)).as_posix()  # noqa: E731
    contents = []
    for f in files:
        with open(f, "rb") as fh:
            contents.append((rel(f), fh.read()))
    digest = hashlib.sha256()
    for name, data in sorted(contents):
        digest.update(name.encode() + b"\0" + hashlib.sha256(data).digest())
    return SceneBundle(digest.hexdigest(), rel(scene), tuple(contents), rel(env) if env else None)


def cache_dir() -> str:
    """Where bundles are written out on this machine."""
    return os.environ.get("CANDELA_SCENE_CACHE") or os.path.join(tempfile.gettempdir(), "candela-scenes")


def _safe(name: str) -> PurePosixPath:
    p = PurePosixPath(name)
    if p.is_absolute() or ".." in p.parts or not p.parts:
        raise ValueError(f"scene bundle: refusing the path {name!r} (outside the bundle)")
    return p


def materialise(bundle: SceneBundle) -> str:
    """The folder holding ``bundle``'s files on this machine, written on
    first use. The folder is complete or absent: files go to a private
    folder renamed into place, so concurrent workers never see half a
    scene, and a folder already there (same hash, same contents) is kept."""
    final = os.path.join(cache_dir(), bundle.digest)
    if os.path.isdir(final):
        return final
    os.makedirs(cache_dir(), exist_ok=True)
    part = os.path.join(cache_dir(), f".{bundle.digest}.{os.getpid()}.{uuid.uuid4().hex[:8]}")
    try:
        for name, data in bundle.files:
            target = os.path.join(part, *_safe(name).parts)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as fh:
                fh.write(data)
        try:
            os.rename(part, final)
        except OSError:
            if not os.path.isdir(final):  # not a lost race: a real failure
                raise
    finally:
        shutil.rmtree(part, ignore_errors=True)
    return final


def scene_path(bundle: SceneBundle) -> str:
    """The scene file of ``bundle`` on this machine (written out if needed)."""
    return os.path.join(materialise(bundle), *_safe(bundle.scene).parts)


def env_map_path(bundle: SceneBundle) -> Optional[str]:
    """The environment map of ``bundle`` on this machine, if it has one."""
    if bundle.env_map is None:
        return None
    return os.path.join(materialise(bundle), *_safe(bundle.env_map).parts)
