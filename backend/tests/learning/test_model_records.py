"""The records committed with each model (metrics.json, metadata.json) name no machine's
folders: a path in them is relative to the repository, so they read the same on every clone."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from holiscene.core.settings import REPO_ROOT
from holiscene.learning.train import recorded_setting

LEARNING = REPO_ROOT / "backend" / "src" / "holiscene" / "learning"


def _strings(value: Any) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, dict):
        return [s for v in value.values() for s in _strings(v)]
    if isinstance(value, list):
        return [s for v in value for s in _strings(v)]
    return []


def test_committed_model_records_hold_no_absolute_paths() -> None:
    records = sorted(LEARNING.glob("*/metrics.json")) + sorted(LEARNING.glob("*/metadata.json"))
    assert len(records) >= 4
    absolute = [
        (record.relative_to(REPO_ROOT), text)
        for record in records
        for text in _strings(json.loads(record.read_text()))
        if text.startswith(("/home/", "/root/", "/tmp/", "/work/", str(REPO_ROOT)))
    ]
    assert absolute == []


def test_a_run_records_repository_paths_relative_to_it() -> None:
    inside = REPO_ROOT / "backend" / "src" / "holiscene" / "learning" / "x" / "model.onnx"
    assert recorded_setting(inside) == "backend/src/holiscene/learning/x/model.onnx"
    assert recorded_setting(Path("/elsewhere/model.onnx")) == "/elsewhere/model.onnx"
    assert recorded_setting(7) == 7
