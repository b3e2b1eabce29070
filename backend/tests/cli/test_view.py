"""`holiscene view SCENE [--port N]`: a running viewer, and its refusals (exit status 2)."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest
from holiscene.cli import main
from holiscene.core.settings import Settings
from holiscene.inputs import read_input_folder
from holiscene.services.workbench import Workbench
from holiscene.viewer.sources import load_scene_argument


def _fails(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.err.startswith("error: "), captured.err
    return captured.err


def test_missing_files_and_bad_scenes_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert "no such file" in _fails(["view", str(tmp_path / "nowhere" / "scene.json")], capsys)
    assert "no such file" in _fails(["view", str(tmp_path / "scene.json")], capsys)
    assert "holds no scene.json or gt.json" in _fails(["view", str(tmp_path)], capsys)
    (tmp_path / "broken.json").write_text("{not json")
    assert "not a readable JSON file" in _fails(["view", str(tmp_path / "broken.json")], capsys)
    (tmp_path / "other.json").write_text('{"name": "x"}')
    assert "not a HoliScene scene" in _fails(["view", str(tmp_path / "other.json")], capsys)
    scene = tmp_path / "ok"
    scene.mkdir()
    assert "not a port number" in _fails(["view", str(scene), "--port", "70000"], capsys)


def test_unknown_scene_ids_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    data_dir = tmp_path / "data"
    err = _fails(["view", "abc123", "--data-dir", str(data_dir)], capsys)
    assert "no scene 'abc123'" in err and "no scene store" in err
    assert not (data_dir / "holiscene.db").exists(), "looking up an id creates no store"

    Workbench(Settings(data_dir=data_dir)).close()  # an empty store
    err = _fails(["view", "abc123", "--data-dir", str(data_dir)], capsys)
    assert "no scene 'abc123'" in err and str(data_dir) in err


def test_stored_scene_loads_by_id(tmp_path: Path, synthetic_folder: Path) -> None:
    settings = Settings(data_dir=tmp_path / "data")
    workbench = Workbench(settings)
    try:
        inputs = read_input_folder(synthetic_folder)
        scene_id = workbench.import_scene(inputs, "stored", "test", run_pipeline=False).scene.id
    finally:
        workbench.close()
    data = load_scene_argument(scene_id, settings)
    assert data.origin == f"scene {scene_id}, revision 1"
    assert data.scene.name == "stored"
    assert data.photo is not None and data.photo.shape == (480, 640, 3)
    assert data.glb is None and any("no 3D scene file yet" in n for n in data.notes)


def test_view_serves_until_interrupted(synthetic_folder: Path, tmp_path: Path) -> None:
    # stderr to a file: an undrained pipe could fill up and stall the viewer's shutdown.
    stderr = (tmp_path / "stderr.txt").open("w")
    process = subprocess.Popen(
        [sys.executable, "-m", "holiscene.cli", "view", str(synthetic_folder), "--port", "0"],
        stdout=subprocess.PIPE,
        stderr=stderr,
        text=True,
    )
    try:
        url = None
        deadline = time.monotonic() + 60
        assert process.stdout is not None
        while url is None and time.monotonic() < deadline:
            line = process.stdout.readline()
            if not line:
                break
            if line.startswith("viewer of "):
                url = line.rsplit(" ", 1)[-1].strip()
        assert url is not None and url.startswith("http://127.0.0.1:"), (
            tmp_path / "stderr.txt"
        ).read_text()
        with urllib.request.urlopen(url, timeout=10) as response:
            assert response.status == 200
            assert b"<html" in response.read().lower()
        process.send_signal(signal.SIGINT)
        # Generous: stopping viser's threads took over 20 s once on a loaded machine.
        assert process.wait(timeout=90) == 0
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
        stderr.close()
