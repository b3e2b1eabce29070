"""A scene imported with its depth after the pipeline: each object's partial and completed
points (GET /api/scenes/{id}/depth-points) in the world of its 3D box, refused with a reason
for a scene without depth or before the pipeline placed the camera; and a placement job after
a layout edit keeps measuring the boxes from the depth."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import cv2
import numpy as np
import pytest
from fastapi.testclient import TestClient
from holiscene.api.routes import scenes as scene_routes
from holiscene.learning.completion.scene_points import MAX_POINTS, scene_depth_points

from ...conftest import wait_for_job
from ..conftest import Accounts, folder_upload

DEPTH_STAGES = {"layout_from_depth", "boxes_from_depth", "shape_completion"}


def _post(client: TestClient, folder: Path, depth: bool, run: bool) -> Any:
    files = folder_upload(folder, depth)
    response = client.post(
        "/api/scenes", files=files, data={"run_pipeline": "true" if run else "false"}
    )
    assert response.status_code == 201, response.text
    return response.json()


def _pipeline_scene(client: TestClient, folder: Path, depth: bool = True) -> Any:
    """The scene's document after its pipeline job."""
    imported = _post(client, folder, depth, run=True)
    job = wait_for_job(client, imported["job"]["id"], timeout=120)
    assert job["status"] == "succeeded", job
    return client.get(f"/api/scenes/{imported['scene']['id']}").json()


def _inside(points: np.ndarray, corners: np.ndarray, margin: float) -> np.ndarray:
    """Which points lie within `margin` metres of the box given by its 8 corners."""
    origin = corners[0]
    axes = np.stack([corners[1] - origin, corners[4] - origin, corners[3] - origin])
    lengths = np.linalg.norm(axes, axis=1)
    local = (points - origin) @ (axes / lengths[:, None]).T
    return np.all((local >= -margin) & (local <= lengths + margin), axis=1)


def test_each_objects_points_lie_in_its_box_and_the_room(
    client: TestClient, synthetic_folder: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    doc = _pipeline_scene(client, synthetic_folder)
    scene_id, scene = doc["scene_id"], doc["scene"]
    assert {s["name"] for s in scene["stages"]} >= DEPTH_STAGES
    assert scene["camera"]["height_source"] == "depth"
    response = client.get(f"/api/scenes/{scene_id}/depth-points")
    assert response.status_code == 200, response.text
    body = response.json()
    assert (body["scene_id"], body["revision"], body["max_points"]) == (
        scene_id,
        doc["revision"],
        MAX_POINTS,
    )
    objects = {o["id"]: o for o in scene["objects"]}
    assert [p["id"] for p in body["objects"]] == [o["id"] for o in scene["objects"] if o["mask"]]
    room = np.array(scene["layout"]["corners_3d"])
    completed = 0
    for entry in body["objects"]:
        partial = np.array(entry["partial"]).reshape(-1, 3)
        assert len(partial) <= MAX_POINTS
        assert _inside(partial, room, 0.05).mean() > 0.98, entry["id"]
        obj = objects[entry["id"]]
        if entry["completed"] is None:
            assert obj["mesh"] is None or obj["mesh"]["library"] != "completion"
            continue
        completed += 1
        # The network's points are what the stage meshed: the object's mesh is the completion.
        assert obj["mesh"]["library"] == "completion", entry["id"]
        points = np.array(entry["completed"])
        assert 0 < len(points) <= MAX_POINTS
        box = np.array(obj["corners_3d"])
        # Grown points stay within 0.15 box lengths of the box; 5 cm covers it for furniture.
        assert _inside(points, box, 0.05 + 0.15 * np.ptp(box, axis=0).max()).all(), entry["id"]
        assert _inside(points, box, 0.02).mean() > 0.8, entry["id"]
    assert completed >= len(body["objects"]) / 2
    # Asked again (the 3D view's toggle, a reload): the same answer, without completing the
    # shapes again.
    completions: list[str] = []

    def counted(scene: Any, depth: np.ndarray) -> Any:
        completions.append(scene.name)
        return scene_depth_points(scene, depth)

    monkeypatch.setattr(scene_routes, "scene_depth_points", counted)
    again = client.get(f"/api/scenes/{scene_id}/depth-points")
    assert again.json() == body and completions == []
    # Revision 1, the import, has no camera yet.
    assert client.get(f"/api/scenes/{scene_id}/depth-points?revision=1").status_code == 409


def test_a_scene_without_depth_or_camera_has_no_depth_points(
    client: TestClient, synthetic_folder: Path
) -> None:
    without = _post(client, synthetic_folder, depth=False, run=False)["scene"]["id"]
    response = client.get(f"/api/scenes/{without}/depth-points")
    assert response.status_code == 404
    assert response.json()["detail"] == f"scene {without} has no depth: it was imported without"
    # With depth, but the pipeline has not placed the camera yet.
    waiting = _post(client, synthetic_folder, depth=True, run=False)["scene"]["id"]
    response = client.get(f"/api/scenes/{waiting}/depth-points")
    assert response.status_code == 409
    assert "no camera pitch and roll yet" in response.json()["detail"]
    assert client.get("/api/scenes/nope/depth-points").status_code == 404


def test_depth_points_and_key_need_a_login(accounts: Accounts) -> None:
    for route in ("depth-points", "depth-key"):
        refused = accounts.client.get(f"/api/scenes/0123456789ab/{route}")
        assert refused.status_code == 401, route
        # Logged in, any role may read them (here: no such scene).
        found = accounts.client.get(
            f"/api/scenes/0123456789ab/{route}", headers=accounts.headers("rita")
        )
        assert found.status_code == 404, route


def test_a_placement_job_after_a_layout_edit_keeps_the_depth_boxes(
    client: TestClient, synthetic_folder: Path
) -> None:
    """The layout set by hand where the depth put it: re-placing the objects measures their
    boxes from the depth again (the placement alone would guess them from typical sizes)."""
    doc = _pipeline_scene(client, synthetic_folder)
    scene_id = doc["scene_id"]
    corners = doc["scene"]["layout"]["corners_2d"]
    body = {
        "base_revision": doc["revision"],
        "author": "ann",
        "edits": [{"kind": "set_layout", "corners_2d": corners}],
    }
    edited = client.post(f"/api/scenes/{scene_id}/edits", json=body)
    assert edited.status_code == 200, edited.text
    assert edited.json()["scene"]["camera"]["height_source"] == "depth"
    started = client.post(f"/api/scenes/{scene_id}/placement-jobs")
    assert started.status_code == 202, started.text
    job = wait_for_job(client, started.json()["id"], timeout=120)
    assert job["status"] == "succeeded", job
    placed = client.get(f"/api/scenes/{scene_id}").json()["scene"]
    ran = {s["name"] for s in placed["stages"]}
    assert {"boxes_from_depth", "shape_completion"} <= ran
    for before, after in zip(doc["scene"]["objects"], placed["objects"], strict=True):
        assert (before["box_3d"] is None) == (after["box_3d"] is None)
        if before["box_3d"] is None:
            continue
        np.testing.assert_allclose(after["box_3d"]["size"], before["box_3d"]["size"], atol=0.03)
        np.testing.assert_allclose(after["box_3d"]["center"], before["box_3d"]["center"], atol=0.03)
        assert after["mesh"] == before["mesh"]


def _hex(bgra: np.ndarray) -> str:
    blue, green, red = (int(v) for v in bgra[:3])
    return f"#{red:02x}{green:02x}{blue:02x}"


def test_the_depth_overlay_has_a_key(client: TestClient, synthetic_folder: Path) -> None:
    """The key names the depths the overlay's colours span (2nd to 98th percentile of the
    depth present) and its colours from near to far: the preview's own near and far ones."""
    scene_id = _post(client, synthetic_folder, depth=True, run=False)["scene"]["id"]
    key = client.get(f"/api/scenes/{scene_id}/depth-key")
    assert key.status_code == 200, key.text
    body = key.json()
    millimetres = cv2.imread(str(synthetic_folder / "depth.png"), cv2.IMREAD_UNCHANGED)
    near, far = np.percentile(millimetres[millimetres > 0], [2, 98]) / 1000.0
    assert body["near_m"] == pytest.approx(near, abs=0.002)
    assert body["far_m"] == pytest.approx(far, abs=0.002)
    assert len(body["colours"]) >= 5
    preview = client.get(f"/api/scenes/{scene_id}/depth-preview.png").content
    rgba = cv2.imdecode(np.frombuffer(preview, np.uint8), cv2.IMREAD_UNCHANGED)
    present = np.where(millimetres > 0, millimetres, 65535)
    nearest = np.unravel_index(np.argmin(present), rgba.shape[:2])
    furthest = np.unravel_index(np.argmax(millimetres), rgba.shape[:2])
    assert _hex(rgba[nearest]) == body["colours"][0]
    assert _hex(rgba[furthest]) == body["colours"][-1]
    without = _post(client, synthetic_folder, depth=False, run=False)["scene"]["id"]
    assert client.get(f"/api/scenes/{without}/depth-key").status_code == 404
