"""The scene-state edit lock: a submitted or accepted scene refuses every edit (supports and
room layout, whoever asks), and the answers about a scene say whether the user asking may
edit it (`editable`, `editable_reason`), so the app can disable its editors."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient
from holiscene.api.permissions import with_edit_permission
from holiscene.editing.workflow_rules import Actor

from ..stored_scenes import store_predicted_scene
from .conftest import Accounts
from .routes.test_workflow import Api, _refused, _set

# The store, as the server uses it, on SQLite and on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases

# Any corners: the lock is checked before the edit is looked at.
LAYOUT = {"kind": "set_layout", "corners_2d": [[1.0, 1.0], [60.0, 1.0], [60.0, 40.0]] + [None] * 5}
SUBMITTED = "submitted for review (by ann)"
# What its annotator and the other annotators are told; reviewers and admins are told how they
# change what they judge.
SUBMITTED_TO_ANNOTATORS = f"{SUBMITTED}: a reviewer must reject it before it can be edited"
SUBMITTED_TO_REVIEWERS = f"{SUBMITTED}: it stays as submitted while you judge it"


@pytest.fixture()
def api(accounts: Accounts) -> Api:
    return Api(accounts)


def _may_edit(api: Api, who: str, scene_id: str) -> tuple[bool, str | None]:
    doc = api.get(who, f"/api/scenes/{scene_id}")
    flow = api.get(who, f"/api/scenes/{scene_id}/workflow")
    assert (flow["editable"], flow["editable_reason"]) == (doc["editable"], doc["editable_reason"])
    return doc["editable"], doc["editable_reason"]


def _everyone(api: Api, scene_id: str) -> dict[str, tuple[bool, str | None]]:
    return {who: _may_edit(api, who, scene_id) for who in ("ann", "bob", "rita", "ada")}


def test_editable_follows_the_state_and_the_user(api: Api, accounts: Accounts) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    # Predicted: anyone may start annotating it.
    assert all(editable for editable, _ in _everyone(api, scene_id).values())

    edited = api.edit("ann", scene_id, _set("o2", "floor"))
    assert edited.status_code == 200
    assert (edited.json()["editable"], edited.json()["editable_reason"]) == (True, None)
    may = _everyone(api, scene_id)
    assert may["ann"] == (True, None)
    # An admin takes a scene over by taking it, not by an edit.
    assert may["ada"] == (False, "the scene is being annotated by ann: take it over to edit it")
    for other in ("bob", "rita"):
        assert may[other] == (False, "the scene is being annotated by ann")

    submitted = api.act("ann", scene_id, "submit")
    assert submitted.status_code == 200
    assert submitted.json()["editable"] is False
    for who, (editable, reason) in _everyone(api, scene_id).items():
        told = SUBMITTED_TO_REVIEWERS if who in ("rita", "ada") else SUBMITTED_TO_ANNOTATORS
        assert not editable and reason is not None and told in reason, (who, reason)

    rejected = api.act("rita", scene_id, "reject", comment="the books lie on the table")
    assert rejected.status_code == 200
    assert rejected.json()["editable"] is False  # rita: ann fixes it
    may = _everyone(api, scene_id)
    assert may["ann"] == (True, None)
    assert may["ada"] == (
        False,
        "the scene was sent back to ann, who fixes it: take it over to edit it",
    )
    assert may["bob"] == (
        False,
        "the scene was sent back to ann, who fixes it (an admin can take it over)",
    )

    assert api.edit("ann", scene_id, _set("o2", "o0")).status_code == 200
    assert api.act("ann", scene_id, "submit").status_code == 200
    assert api.act("rex", scene_id, "accept").status_code == 200
    for who, (editable, reason) in _everyone(api, scene_id).items():
        assert not editable and reason is not None and "accepted" in reason, who

    # An earlier revision is never editable.
    old = api.get("ann", f"/api/scenes/{scene_id}/revisions/1")
    assert old["editable"] is False
    assert "edits apply to the latest" in old["editable_reason"]


@pytest.mark.parametrize("who", ["ann", "rita", "ada"])
def test_a_submitted_scene_refuses_every_edit(api: Api, accounts: Accounts, who: str) -> None:
    """Supports and the room layout, from its annotator, a reviewer or an admin: 409 with the
    reason, and nothing is written (no revision, no state change)."""
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    assert api.edit("ann", scene_id, _set("o2", "floor")).status_code == 200
    assert api.act("ann", scene_id, "submit").status_code == 200
    before = api.snapshot(scene_id)
    for edit in (_set("o1", "floor"), {"kind": "remove_support", "child": "o1"}, LAYOUT):
        _refused(api, scene_id, api.edit(who, scene_id, edit), 409, SUBMITTED)
    _refused(api, scene_id, api.post(who, f"/api/scenes/{scene_id}/take"), 409, SUBMITTED)
    placement = api.post(who, f"/api/scenes/{scene_id}/placement-jobs")
    _refused(api, scene_id, placement, 409, "cannot re-run")
    assert api.snapshot(scene_id) == before


def test_an_accepted_scene_refuses_edits(api: Api, accounts: Accounts) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    assert api.edit("ann", scene_id, _set("o2", "floor")).status_code == 200
    assert api.act("ann", scene_id, "submit").status_code == 200
    assert api.act("rita", scene_id, "accept").status_code == 200
    before = api.snapshot(scene_id)
    for who in ("ann", "rita", "ada"):
        for edit in (_set("o1", "floor"), LAYOUT):
            _refused(api, scene_id, api.edit(who, scene_id, edit), 409, "accepted")
    assert api.snapshot(scene_id) == before


def test_the_local_user_sees_the_lock_too(client: TestClient) -> None:
    """Local single-user mode: the local admin may edit, until the scene is submitted."""
    workbench = client.app.state.workbench  # type: ignore[attr-defined]
    scene_id = store_predicted_scene(workbench.scenes)
    doc = client.get(f"/api/scenes/{scene_id}").json()
    assert (doc["editable"], doc["editable_reason"]) == (True, None)
    submitted = client.post(f"/api/scenes/{scene_id}/take")
    assert submitted.status_code == 200
    revision = client.get(f"/api/scenes/{scene_id}").json()["revision"]
    assert client.post(f"/api/scenes/{scene_id}/submit", json={"revision": revision}).is_success
    doc = client.get(f"/api/scenes/{scene_id}").json()
    assert doc["editable"] is False and "submitted for review" in doc["editable_reason"]


def test_a_save_landing_after_the_latest_was_read_does_not_lock_it(
    api: Api, accounts: Accounts
) -> None:
    """The page's answer about the latest revision, read just before a colleague saved, still
    says editable (the page merges that revision when it saves); the same revision asked for
    by number is an earlier one by then."""
    workbench = accounts.workbench
    scene_id = store_predicted_scene(workbench.scenes)
    ada = Actor("ada", "admin")
    read_before = workbench.scenes.document(scene_id)
    flow_before = workbench.workflow.scene_workflow(scene_id)
    assert api.edit("ada", scene_id, _set("o2", "floor")).status_code == 200
    for answer in (read_before, flow_before):
        judged = with_edit_permission(answer, workbench, ada)
        assert (judged.editable, judged.editable_reason) == (True, None)
    by_number = with_edit_permission(read_before, workbench, ada, by_number=True)
    assert by_number.editable is False
    assert "edits apply to the latest" in (by_number.editable_reason or "")
