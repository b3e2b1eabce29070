"""The data directory: one folder per scene holding its input files and 3D results.

A scene's folder is a valid `holiscene infer` input folder (img.*, cam_K.txt,
detections.json). Folders are written under a temporary name and renamed into place, so a
failed import leaves nothing behind.
"""

from __future__ import annotations

import os
import shutil
import tempfile
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


class SceneFiles:
    def __init__(self, data_dir: Path) -> None:
        self.root = data_dir / "scenes"
        self.root.mkdir(parents=True, exist_ok=True)

    def folder(self, scene_id: str) -> Path:
        return self.root / scene_id

    def glb_path(self, scene_id: str, revision: int) -> Path:
        return self.folder(scene_id) / f"scene-r{revision}.glb"

    @contextmanager
    def new_folder(self, scene_id: str) -> Iterator[Path]:
        """A folder to fill; it becomes the scene's folder only if the block succeeds."""
        staging = Path(tempfile.mkdtemp(prefix=f".{scene_id}-", dir=self.root))
        try:
            yield staging
            os.replace(staging, self.folder(scene_id))
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise

    def remove(self, scene_id: str) -> None:
        shutil.rmtree(self.folder(scene_id), ignore_errors=True)

    def write_atomic(self, path: Path, data: bytes) -> None:
        tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
        tmp.write_bytes(data)
        os.replace(tmp, path)
