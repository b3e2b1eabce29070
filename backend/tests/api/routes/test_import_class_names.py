"""Class names on import: a name no vocabulary knows becomes otherprop with the name kept and a
warning, never a refusal of the whole file; a class_map.json maps a dataset's own names."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient
from holiscene.core.settings import Settings
from holiscene.inputs import read_input_folder

from ...conftest import wait_for_job

BOXES = [
    {"bbox": [10, 10, 120, 120], "class": "basket"},  # SUN RGB-D: otherprop, known
    {"bbox": [150, 20, 260, 200], "class": "spaceship"},  # nowhere: otherprop, flagged
    {"bbox": [300, 40, 400, 220], "class": "Chairs"},  # a plural of an NYU-40 name
]


def _import(client: TestClient, t3d5: Path, class_map: dict[str, str] | None = None) -> Any:
    files = {
        "image": ("img.jpg", (t3d5 / "img.jpg").read_bytes(), "image/jpeg"),
        "detections": ("detections.json", json.dumps(BOXES).encode(), "application/json"),
    }
    if class_map is not None:
        files["class_map"] = ("class_map.json", json.dumps(class_map).encode(), "application/json")
    return client.post("/api/scenes", files=files, data={"run_pipeline": "false"})


def _objects(client: TestClient, scene_id: str) -> list[tuple[str, str | None]]:
    scene = client.get(f"/api/scenes/{scene_id}").json()["scene"]
    return [(o["class"], o.get("source_class")) for o in scene["objects"]]


def test_unknown_names_become_otherprop_with_a_warning(client: TestClient, t3d5: Path) -> None:
    response = _import(client, t3d5)
    assert response.status_code == 201, response.text
    scene_id = response.json()["scene"]["id"]
    assert _objects(client, scene_id) == [
        ("otherprop", "basket"),
        ("otherprop", "spaceship"),
        ("chair", "Chairs"),
    ]
    stages = client.get(f"/api/scenes/{scene_id}").json()["scene"]["stages"]
    warnings = [s["note"] for s in stages if s["warning"]]
    assert len(warnings) == 1 and "'spaceship'" in warnings[0] and "basket" not in warnings[0]


def test_a_class_map_wins_over_the_aliases(client: TestClient, t3d5: Path) -> None:
    response = _import(client, t3d5, {"SpaceShip": "lamp", "basket": "box"})
    assert response.status_code == 201, response.text
    scene_id = response.json()["scene"]["id"]
    assert _objects(client, scene_id) == [
        ("box", "basket"),
        ("lamp", "spaceship"),
        ("chair", "Chairs"),
    ]
    stages = client.get(f"/api/scenes/{scene_id}").json()["scene"]["stages"]
    assert not [s for s in stages if s["warning"]]


def test_a_bad_class_map_is_refused_and_nothing_is_stored(
    client: TestClient, settings: Settings, t3d5: Path
) -> None:
    scenes_before = client.get("/api/scenes").json()
    folders_before = sorted(p.name for p in settings.data_dir.rglob("*"))
    response = _import(client, t3d5, {"spaceship": "starship"})
    assert response.status_code == 422
    assert "class_map.json" in response.json()["detail"]
    assert client.get("/api/scenes").json() == scenes_before
    assert sorted(p.name for p in settings.data_dir.rglob("*")) == folders_before


def test_the_stored_boxes_read_back_to_the_same_classes(
    client: TestClient, settings: Settings, t3d5: Path
) -> None:
    """A pipeline re-run reads the stored detections.json: the class a user's map chose and
    the flag on an unknown name must survive it."""
    response = _import(client, t3d5, {"basket": "box"})
    scene_id = response.json()["scene"]["id"]
    [stored] = [p for p in settings.data_dir.rglob("detections.json") if scene_id in str(p)]
    folder = stored.parent
    again = read_input_folder(folder).detections
    assert again is not None
    assert [(d.cls, d.source_class, d.class_known) for d in again] == [
        ("box", "basket", True),
        ("otherprop", "spaceship", False),
        ("chair", "Chairs", True),
    ]


def test_the_pipeline_flags_the_unknown_name_too(client: TestClient, t3d5: Path) -> None:
    files = {
        "image": ("img.jpg", (t3d5 / "img.jpg").read_bytes(), "image/jpeg"),
        "detections": ("detections.json", json.dumps(BOXES).encode(), "application/json"),
    }
    result = client.post("/api/scenes", files=files).json()
    assert wait_for_job(client, result["job"]["id"])["status"] == "succeeded"
    scene = client.get(f"/api/scenes/{result['scene']['id']}").json()["scene"]
    assert [o["class"] for o in scene["objects"]] == ["otherprop", "otherprop", "chair"]
    flagged = [s for s in scene["stages"] if s["warning"] and "spaceship" in (s["note"] or "")]
    assert [s["name"] for s in flagged] == ["objects_from_detector"]
    assert flagged[0]["model"].startswith("object detector v1 (")
