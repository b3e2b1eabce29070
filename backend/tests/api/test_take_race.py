"""Two annotators taking the same scene at the same moment, with real threads: exactly one
gets it, the other is told who did (409), and the history holds one claim."""

from __future__ import annotations

from typing import Any

import pytest
from httpx import Response

from ..stored_scenes import store_predicted_scene
from .at_once import at_once
from .conftest import Accounts

# Store and workflow behaviour: on both databases (databases.py).
pytestmark = pytest.mark.both_databases

TRIES = 8


def _take(accounts: Accounts, who: str, scene_id: str) -> Response:
    return accounts.client.post(f"/api/scenes/{scene_id}/take", headers=accounts.headers(who))


def _edit(accounts: Accounts, who: str, scene_id: str) -> Response:
    """The first edit takes the scene too (the implicit take)."""
    body = {
        "base_revision": 2,  # the pipeline's revision of a freshly predicted test scene
        "author": who,
        "edits": [{"kind": "set_support", "child": "o2", "parent": "floor", "type": "below"}],
    }
    return accounts.client.post(
        f"/api/scenes/{scene_id}/edits", json=body, headers=accounts.headers(who)
    )


@pytest.mark.parametrize("second", [_take, _edit], ids=["take-take", "take-edit"])
def test_of_two_annotators_taking_at_once_exactly_one_wins(accounts: Accounts, second: Any) -> None:
    for _ in range(TRIES):
        scene_id = store_predicted_scene(accounts.workbench.scenes)
        ann, bob = at_once(accounts, scene_id, (_take, "ann"), (second, "bob"))
        assert sorted([ann.status_code, bob.status_code]) == [200, 409], (ann.text, bob.text)
        winner, loser = ("ann", bob) if ann.status_code == 200 else ("bob", ann)
        detail = loser.json()["detail"]
        message = detail["message"] if isinstance(detail, dict) else detail
        assert winner in message, message  # who has the scene now

        flow = accounts.workbench.workflow.scene_workflow(scene_id)
        assert (flow.state, flow.assignee) == ("in_annotation", winner)
        claims = [e for e in flow.events if e.action == "claim"]
        assert [c.actor for c in claims] == [winner]


def test_of_two_annotators_saving_first_edits_at_once_exactly_one_takes_the_scene(
    accounts: Accounts,
) -> None:
    """Each first edit would take the scene (written with its revision in one statement); the
    loser is refused (409) and writes nothing."""
    for _ in range(TRIES):
        scene_id = store_predicted_scene(accounts.workbench.scenes)
        ann, bob = at_once(accounts, scene_id, (_edit, "ann"), (_edit, "bob"))
        assert sorted([ann.status_code, bob.status_code]) == [200, 409], (ann.text, bob.text)
        winner = "ann" if ann.status_code == 200 else "bob"
        flow = accounts.workbench.workflow.scene_workflow(scene_id)
        assert (flow.state, flow.assignee) == ("in_annotation", winner)
        claims = [e for e in flow.events if e.action == "claim"]
        assert [(c.actor, c.revision) for c in claims] == [(winner, 3)]
        history = accounts.workbench.scenes.revisions(scene_id)
        assert [(r.number, r.author) for r in history if r.number > 2] == [(3, winner)]


def test_the_same_annotator_taking_twice_at_once_gets_it_once(accounts: Accounts) -> None:
    """Two tabs of one annotator: both succeed (the scene is theirs), one claim."""
    for _ in range(TRIES):
        scene_id = store_predicted_scene(accounts.workbench.scenes)
        answers = at_once(accounts, scene_id, (_take, "ann"), (_take, "ann"))
        assert [a.status_code for a in answers] == [200, 200], [a.text for a in answers]
        flow = accounts.workbench.workflow.scene_workflow(scene_id)
        assert (flow.state, flow.assignee) == ("in_annotation", "ann")
        assert [e.actor for e in flow.events if e.action == "claim"] == ["ann"]
