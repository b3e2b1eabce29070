"""The object detector's files over HTTP (GET /api/detector/...), as the browser fetches them."""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.learning.detector import runtime
from holiscene.learning.detector.active import active_detector_dir


def test_serves_the_committed_default_detector(client: TestClient) -> None:
    info = client.get("/api/detector/active").json()
    model = active_detector_dir() / runtime.MODEL_FILE
    sha256 = hashlib.sha256(model.read_bytes()).hexdigest()
    metadata = json.loads((active_detector_dir() / runtime.METADATA_FILE).read_text())
    assert info["model_sha256"] == sha256 and info["id"] == sha256[:16]
    assert info["label_space"] == metadata["label_space"]
    assert info["classes"] == metadata["classes"]
    assert info["model_bytes"] == model.stat().st_size

    onnx = client.get(info["model_url"])
    assert onnx.status_code == 200
    assert hashlib.sha256(onnx.content).hexdigest() == sha256
    assert onnx.headers["content-type"] == "application/octet-stream"
    assert "immutable" in onnx.headers["cache-control"]
    served = client.get(info["metadata_url"])
    assert served.status_code == 200 and served.json() == metadata


def test_refuses_other_ids_and_files(client: TestClient) -> None:
    info = client.get("/api/detector/active").json()
    stale = client.get(f"/api/detector/0123456789abcdef/{runtime.MODEL_FILE}")
    assert stale.status_code == 404 and "not the active one" in stale.json()["detail"]
    for name in ("LICENSE", "..%2Fmetadata.json", "model.onnx.bak"):
        assert client.get(f"/api/detector/{info['id']}/{name}").status_code == 404


def test_a_replaced_model_gets_a_new_id(
    client: TestClient, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    folder = tmp_path / "detector"
    folder.mkdir()
    shutil.copy(runtime.COCO_DETECTOR_DIR / runtime.METADATA_FILE, folder)
    (folder / runtime.MODEL_FILE).write_bytes(b"first")
    monkeypatch.setattr(runtime, "DEFAULT_DETECTOR_DIR", folder)
    first = client.get("/api/detector/active").json()
    assert first["id"] == hashlib.sha256(b"first").hexdigest()[:16]
    assert client.get(first["model_url"]).content == b"first"

    (folder / runtime.MODEL_FILE).write_bytes(b"second model")
    second = client.get("/api/detector/active").json()
    assert second["id"] != first["id"]
    assert client.get(first["model_url"]).status_code == 404
    assert client.get(second["model_url"]).content == b"second model"


def test_the_coco_model_stands_in_for_a_missing_default(
    client: TestClient, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(runtime, "DEFAULT_DETECTOR_DIR", tmp_path / "none")
    info = client.get("/api/detector/active").json()
    coco = runtime.COCO_DETECTOR_DIR / runtime.MODEL_FILE
    assert info["model_sha256"] == hashlib.sha256(coco.read_bytes()).hexdigest()
    assert info["label_space"] == "coco80" and len(info["classes"]) == 80


def test_no_detector_installed(
    client: TestClient, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(runtime, "DEFAULT_DETECTOR_DIR", tmp_path / "none")
    monkeypatch.setattr(runtime, "COCO_DETECTOR_DIR", tmp_path / "none either")
    missing = client.get("/api/detector/active")
    assert missing.status_code == 404
    assert missing.json()["detail"].startswith("no object detector is installed")
