"""RestoreSupport edits (undo and revert in the app): a supporter comes back exactly as an
earlier revision stored it, the pipeline's guess as a guess, with its confidence."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from ...conftest import imported_scene
from ...conftest import post_edits as _edit


def _imported(client: TestClient, folder: Path) -> dict[str, Any]:
    return imported_scene(client, folder, "t3d-5")


def _support(doc: dict[str, Any], child: str) -> dict[str, Any] | None:
    return next((s for s in doc["scene"]["supports"] if s["child"] == child), None)


def test_restore_brings_back_the_pipelines_guess_unchanged(client: TestClient, t3d5: Path) -> None:
    predicted = _imported(client, t3d5)
    guess = _support(predicted, "o1")
    assert guess is not None and guess["source"] == "auto" and guess["confidence"] is not None

    accepted = _edit(
        client,
        predicted,
        {"kind": "set_support", "child": "o1", "parent": guess["parent"], "type": guess["type"]},
    ).json()
    assert _support(accepted, "o1")["source"] == "manual"  # type: ignore[index]

    response = _edit(
        client,
        accepted,
        {"kind": "restore_support", "child": "o1", "from_revision": predicted["revision"]},
    )
    assert response.status_code == 200, response.text
    restored = response.json()
    assert restored["revision"] == accepted["revision"] + 1
    assert _support(restored, "o1") == guess
    history = client.get(f"/api/scenes/{predicted['scene_id']}/revisions").json()
    assert history[-1]["edits"] == [
        {"kind": "restore_support", "child": "o1", "from_revision": predicted["revision"]}
    ]
    assert f"as in revision {predicted['revision']}" in history[-1]["summary"]


def test_restore_from_a_revision_without_a_supporter_removes_it(
    client: TestClient, t3d5: Path
) -> None:
    predicted = _imported(client, t3d5)
    removed = _edit(client, predicted, {"kind": "remove_support", "child": "o2"}).json()
    assert _support(removed, "o2") is None
    back = _edit(
        client,
        removed,
        {"kind": "restore_support", "child": "o2", "from_revision": predicted["revision"]},
        {"kind": "restore_support", "child": "o3", "from_revision": removed["revision"]},
    ).json()
    assert _support(back, "o2") == _support(predicted, "o2")
    assert _support(back, "o3") == _support(removed, "o3")
    # o2 had no supporter in that revision: restoring from it removes the supporter again.
    again = _edit(
        client,
        back,
        {"kind": "restore_support", "child": "o2", "from_revision": removed["revision"]},
    ).json()
    assert _support(again, "o2") is None


def test_bad_restores_are_refused_whole(client: TestClient, t3d5: Path) -> None:
    predicted = _imported(client, t3d5)
    missing = _edit(
        client, predicted, {"kind": "restore_support", "child": "o1", "from_revision": 99}
    )
    assert missing.status_code == 422
    assert "no revision 99" in missing.text

    # Revision r: o0 on o1. Then o1 on o0 (o0 on the floor): restoring o0 from r closes a loop.
    r = _edit(
        client,
        predicted,
        {"kind": "set_support", "child": "o1", "parent": "floor", "type": "below"},
        {"kind": "set_support", "child": "o0", "parent": "o1", "type": "below"},
    ).json()
    flipped = _edit(
        client,
        r,
        {"kind": "set_support", "child": "o0", "parent": "floor", "type": "below"},
        {"kind": "set_support", "child": "o1", "parent": "o0", "type": "below"},
    ).json()
    cycle = _edit(
        client, flipped, {"kind": "restore_support", "child": "o0", "from_revision": r["revision"]}
    )
    assert cycle.status_code == 422, cycle.text
    after = client.get(f"/api/scenes/{predicted['scene_id']}").json()
    assert after["revision"] == flipped["revision"]
