"""The object detectors' files, for the browser: which detector is active (the registry's active
one of kind "detector", the one pipeline jobs use), and its model.onnx and metadata.json (the
scene page runs the model with onnxruntime-web to suggest objects); and the suggester, the
shipped detector whose boxes the page offers as guesses on request (docs/detector.md).

As with the Relation Network's registry (models.py), the files live under an id that changes
whenever the model does (the start of the model file's sha256), so browsers may keep them for
good. Any logged-in user may fetch them.
"""

from __future__ import annotations

import hashlib
from functools import lru_cache
from pathlib import Path

from fastapi import APIRouter, HTTPException
from fastapi.responses import FileResponse
from holiscene_schema import DetectorInfo, ErrorMessage

from ...learning.detector import runtime
from ...learning.detector.runtime import DEFAULT_DETECTOR_DIR, SUGGESTER_DETECTOR_DIR
from ..deps import WorkbenchDep

router = APIRouter(prefix="/api/detector", tags=["detector"])

_404: dict[int | str, dict[str, object]] = {404: {"model": ErrorMessage}}
_IMMUTABLE = {"Cache-Control": "public, max-age=31536000, immutable"}
DETECTOR_FILES = {
    runtime.MODEL_FILE: "application/octet-stream",
    runtime.METADATA_FILE: "application/json",
}


@lru_cache(maxsize=4)
def _digest(path: Path, mtime_ns: int, size: int) -> str:
    # Keyed by modification time and size too, so a replaced file is hashed afresh.
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _info(model_dir: Path) -> DetectorInfo:
    try:
        metadata = runtime.read_metadata(model_dir)
        model = model_dir / runtime.MODEL_FILE
        stat = model.stat()
    except (runtime.DetectorModelError, FileNotFoundError) as error:
        raise HTTPException(404, f"no object detector is installed: {error}") from None
    sha256 = _digest(model.resolve(), stat.st_mtime_ns, stat.st_size)
    detector_id = sha256[:16]
    return DetectorInfo(
        id=detector_id,
        name=str(metadata.get("name") or "object detector"),
        label_space=metadata["label_space"],
        classes=[str(c) for c in metadata["classes"]],
        model_sha256=sha256,
        model_bytes=stat.st_size,
        model_url=f"/api/detector/{detector_id}/{runtime.MODEL_FILE}",
        metadata_url=f"/api/detector/{detector_id}/{runtime.METADATA_FILE}",
    )


def _is_suggester(detector_id: str) -> bool:
    try:
        return _info(SUGGESTER_DETECTOR_DIR).id == detector_id
    except HTTPException:  # none installed
        return False


def _active_dir(workbench: WorkbenchDep) -> Path:
    return workbench.detectors.active_dir() or DEFAULT_DETECTOR_DIR


@router.get("/active", response_model=DetectorInfo, responses=_404)
def active_detector(workbench: WorkbenchDep) -> DetectorInfo:
    """The detector the browser runs; 404 when none is installed."""
    return _info(_active_dir(workbench))


@router.get("/suggester", response_model=DetectorInfo, responses=_404)
def suggester_detector() -> DetectorInfo:
    """The detector behind the scene page's guesses; 404 when none is installed."""
    return _info(SUGGESTER_DETECTOR_DIR)


@router.get(
    "/{detector_id}/{file_name}",
    responses={200: {"content": {media: {} for media in set(DETECTOR_FILES.values())}}, **_404},
)
def detector_file(detector_id: str, file_name: str, workbench: WorkbenchDep) -> FileResponse:
    """The active detector's or the suggester's model.onnx or metadata.json (404 under an
    older id)."""
    model_dir = _active_dir(workbench)
    active = _info(model_dir)
    if detector_id != active.id:
        if not _is_suggester(detector_id):
            raise HTTPException(
                404, f"detector {detector_id} is not the active one ({active.id}) or the suggester"
            )
        model_dir = SUGGESTER_DETECTOR_DIR
    if file_name not in DETECTOR_FILES:
        raise HTTPException(404, f"the detector has no file {file_name!r}")
    return FileResponse(
        model_dir / file_name, media_type=DETECTOR_FILES[file_name], headers=_IMMUTABLE
    )
