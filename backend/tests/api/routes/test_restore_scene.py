"""RestoreScene edits (the history's "Revert to this"): the whole scene goes back as an earlier
revision had it (objects, supports, room layout, camera, people's removals), as a new revision
that a restore_scene of the revision before it takes back. On the real t3d-5 photo."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from ...conftest import imported_scene
from ...conftest import post_edits as _edit


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
