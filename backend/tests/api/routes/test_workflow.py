"""The annotation workflow over HTTP: states and who may change them, refusals that change
nothing, "Next scene" by uncertainty, second annotations, agreement and the dashboard."""

from __future__ import annotations

from datetime import datetime
from typing import Any

import pytest
from fastapi.testclient import TestClient
from holiscene.editing.workflow_rules import WorkflowError

from ...stored_scenes import store_predicted_scene
from ..conftest import Accounts

# The store, as the server uses it, on SQLite and on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases


def _set(child: str, parent: str, kind: str = "below") -> dict[str, str]:
    return {"kind": "set_support", "child": child, "parent": parent, "type": kind}


class Api:
    """The accounts' requests, by name."""

    def __init__(self, accounts: Accounts) -> None:
        self.accounts = accounts
        self.client: TestClient = accounts.client

    def get(self, who: str, url: str) -> Any:
        response = self.client.get(url, headers=self.accounts.headers(who))
        assert response.status_code == 200, response.text
        return response.json()

    def post(self, who: str, url: str, body: Any = None) -> Any:
        return self.client.post(url, json=body, headers=self.accounts.headers(who))

    def edit(self, who: str, scene_id: str, *edits: dict[str, str]) -> Any:
        revision = self.get(who, f"/api/scenes/{scene_id}")["revision"]
        body = {"base_revision": revision, "author": "ignored", "edits": list(edits)}
        return self.post(who, f"/api/scenes/{scene_id}/edits", body)

    def workflow(self, scene_id: str) -> Any:
        return self.get("ada", f"/api/scenes/{scene_id}/workflow")

    def act(self, who: str, scene_id: str, action: str, **body: Any) -> Any:
        body.setdefault("revision", self.workflow(scene_id)["revision"])
        return self.post(who, f"/api/scenes/{scene_id}/{action}", body)

    def snapshot(self, scene_id: str) -> tuple[Any, ...]:
        """Everything a refused request must leave as it was."""
        flow = self.workflow(scene_id)
        revisions = self.get("ada", f"/api/scenes/{scene_id}/revisions")
        return (flow["state"], flow["assignee"], flow["revision"], len(flow["events"]), revisions)


@pytest.fixture()
def api(accounts: Accounts) -> Api:
    return Api(accounts)


def _refused(api: Api, scene_id: str, response: Any, status: int, message: str) -> None:
    assert response.status_code == status, response.text
    detail = response.json()["detail"]
    text = detail["message"] if isinstance(detail, dict) else detail
    assert message in text, text


def test_a_scene_goes_through_every_state(api: Api, accounts: Accounts) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    flow = api.workflow(scene_id)
    assert (flow["state"], flow["assignee"]) == ("predicted", None)
    assert [(e["action"], e["actor"], e["to_state"]) for e in flow["events"]] == [
        ("import", "test", "new"),
        ("predict", "pipeline", "predicted"),
    ]

    # The first edit takes the scene; the author is the account, whatever the body says.
    edited = api.edit("ann", scene_id, _set("o2", "floor"))
    assert edited.status_code == 200, edited.text
    support = next(s for s in edited.json()["scene"]["supports"] if s["child"] == "o2")
    assert (support["author"], support["source"]) == ("ann", "manual")
    flow = api.workflow(scene_id)
    assert (flow["state"], flow["assignee"]) == ("in_annotation", "ann")
    summary = next(s for s in api.get("bob", "/api/scenes") if s["id"] == scene_id)
    assert (summary["state"], summary["assignee"]) == ("in_annotation", "ann")

    # Someone else's scene: no edits, no submission; nothing changes.
    before = api.snapshot(scene_id)
    _refused(api, scene_id, api.edit("bob", scene_id, _set("o1", "floor")), 409, "annotated by ann")
    _refused(api, scene_id, api.act("bob", scene_id, "submit"), 409, "only the annotator")
    _refused(
        api, scene_id, api.post("bob", f"/api/scenes/{scene_id}/take"), 409, "annotated by ann"
    )
    # Submitting an older revision than the latest is refused too.
    stale = api.act("ann", scene_id, "submit", revision=flow["revision"] - 1)
    _refused(api, scene_id, stale, 409, "changed since you loaded it")
    # Annotators do not review.
    _refused(api, scene_id, api.act("ann", scene_id, "accept"), 403, "needs the reviewer role")
    assert api.snapshot(scene_id) == before

    submitted = api.act("ann", scene_id, "submit")
    assert submitted.status_code == 200 and submitted.json()["state"] == "submitted"
    before = api.snapshot(scene_id)
    _refused(api, scene_id, api.edit("ann", scene_id, _set("o1", "floor")), 409, "submitted")
    pipeline = api.post("ann", f"/api/scenes/{scene_id}/pipeline-jobs")
    _refused(api, scene_id, pipeline, 409, "cannot re-run")
    # A rejection says what went wrong.
    _refused(api, scene_id, api.act("rita", scene_id, "reject"), 422, "comment")
    _refused(api, scene_id, api.act("rita", scene_id, "reject", comment="   "), 422, "comment")
    assert api.snapshot(scene_id) == before

    comment = "The books lie on the table, not on the floor."
    rejected = api.act("rita", scene_id, "reject", comment=comment)
    assert rejected.status_code == 200, rejected.text
    flow = rejected.json()
    assert (flow["state"], flow["assignee"], flow["review_comment"]) == (
        "rejected",
        "ann",
        comment,
    )
    _refused(api, scene_id, api.act("rita", scene_id, "accept"), 409, "only a submitted scene")
    _refused(api, scene_id, api.edit("bob", scene_id, _set("o2", "o0")), 409, "sent back to ann")

    # The annotator fixes it (the edit reopens it) and submits again; another reviewer accepts.
    assert api.edit("ann", scene_id, _set("o2", "o0")).status_code == 200
    flow = api.workflow(scene_id)
    # The comment stays in view while the annotator works on it, until the next submission.
    assert (flow["state"], flow["review_comment"]) == ("in_annotation", comment)
    submitted = api.act("ann", scene_id, "submit")
    assert submitted.status_code == 200 and submitted.json()["review_comment"] is None
    accepted = api.act("rex", scene_id, "accept")
    assert accepted.status_code == 200 and accepted.json()["state"] == "accepted"
    assert accepted.json()["review_comment"] is None
    _refused(api, scene_id, api.edit("ann", scene_id, _set("o1", "floor")), 409, "accepted")

    flow = api.workflow(scene_id)
    assert [(e["action"], e["actor"], e["from_state"], e["to_state"]) for e in flow["events"]] == [
        ("import", "test", None, "new"),
        ("predict", "pipeline", "new", "predicted"),
        ("claim", "ann", "predicted", "in_annotation"),
        ("submit", "ann", "in_annotation", "submitted"),
        ("reject", "rita", "submitted", "rejected"),
        ("reopen", "ann", "rejected", "in_annotation"),
        ("submit", "ann", "in_annotation", "submitted"),
        ("accept", "rex", "submitted", "accepted"),
    ]
    assert flow["events"][4]["comment"] == comment
    assert all(e["assignee"] == "ann" for e in flow["events"][2:])
    # The list's "Updated" is the latest step (the acceptance), not the latest revision only.
    summary = next(s for s in api.get("bob", "/api/scenes") if s["id"] == scene_id)
    accepted_at = datetime.fromisoformat(flow["events"][-1]["at"])
    assert datetime.fromisoformat(summary["last_activity_at"]) == accepted_at
    assert datetime.fromisoformat(summary["updated_at"]) < accepted_at


def test_a_scene_taken_by_mistake_is_given_back_with_its_edits(
    api: Api, accounts: Accounts
) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    edited = api.edit("ann", scene_id, _set("o2", "floor"))
    assert edited.status_code == 200, edited.text
    before = api.snapshot(scene_id)
    _refused(api, scene_id, api.act("bob", scene_id, "release"), 409, "only they or an admin")
    stale = api.act("ann", scene_id, "release", revision=edited.json()["revision"] - 1)
    _refused(api, scene_id, stale, 409, "changed since you loaded it")
    assert api.snapshot(scene_id) == before

    released = api.act("ann", scene_id, "release")
    assert released.status_code == 200, released.text
    flow = released.json()
    assert (flow["state"], flow["assignee"]) == ("predicted", None)
    assert flow["events"][-1]["action"] == "release"
    assert flow["revision"] == edited.json()["revision"]  # the edit stays
    _refused(api, scene_id, api.act("ann", scene_id, "release"), 409, "only a scene in annotation")
    # ann's next scene is another one: the scene she gave back comes after all others.
    other = store_predicted_scene(
        accounts.workbench.scenes,
        name="less uncertain",
        confidences={"o0": 0.99, "o1": 0.99, "o2": 0.99, "o3": 0.99},
    )
    assert api.workflow(other)["state"] == "predicted"
    mine = api.post("ann", "/api/scenes/next")
    assert mine.status_code == 200 and mine.json()["id"] == other
    # It waits for the next annotator, who gets it with ann's edit.
    taken = api.post("bob", "/api/scenes/next")
    assert taken.status_code == 200 and taken.json()["id"] == scene_id
    assert taken.json()["assignee"] == "bob"
    doc = api.get("bob", f"/api/scenes/{scene_id}")
    assert any(s["child"] == "o2" and s["author"] == "ann" for s in doc["scene"]["supports"])

    # Sent back by a reviewer: its annotator fixes it; an admin may still give it back.
    assert api.act("bob", scene_id, "submit").status_code == 200
    assert (
        api.act("rita", scene_id, "reject", comment="o1 is on the wrong thing").status_code == 200
    )
    assert api.edit("bob", scene_id, _set("o1", "floor")).status_code == 200
    _refused(api, scene_id, api.act("bob", scene_id, "release"), 409, "sent back by a reviewer")
    by_admin = api.act("ada", scene_id, "release")
    assert by_admin.status_code == 200, by_admin.text
    assert (by_admin.json()["state"], by_admin.json()["assignee"]) == ("predicted", None)


def test_a_submission_is_taken_back_by_its_annotator_until_a_reviewer_decides(
    api: Api, accounts: Accounts
) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    assert api.edit("ann", scene_id, _set("o2", "floor")).status_code == 200
    submitted = api.act("ann", scene_id, "submit")
    assert submitted.status_code == 200, submitted.text
    before = api.snapshot(scene_id)
    _refused(api, scene_id, api.act("bob", scene_id, "withdraw"), 409, "only the annotator who")
    _refused(api, scene_id, api.act("rita", scene_id, "withdraw"), 409, "sends it back")
    assert api.snapshot(scene_id) == before

    back = api.act("ann", scene_id, "withdraw")
    assert back.status_code == 200, back.text
    flow = back.json()
    assert (flow["state"], flow["assignee"]) == ("in_annotation", "ann")
    assert flow["events"][-1]["action"] == "withdraw"
    assert flow["editable"] is True
    # Hers to edit again; the reviewer's queue no longer holds it.
    assert api.edit("ann", scene_id, _set("o1", "floor")).status_code == 200
    _refused(api, scene_id, api.act("rita", scene_id, "accept"), 409, "only a submitted scene")
    assert api.act("ann", scene_id, "submit").status_code == 200
    assert api.act("rita", scene_id, "accept").status_code == 200
    _refused(api, scene_id, api.act("ann", scene_id, "withdraw"), 409, "only a submitted scene")
    # The dashboard counts one submission: the one taken back never reached a reviewer.
    people = {p["name"]: p for p in api.get("ada", "/api/dashboard")["people"]}
    assert (people["ann"]["submitted"], people["ann"]["accepted"]) == (1, 1)


def test_an_admin_takes_a_scene_over_by_taking_it_not_by_an_edit(
    api: Api, accounts: Accounts
) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    assert api.edit("ann", scene_id, _set("o2", "floor")).status_code == 200
    before = api.snapshot(scene_id)
    refused = api.edit("ada", scene_id, _set("o1", "floor"))
    _refused(api, scene_id, refused, 409, "being annotated by ann: take it over to edit it")
    doc = api.get("ada", f"/api/scenes/{scene_id}")
    assert doc["editable"] is False and "take it over" in doc["editable_reason"]
    assert api.snapshot(scene_id) == before

    taken = api.post("ada", f"/api/scenes/{scene_id}/take")
    assert taken.status_code == 200 and taken.json()["assignee"] == "ada"
    assert api.edit("ada", scene_id, _set("o1", "floor")).status_code == 200
    _refused(api, scene_id, api.edit("ann", scene_id, _set("o3", "floor")), 409, "by ada")


def test_reviewers_do_not_review_their_own_work(api: Api, accounts: Accounts) -> None:
    scene_id = store_predicted_scene(accounts.workbench.scenes)
    assert api.post("rita", f"/api/scenes/{scene_id}/take").json()["assignee"] == "rita"
    assert api.act("rita", scene_id, "submit").status_code == 200
    _refused(api, scene_id, api.act("rita", scene_id, "accept"), 409, "another reviewer")
    assert api.act("rex", scene_id, "accept").status_code == 200


def test_next_to_review_opens_the_oldest_submitted_scene_of_someone_else(
    api: Api, accounts: Accounts
) -> None:
    scenes = accounts.workbench.scenes
    older, newer, own = (store_predicted_scene(scenes, name) for name in ("a", "b", "c"))
    for who, scene_id in (("ann", older), ("bob", newer), ("rita", own)):
        assert api.post(who, f"/api/scenes/{scene_id}/take").status_code == 200
    for who, scene_id in (("ann", older), ("bob", newer), ("rita", own)):
        assert api.act(who, scene_id, "submit").status_code == 200
    before = api.snapshot(older)
    assert api.get("rita", "/api/scenes/next-review")["id"] == older
    assert api.snapshot(older) == before  # opening it to review assigns nothing
    assert api.act("rex", older, "accept").status_code == 200
    assert api.get("rita", "/api/scenes/next-review")["id"] == newer
    assert api.act("rex", newer, "reject", comment="o1 is on the desk").status_code == 200
    # Only rita's own submission waits: not for her, but for rex.
    nothing = api.client.get("/api/scenes/next-review", headers=accounts.headers("rita"))
    assert nothing.status_code == 404 and "review" in nothing.json()["detail"]
    assert api.get("rex", "/api/scenes/next-review")["id"] == own
    refused = api.client.get("/api/scenes/next-review", headers=accounts.headers("ann"))
    assert refused.status_code == 403


def test_next_to_review_after_the_open_scene_moves_through_the_queue(
    api: Api, accounts: Accounts
) -> None:
    scenes = accounts.workbench.scenes
    queue = [store_predicted_scene(scenes, name) for name in ("a", "b", "c")]
    for scene_id in queue:
        assert api.post("ann", f"/api/scenes/{scene_id}/take").status_code == 200
        assert api.act("ann", scene_id, "submit").status_code == 200
    first, second, third = queue

    def after(scene_id: str) -> str:
        return str(api.get("rita", f"/api/scenes/next-review?after={scene_id}")["id"])

    # Skipping goes on through the queue and round to the oldest, never the scene open.
    assert [after(first), after(second), after(third)] == [second, third, first]
    assert after("no-such-scene") == first
    assert api.act("rex", second, "accept").status_code == 200
    assert api.act("rex", third, "accept").status_code == 200
    alone = api.client.get(
        f"/api/scenes/next-review?after={first}", headers=accounts.headers("rita")
    )
    assert alone.status_code == 404 and "other than this one" in alone.json()["detail"]


def test_next_scene_picks_the_most_uncertain_first(api: Api, accounts: Accounts) -> None:
    scenes = accounts.workbench.scenes
    # Mean doubt (1 - confidence) over 4 objects, 0.9 unless given:
    # sure (0.1 * 4) / 4 = 0.1; unsure (0.1 + 0.6 * 3) / 4 = 0.475; middle (0.1 + 0.6 + 0.4
    # + 0.1) / 4 = 0.3.
    sure = store_predicted_scene(scenes, "sure")
    unsure = store_predicted_scene(scenes, "unsure", {"o1": 0.4, "o2": 0.4, "o3": 0.4})
    middle = store_predicted_scene(scenes, "middle", {"o1": 0.4, "o2": 0.6})
    listed = {s["name"]: s["uncertainty"] for s in api.get("ann", "/api/scenes")}
    assert listed == pytest.approx({"sure": 0.1, "unsure": 0.475, "middle": 0.3})

    first = api.post("ann", "/api/scenes/next")
    assert first.status_code == 200, first.text
    assert (first.json()["id"], first.json()["state"], first.json()["assignee"]) == (
        unsure,
        "in_annotation",
        "ann",
    )
    assert api.post("bob", "/api/scenes/next").json()["id"] == middle
    assert api.post("ann", "/api/scenes/next").json()["id"] == sure
    nothing = api.post("bob", "/api/scenes/next")
    assert nothing.status_code == 404 and "no scene is waiting" in nothing.json()["detail"]
    assert api.get("ann", "/api/scenes?state=predicted") == []
    mine = api.get("ann", "/api/scenes?state=in_annotation")
    assert sorted(s["name"] for s in mine) == ["middle", "sure", "unsure"]

    # A scene a reviewer sent back to its annotator comes before any new one.
    newer = store_predicted_scene(scenes, "newer", {"o0": 0.1})
    assert api.act("ann", unsure, "submit").status_code == 200
    assert api.act("rita", unsure, "reject", comment="o3 stands on o0").status_code == 200
    back = api.post("ann", "/api/scenes/next").json()
    assert (back["id"], back["state"]) == (unsure, "in_annotation")
    assert api.post("ann", "/api/scenes/next").json()["id"] == newer


def test_next_scene_offers_a_scene_without_objects_first(api: Api, accounts: Accounts) -> None:
    scenes = accounts.workbench.scenes
    # Stored before the empty one: as uncertain (no object has a supporter), and less.
    unsupported = store_predicted_scene(scenes, "unsupported", supports=[])
    unsure = store_predicted_scene(scenes, "unsure", {"o1": 0.4, "o2": 0.4, "o3": 0.4})
    empty = store_predicted_scene(scenes, "empty", with_objects=False)
    listed = {s["name"]: s["uncertainty"] for s in api.get("ann", "/api/scenes")}
    assert listed == pytest.approx({"unsupported": 1.0, "unsure": 0.475, "empty": 1.0})

    assert api.post("ann", "/api/scenes/next").json()["id"] == empty
    assert api.post("bob", "/api/scenes/next").json()["id"] == unsupported
    assert api.post("ann", "/api/scenes/next").json()["id"] == unsure


def test_second_annotation_agreement_and_dashboard(api: Api, accounts: Accounts) -> None:
    scenes = accounts.workbench.scenes
    scene_id = store_predicted_scene(scenes, "twice")
    other = store_predicted_scene(scenes, "once")

    # Round 1: ann moves o2 (books) onto the floor and o3 (chair) behind the wall.
    assert api.post("ann", "/api/scenes/next").json()["id"] == scene_id
    assert api.edit("ann", scene_id, _set("o2", "floor"), _set("o3", "w", "behind")).is_success
    assert api.act("ann", scene_id, "submit").status_code == 200
    assert api.act("rita", scene_id, "accept").status_code == 200
    round_1 = api.workflow(scene_id)["revision"]

    # Only reviewers ask for a second annotation, of a submitted or accepted scene.
    _refused(api, scene_id, api.act("ann", scene_id, "second-annotation"), 403, "reviewer")
    _refused(api, other, api.act("rita", other, "second-annotation"), 409, "submitted or accepted")
    again = api.act("rita", scene_id, "second-annotation", comment="agreement check")
    assert again.status_code == 200, again.text
    flow = again.json()
    assert (flow["state"], flow["assignee"], flow["annotation_round"]) == ("predicted", None, 2)
    # The second annotator starts from the pipeline's guesses, not from ann's labels.
    reset = api.get("bob", f"/api/scenes/{scene_id}")
    assert reset["revision"] == round_1 + 1
    supports = {
        s["child"]: (s["parent"], s["type"], s["source"]) for s in reset["scene"]["supports"]
    }
    assert supports == {
        "o0": ("floor", "below", "auto"),
        "o1": ("o0", "below", "auto"),
        "o2": ("o0", "below", "auto"),
        "o3": ("floor", "below", "auto"),
    }
    history = api.get("bob", f"/api/scenes/{scene_id}/revisions")
    assert (history[-1]["kind"], history[-1]["author"]) == ("reset", "rita")

    # ann labelled round 1, so round 2 is not hers: Next gives her the other scene.
    assert api.post("ann", "/api/scenes/next").json()["id"] == other
    _refused(api, scene_id, api.edit("ann", scene_id, _set("o1", "floor")), 409, "earlier round")
    # bob: o2 onto the floor like ann, o3 stays on the floor (ann: behind the wall), o1 on
    # the floor (ann: on the table). Agreement: o0 and o2 of 4 objects.
    assert api.post("bob", "/api/scenes/next").json()["id"] == scene_id
    assert api.edit("bob", scene_id, _set("o2", "floor"), _set("o1", "floor")).is_success
    assert api.act("bob", scene_id, "submit").status_code == 200
    round_2 = api.workflow(scene_id)["revision"]
    assert api.act("rex", scene_id, "reject", comment="o1 is on the table").status_code == 200

    dashboard = api.get("ann", "/api/dashboard")
    assert dashboard["states"] == {
        "new": 0,
        "predicted": 0,
        "in_annotation": 1,
        "submitted": 0,
        "accepted": 0,
        "rejected": 1,
    }
    assert dashboard["agreement"] == [
        {
            "scene_id": scene_id,
            "name": "twice",
            "annotators": ["ann", "bob"],
            "revisions": [round_1, round_2],
            "objects": 4,
            "matching": 2,
            "agreement": 0.5,
        }
    ]
    assert dashboard["mean_agreement"] == 0.5
    people = {p["name"]: p for p in dashboard["people"]}
    assert set(people) == {"ada", "ann", "bob", "rex", "rita"}
    assert {k: v for k, v in people["ann"].items() if k != "name"} == {
        "role": "annotator",
        "in_annotation": 1,
        "submitted": 1,
        "accepted": 1,
        "rejected": 0,
        "reviewed": 0,
    }
    assert (people["bob"]["submitted"], people["bob"]["rejected"]) == (1, 1)
    assert (people["rita"]["reviewed"], people["rex"]["reviewed"]) == (1, 1)
    assert people["ada"]["submitted"] == 0


def test_pipeline_result_is_not_stored_on_a_submitted_scene(api: Api, accounts: Accounts) -> None:
    """A pipeline run that ends after the annotator submitted must not change the scene under
    the reviewer: the run's result is refused, the submitted revision stays."""
    scenes = accounts.workbench.scenes
    scene_id = store_predicted_scene(scenes)
    assert api.post("ann", f"/api/scenes/{scene_id}/take").status_code == 200
    assert api.act("ann", scene_id, "submit").status_code == 200
    before = api.snapshot(scene_id)
    current = scenes.document(scene_id).scene
    with pytest.raises(WorkflowError, match=r"submitted.*not stored"):
        scenes.commit_pipeline_result(scene_id, current, None)
    assert api.snapshot(scene_id) == before  # same revisions, state and history


def test_an_archived_scene_leaves_the_lists_and_nobody_works_on_it(
    api: Api, accounts: Accounts
) -> None:
    scenes = accounts.workbench.scenes
    kept = store_predicted_scene(scenes, "kept", {"o1": 0.9, "o2": 0.9, "o3": 0.9})
    junk = store_predicted_scene(scenes, "all black", with_objects=False)  # the most uncertain
    before = api.snapshot(junk)

    # Only an admin archives.
    _refused(api, junk, api.post("rex", f"/api/scenes/{junk}/archive"), 403, "admin")
    archived = api.post("ada", f"/api/scenes/{junk}/archive")
    assert archived.status_code == 200, archived.text
    assert archived.json()["archived_by"] == "ada" and archived.json()["archived_at"]

    # Out of the list, "Next scene" and the dashboard's counts; listed on request.
    assert [s["name"] for s in api.get("ann", "/api/scenes")] == ["kept"]
    assert [s["id"] for s in api.get("ann", "/api/scenes?archived=only")] == [junk]
    assert len(api.get("ann", "/api/scenes?archived=include")) == 2
    assert api.get("ann", "/api/dashboard")["states"]["predicted"] == 1
    assert api.post("ann", "/api/scenes/next").json()["id"] == kept

    # Read only for everyone, admins too, with the reason; nothing written.
    document = api.get("bob", f"/api/scenes/{junk}")
    assert document["editable"] is False
    assert "archived by ada" in document["editable_reason"]
    refused = api.edit("ada", junk, _set("o1", "floor"))
    _refused(api, junk, refused, 409, "archived by ada")
    _refused(api, junk, api.post("ada", f"/api/scenes/{junk}/take"), 409, "archived by ada")
    _refused(api, junk, api.act("ada", junk, "submit"), 409, "archived by ada")
    assert api.workflow(junk)["archived_by"] == "ada"
    pipeline = api.post("ada", f"/api/scenes/{junk}/pipeline-jobs")
    _refused(api, junk, pipeline, 409, "archived by ada")
    flow, assignee, revision, events, revisions = api.snapshot(junk)
    assert (flow, assignee, revision, events - 1, revisions) == before  # the archive step only

    # Restored as it was: listed, and "Next scene" offers it again; the history says both.
    restored = api.post("ada", f"/api/scenes/{junk}/unarchive")
    assert restored.status_code == 200, restored.text
    assert restored.json()["archived_at"] is None
    steps = [(e["action"], e["actor"]) for e in api.workflow(junk)["events"]]
    assert steps[-2:] == [("archive", "ada"), ("unarchive", "ada")]
    assert api.get("bob", f"/api/scenes/{junk}")["editable"] is True
    assert api.post("bob", "/api/scenes/next").json()["id"] == junk
