"""RestoreScene edits (the history's "Revert to this"): the whole scene goes back as an earlier
revision had it (objects, supports, room layout, camera, people's removals), as a new revision
that a restore_scene of the revision before it takes back. On the real t3d-5 photo."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from ...conftest import imported_scene, wait_for_job
from ...conftest import post_edits as _edit

# Revert writes the scene's GLB pointer with the revision: on SQLite and on PostgreSQL.
pytestmark = pytest.mark.both_databases


def _imported(client: TestClient, folder: Path) -> dict[str, Any]:
    return imported_scene(client, folder, "t3d-5")


def _restore(number: int) -> dict[str, Any]:
    return {"kind": "restore_scene", "from_revision": number}


def _changed_everywhere(client: TestClient, doc: dict[str, Any]) -> dict[str, Any]:
    """`doc` with an object removed, another's class changed, a support set by hand and the room
    refitted at another camera height: one revision."""
    layout = doc["scene"]["layout"]
    response = _edit(
        client,
        doc,
        {"kind": "remove_object", "id": "o2"},
        {"kind": "set_class", "id": "o1", "class": "table"},
        {"kind": "set_support", "child": "o3", "parent": "floor", "type": "below"},
        {"kind": "set_layout", "corners_2d": layout["corners_2d"], "camera_height_m": 2.2},
    )
    assert response.status_code == 200, response.text
    changed: dict[str, Any] = response.json()
    assert changed["scene"]["layout"] != layout
    return changed


def test_restore_scene_puts_everything_back_and_is_undone_by_the_same_edit(
    client: TestClient, t3d5: Path
) -> None:
    predicted = _imported(client, t3d5)
    changed = _changed_everywhere(client, predicted)
    assert changed["scene"]["removed_by_person"]

    response = _edit(client, changed, _restore(predicted["revision"]))
    assert response.status_code == 200, response.text
    reverted = response.json()
    assert reverted["revision"] == changed["revision"] + 1
    assert reverted["scene"] == predicted["scene"]  # objects, supports, layout, camera, stages

    undone = _edit(client, reverted, _restore(changed["revision"])).json()
    assert undone["scene"] == changed["scene"]

    history = client.get(f"/api/scenes/{predicted['scene_id']}/revisions").json()
    assert history[-2]["edits"] == [_restore(predicted["revision"])]
    assert history[-2]["summary"] == f"the scene as in revision {predicted['revision']}"


def test_edits_after_a_restore_in_one_request_apply_on_the_restored_scene(
    client: TestClient, t3d5: Path
) -> None:
    predicted = _imported(client, t3d5)
    changed = _changed_everywhere(client, predicted)
    response = _edit(
        client,
        changed,
        _restore(predicted["revision"]),
        {"kind": "set_class", "id": "o2", "class": "cabinet"},  # o2 is back
    )
    assert response.status_code == 200, response.text
    objects = {o["id"]: o for o in response.json()["scene"]["objects"]}
    assert objects["o2"]["class"] == "cabinet"
    assert objects["o1"]["class"] == next(
        o["class"] for o in predicted["scene"]["objects"] if o["id"] == "o1"
    )


def test_a_restore_of_a_missing_revision_is_refused_and_writes_nothing(
    client: TestClient, t3d5: Path
) -> None:
    predicted = _imported(client, t3d5)
    changed = _changed_everywhere(client, predicted)
    missing = _edit(client, changed, _restore(changed["revision"] + 5))
    assert missing.status_code == 422
    assert f"no revision {changed['revision'] + 5} to restore the scene from" in missing.text
    out_of_range = _edit(client, changed, _restore(0))
    assert out_of_range.status_code == 422
    after = client.get(f"/api/scenes/{predicted['scene_id']}").json()
    assert after["revision"] == changed["revision"]
    assert after["scene"] == changed["scene"]


def test_a_restore_on_a_stale_revision_conflicts(client: TestClient, t3d5: Path) -> None:
    predicted = _imported(client, t3d5)
    _changed_everywhere(client, predicted)
    stale = _edit(client, predicted, _restore(predicted["revision"]))
    assert stale.status_code == 409


def _glb(client: TestClient, scene_id: str) -> bytes | None:
    response = client.get(f"/api/scenes/{scene_id}/scene.glb")
    if response.status_code == 404:
        return None
    assert response.status_code == 200, response.text
    return response.content


def test_a_restored_scene_brings_back_its_3d_scene(client: TestClient, t3d5: Path) -> None:
    predicted = _imported(client, t3d5)
    scene_id = predicted["scene_id"]
    predicted_glb = _glb(client, scene_id)
    assert predicted_glb is not None
    removed = _edit(client, predicted, {"kind": "remove_object", "id": "o2"}).json()
    started = client.post(f"/api/scenes/{scene_id}/placement-jobs")
    assert started.status_code == 202, started.text
    assert wait_for_job(client, started.json()["id"], timeout=120)["status"] == "succeeded"
    placed = client.get(f"/api/scenes/{scene_id}").json()
    assert placed["revision"] == removed["revision"] + 1
    # The history says who placed the objects again, and only the stages that job ran.
    entry = client.get(f"/api/scenes/{scene_id}/revisions").json()[-1]
    assert entry["author"] == "local"
    assert entry["summary"].startswith("objects placed again: ")
    assert "placement" in entry["summary"] and "masks_grabcut" not in entry["summary"]
    placed_glb = _glb(client, scene_id)
    assert placed_glb is not None and placed_glb != predicted_glb

    reverted = _edit(client, placed, _restore(predicted["revision"])).json()
    assert _glb(client, scene_id) == predicted_glb
    # A revert of the revert finds the placement's GLB through it.
    again = _edit(client, reverted, _restore(placed["revision"])).json()
    assert _glb(client, scene_id) == placed_glb
    # The imported revision had none: neither has the scene now.
    _edit(client, again, _restore(1))
    assert _glb(client, scene_id) is None
    # A revision that was itself a revert leads to the GLB it brought back.
    latest = client.get(f"/api/scenes/{scene_id}").json()
    latest = _edit(client, latest, _restore(reverted["revision"])).json()
    assert _glb(client, scene_id) == predicted_glb
    # An edit that restores nothing keeps the GLB as it is.
    _edit(client, latest, {"kind": "set_class", "id": "o1", "class": "table"})
    assert _glb(client, scene_id) == predicted_glb
