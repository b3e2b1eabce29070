"""The object detector's files over HTTP (GET /api/detector/...), as the browser fetches them."""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.learning.detector import runtime
from holiscene.learning.detector.runtime import DEFAULT_DETECTOR_DIR
from holiscene.store.model_registry import Registration


def test_serves_the_committed_default_detector(client: TestClient) -> None:
    info = client.get("/api/detector/active").json()
    model = DEFAULT_DETECTOR_DIR / runtime.MODEL_FILE
    sha256 = hashlib.sha256(model.read_bytes()).hexdigest()
    metadata = json.loads((DEFAULT_DETECTOR_DIR / runtime.METADATA_FILE).read_text())
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
    assert "or the suggester" in stale.json()["detail"]
    for name in ("LICENSE", "..%2Fmetadata.json", "model.onnx.bak"):
        assert client.get(f"/api/detector/{info['id']}/{name}").status_code == 404


def test_a_promoted_detector_is_served_under_a_new_id(client: TestClient, tmp_path: Path) -> None:
    first = client.get("/api/detector/active").json()
    folder = tmp_path / "detector"
    folder.mkdir()
    shutil.copy(runtime.COCO_DETECTOR_DIR / runtime.METADATA_FILE, folder)
    (folder / runtime.MODEL_FILE).write_bytes(b"another model")
    workbench = client.app.state.workbench  # type: ignore[attr-defined]
    registered = workbench.detectors.register(folder, Registration(status="accepted"))
    workbench.detectors.promote(registered.id, "admin")
    second = client.get("/api/detector/active").json()
    assert second["id"] == hashlib.sha256(b"another model").hexdigest()[:16] != first["id"]
    assert client.get(first["model_url"]).status_code == 404
    assert client.get(second["model_url"]).content == b"another model"


def test_serves_the_suggester_beside_the_active_detector(client: TestClient) -> None:
    """The scene page's guesses come from the shipped suggester, whatever detector is active;
    its files are served under its own id."""
    info = client.get("/api/detector/suggester").json()
    model = runtime.SUGGESTER_DETECTOR_DIR / runtime.MODEL_FILE
    sha256 = hashlib.sha256(model.read_bytes()).hexdigest()
    assert info["id"] == sha256[:16] != client.get("/api/detector/active").json()["id"]
    assert info["label_space"] == "nyu40" and "lamp" in info["classes"]
    onnx = client.get(info["model_url"])
    assert onnx.status_code == 200 and hashlib.sha256(onnx.content).hexdigest() == sha256
    metadata = json.loads((runtime.SUGGESTER_DETECTOR_DIR / runtime.METADATA_FILE).read_text())
    assert client.get(info["metadata_url"]).json() == metadata


def test_no_suggester_installed_is_a_404(
    client: TestClient, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    from holiscene.api.routes import detector

    shipped = client.get("/api/detector/suggester").json()
    monkeypatch.setattr(detector, "SUGGESTER_DETECTOR_DIR", tmp_path / "none")
    missing = client.get("/api/detector/suggester")
    assert missing.status_code == 404 and "no object detector" in missing.json()["detail"]
    assert client.get(shipped["model_url"]).status_code == 404
