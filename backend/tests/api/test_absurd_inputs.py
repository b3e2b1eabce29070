"""Inputs far outside what a person would send get a 4xx that says why, never a 500, and
nothing a user reads (answers, job errors) shows how the server is laid out."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.core.errors import user_facing_error
from holiscene.core.settings import Settings
from PIL import Image

from ..bad_inputs import png_header_only
from ..conftest import wait_for_job


def _png(width: int, height: int) -> bytes:
    out = io.BytesIO()
    Image.fromarray(np.full((height, width, 3), 128, np.uint8)).save(out, format="PNG")
    return out.getvalue()


def _import(client: TestClient, filename: str, photo: bytes, **files: bytes):  # type: ignore[no-untyped-def]
    sent = {"image": (filename, photo, "image/png")}
    sent.update({key: (f"{key}.json", data, "application/json") for key, data in files.items()})
    return client.post("/api/scenes", files=sent, data={"run_pipeline": "false"})


@pytest.fixture()
def scene_id(client: TestClient) -> str:
    imported = _import(client, "room.png", _png(64, 48))
    assert imported.status_code == 201, imported.text
    return str(imported.json()["scene"]["id"])


def test_revision_numbers_beyond_the_database_integers(client: TestClient, scene_id: str) -> None:
    for number in ("99999999999999999999", str(2**31)):
        answer = client.get(f"/api/scenes/{scene_id}/revisions/{number}")
        assert answer.status_code == 422, answer.text
        assert "less than or equal to 2147483647" in answer.json()["detail"]
    # The largest number allowed is merely a revision that does not exist.
    assert client.get(f"/api/scenes/{scene_id}/revisions/{2**31 - 1}").status_code == 404

    restores = (
        {"kind": "restore_support", "child": "o1", "from_revision": 2**70},
        {"kind": "restore_object", "id": "o1", "from_revision": 2**70},
    )
    for edit in restores:
        body = {"base_revision": 1, "author": "ann", "edits": [edit]}
        answer = client.post(f"/api/scenes/{scene_id}/edits", json=body)
        assert answer.status_code == 422, answer.text
        assert "from_revision" in answer.json()["detail"]
    body = {"base_revision": 2**63, "author": "ann", "edits": [restores[0]]}
    assert client.post(f"/api/scenes/{scene_id}/edits", json=body).status_code == 422
    assert (
        client.post(f"/api/scenes/{scene_id}/submit", json={"revision": 2**64}).status_code == 422
    )
    assert [r["number"] for r in client.get(f"/api/scenes/{scene_id}/revisions").json()] == [1]


def test_deeply_nested_detections(client: TestClient) -> None:
    nested = b"[" * 100_000 + b"]" * 100_000
    answer = _import(client, "room.png", _png(64, 48), detections=nested)
    assert answer.status_code == 422, answer.text
    assert "nested too deeply" in answer.json()["detail"]
    assert client.get("/api/scenes").json() == []


def test_a_long_file_name_is_cut_to_the_scene_name_limit(client: TestClient) -> None:
    answer = _import(client, "x" * 300 + ".png", _png(64, 48))
    assert answer.status_code == 201, answer.text
    assert answer.json()["scene"]["name"] == "x" * 200
    # A name typed by the user is theirs to shorten: refused, not cut.
    typed = client.post(
        "/api/scenes",
        files={"image": ("room.png", _png(64, 48), "image/png")},
        data={"run_pipeline": "false", "name": "y" * 201},
    )
    assert typed.status_code == 422 and "name" in typed.json()["detail"]
    # The next photo of that name gets a number, still within the limit.
    again = _import(client, "x" * 300 + ".png", _png(64, 48))
    assert again.json()["scene"]["name"] == "x" * 198 + " 2"


def test_photos_of_one_file_name_from_several_folders_get_numbered_names(
    client: TestClient,
) -> None:
    names = [_import(client, "img.jpg", _png(64, 48)).json()["scene"]["name"] for _ in range(3)]
    assert names == ["img", "img 2", "img 3"]
    # A typed name that is taken gets a number too: two scenes of one name could not be told
    # apart in the list or in a notice naming them. "img 10" does not make "img" numbered.
    typed = client.post(
        "/api/scenes",
        files={"image": ("img.jpg", _png(64, 48), "image/png")},
        data={"run_pipeline": "false", "name": "img"},
    )
    assert typed.json()["scene"]["name"] == "img 4"
    assert _import(client, "img 10.png", _png(64, 48)).json()["scene"]["name"] == "img 10"
    assert _import(client, "img.png", _png(64, 48)).json()["scene"]["name"] == "img 5"


@pytest.mark.parametrize(
    ("width", "height", "status", "reason"),
    [(40_000_000, 1, 422, "both sides at least"), (20_000, 20_000, 413, "too large")],
)
def test_photos_of_absurd_size(
    client: TestClient, settings: Settings, width: int, height: int, status: int, reason: str
) -> None:
    answer = _import(client, "strip.png", png_header_only(width, height))
    assert answer.status_code == status and reason in answer.json()["detail"]
    assert str(settings.data_dir) not in answer.text
    assert client.get("/api/scenes").json() == []


def test_a_failed_job_shows_no_server_paths_nor_traceback(
    client: TestClient, settings: Settings, scene_id: str
) -> None:
    # The photo vanished from the store: the pipeline fails on reading it, with its path.
    photo = client.app.state.workbench.scenes.image_path(scene_id)  # type: ignore[attr-defined]
    photo.unlink()
    started = client.post(f"/api/scenes/{scene_id}/pipeline-jobs")
    assert started.status_code == 202, started.text
    job = wait_for_job(client, started.json()["id"])
    assert job["status"] == "failed"
    error = job["error"]
    assert "Traceback" not in error and "\n" not in error
    for hidden in (str(settings.data_dir), str(Path(__file__).parents[2]), ".py"):
        assert hidden not in error, error
    assert "server log" in error


def test_user_facing_error_hides_paths_but_keeps_the_reason() -> None:
    opencv = OSError(
        "OpenCV(4.10.0) /io/opencv/modules/imgproc/src/resize.cpp:4152: error: (-215:Assertion "
        "failed) !ssize.empty() in function 'resize'\nmore detail"
    )
    assert user_facing_error(opencv) == (
        "OSError: OpenCV(4.10.0) <server path>:4152: error: (-215:Assertion failed) "
        "!ssize.empty() in function 'resize'"
    )
    windows = FileNotFoundError(r"no such file: C:\data\scenes\abc\img.png (ratio 3/4 in m/s)")
    assert user_facing_error(windows) == (
        "FileNotFoundError: no such file: <server path> (ratio 3/4 in m/s)"
    )
    assert len(user_facing_error(ValueError("v" * 1000))) == 300
