"""Two annotators taking the same scene at the same moment, with real threads: exactly one
gets it, the other is told who did (409), and the history holds one claim."""

from __future__ import annotations

import threading
from typing import Any

import pytest
from httpx import Response

from .conftest import Accounts
from .scenes import store_predicted_scene

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


def _at_once(accounts: Accounts, scene_id: str, *requests: tuple[Any, str]) -> list[Response]:
    """Run each (request, who) in its own thread, released together by a barrier."""
    barrier = threading.Barrier(len(requests))
    answers: list[Response | None] = [None] * len(requests)

    def run(index: int) -> None:
        request, who = requests[index]
        barrier.wait()
        answers[index] = request(accounts, who, scene_id)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(requests))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    assert all(a is not None for a in answers), "a request did not come back"
    return [a for a in answers if a is not None]


@pytest.mark.parametrize("second", [_take, _edit], ids=["take-take", "take-edit"])
def test_of_two_annotators_taking_at_once_exactly_one_wins(accounts: Accounts, second: Any) -> None:
    for _ in range(TRIES):
        scene_id = store_predicted_scene(accounts.workbench.scenes)
        ann, bob = _at_once(accounts, scene_id, (_take, "ann"), (second, "bob"))
        assert sorted([ann.status_code, bob.status_code]) == [200, 409], (ann.text, bob.text)
        winner, loser = ("ann", bob) if ann.status_code == 200 else ("bob", ann)
        detail = loser.json()["detail"]
        message = detail["message"] if isinstance(detail, dict) else detail
        assert winner in message, message  # who has the scene now

        flow = accounts.workbench.workflow.scene_workflow(scene_id)
        assert (flow.state, flow.assignee) == ("in_annotation", winner)
        claims = [e for e in flow.events if e.action == "claim"]
        assert [c.actor for c in claims] == [winner]
