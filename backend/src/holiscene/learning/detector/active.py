"""Which detector the app serves to the browser (GET /api/detector/active) and the shared
vectors are made from: the default detector (the one the pipeline's objects_from_detector
stage uses unless told otherwise), or, while there is none, the COCO model it starts from."""

from __future__ import annotations

from pathlib import Path

from . import runtime


def active_detector_dir() -> Path:
    for folder in (runtime.DEFAULT_DETECTOR_DIR, runtime.COCO_DETECTOR_DIR):
        if (folder / runtime.MODEL_FILE).is_file():
            return folder
    return runtime.DEFAULT_DETECTOR_DIR
