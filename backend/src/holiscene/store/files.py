"""The data directory: one folder per scene holding its input files and 3D results.

A scene's folder is a valid `holiscene infer` input folder (img.*, cam_K.txt,
detections.json). Folders are written under a temporary name and renamed into place, so a
failed import leaves nothing behind; one killed midway leaves its staging folder, which the
next server start removes.
"""

from __future__ import annotations

import os
import shutil
import tempfile
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..core.data_dir_owner import try_lock

# Scene ids are hex, so no scene folder starts with a dot.
STAGING_PREFIX = "."
# What a dataset measured for the photo (a Scene with 3D boxes, layout, camera), imported
# with it; `holiscene eval --store` scores the scene's current revision against it.
GROUND_TRUTH_FILE = "gt.json"


class SceneFiles:
    def __init__(self, data_dir: Path) -> None:
        self.root = data_dir / "scenes"
        self.root.mkdir(parents=True, exist_ok=True)

    def folder(self, scene_id: str) -> Path:
        return self.root / scene_id

    def glb_path(self, scene_id: str, revision: int) -> Path:
        return self.folder(scene_id) / f"scene-r{revision}.glb"

    def ground_truth_path(self, scene_id: str) -> Path:
        """gt.json of the scene: present only for scenes imported with ground truth."""
        return self.folder(scene_id) / GROUND_TRUTH_FILE

    @contextmanager
    def new_folder(self, scene_id: str) -> Iterator[Path]:
        """A folder to fill; it becomes the scene's folder only if the block succeeds.

        The staging folder is flock-ed while it is filled, so start-up can tell the folder of
        a dead import (lock free: remove it) from one another process is still filling."""
        staging = Path(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{scene_id}-", dir=self.root))
        held = os.open(staging, os.O_RDONLY | os.O_DIRECTORY)
        try:
            # Made this instant: only a server start-up sweeping at this very moment could
            # take it first, and then this import fails (on its missing folder), nothing worse.
            try_lock(held)
            yield staging
            os.replace(staging, self.folder(scene_id))
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise
        finally:
            os.close(held)

    def remove_abandoned_staging(self) -> list[Path]:
        """Remove the staging folders of imports that died midway (killed, power cut): the
        ones whose lock nobody holds. Returns what was removed."""
        removed = []
        for path in self.root.glob(f"{STAGING_PREFIX}*"):
            if not path.is_dir() or path.is_symlink():
                continue
            fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY)
            try:
                if not try_lock(fd):
                    continue  # an import in another process is filling it now
                shutil.rmtree(path, ignore_errors=True)
                removed.append(path)
            finally:
                os.close(fd)
        return removed

    def remove(self, scene_id: str) -> None:
        shutil.rmtree(self.folder(scene_id), ignore_errors=True)

    def write_atomic(self, path: Path, data: bytes) -> None:
        tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
        tmp.write_bytes(data)
        os.replace(tmp, path)
