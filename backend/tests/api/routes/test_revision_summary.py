"""A revision's summary, as a reviewer reads it in the history: the changes first, the guesses
an annotator confirmed as they were counted after them. On the real t3d-5 photo."""

from __future__ import annotations

from pathlib import Path

from fastapi.testclient import TestClient

from ...conftest import imported_scene, post_edits


def test_confirmed_guesses_are_counted_after_the_changes(client: TestClient, t3d5: Path) -> None:
    doc = imported_scene(client, t3d5, "t3d-5")
    guessed = doc["scene"]["supports"]
    assert len(guessed) >= 3
    *kept, changed = guessed
    new_parent = "wall" if changed["parent"] != "wall" else "floor"
    new_type = "behind" if new_parent == "wall" else "below"
    edits = [
        {"kind": "set_support", "child": changed["child"], "parent": new_parent, "type": new_type},
        *(
            {"kind": "set_support", "child": s["child"], "parent": s["parent"], "type": s["type"]}
            for s in kept
        ),
    ]
    response = post_edits(client, doc, *edits)
    assert response.status_code == 200, response.text
    summary = client.get(f"/api/scenes/{doc['scene_id']}/revisions").json()[-1]["summary"]
    children = ", ".join(s["child"] for s in kept)
    assert summary == (
        f"{changed['child']} supported by {new_parent} ({new_type}); "
        f"{len(kept)} supporters confirmed as they were ({children})"
    )
