"""A pipeline or placement job and a save that lands while it runs: the job's result must not
silently overwrite the newer revision.

The job is held at its last progress report (every stage done, its result not yet stored) by
a real threading.Event, while the test saves through the API; then it is let go.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from holiscene.core.settings import Settings
from holiscene.editing.workflow_rules import Actor, WorkflowError
from holiscene.services.workbench import Workbench
from holiscene.store.jobs import JobStore
from holiscene.store.scenes import SceneChangedError
from holiscene_schema import EditRequest

from ..conftest import upload, wait_for_job
from ..editing.test_layout import _moved_corners
from ..stored_scenes import store_predicted_scene

# The store, as the server uses it, on SQLite and on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases


class Gate:
    """Wraps JobStore.progress: once armed, the next job that reports "done" (its result
    computed, not stored yet) waits there until the test opens the gate."""

    def __init__(self, jobs: JobStore) -> None:
        self._progress = jobs.progress
        self.armed = threading.Event()
        self.reached = threading.Event()
        self.open = threading.Event()

    def __call__(self, job_id: str, stage: str, fraction: float) -> None:
        self._progress(job_id, stage, fraction)
        if stage == "done" and self.armed.is_set():
            self.armed.clear()
            self.reached.set()
            if not self.open.wait(60):
                raise TimeoutError("the test never let the job go on")


@pytest.fixture()
def gate(client: TestClient, monkeypatch: pytest.MonkeyPatch) -> Iterator[Gate]:
    jobs = _workbench(client).jobs
    held = Gate(jobs)
    monkeypatch.setattr(jobs, "progress", held)
    yield held
    held.open.set()  # never leave a job thread waiting


def _workbench(client: TestClient) -> Workbench:
    workbench: Workbench = client.app.state.workbench  # type: ignore[attr-defined]
    return workbench


def _scene(client: TestClient, scene_id: str) -> Any:
    return client.get(f"/api/scenes/{scene_id}").json()


def _save(client: TestClient, scene_id: str, base: int, edit: dict[str, Any]) -> Any:
    body = {"base_revision": base, "author": "ann", "edits": [edit]}
    response = client.post(f"/api/scenes/{scene_id}/edits", json=body)
    assert response.status_code == 200, response.text
    return response.json()


def _layout_edit(doc: Any, dy: float) -> dict[str, Any]:
    return {"kind": "set_layout", "corners_2d": _moved_corners(doc, dy)}


def _support_edit(doc: Any) -> dict[str, Any]:
    """Another supporter for the first supported object: the wall instead of the floor, else
    the floor."""
    first = doc["scene"]["supports"][0]
    parent, kind = ("wall", "behind") if first["parent"] == "floor" else ("floor", "below")
    return {"kind": "set_support", "child": first["child"], "parent": parent, "type": kind}


def _predicted(client: TestClient, t3d5: Path) -> str:
    result = upload(client, t3d5, name="t3d-5")
    assert wait_for_job(client, result["job"]["id"])["status"] == "succeeded"
    return str(result["scene"]["id"])


def _start(client: TestClient, gate: Gate, scene_id: str, kind: str) -> Any:
    gate.armed.set()
    started = client.post(f"/api/scenes/{scene_id}/{kind}-jobs")
    assert started.status_code == 202, started.text
    assert gate.reached.wait(60), "the job never finished its stages"
    return started.json()


@pytest.mark.parametrize("saved", ["layout", "support"])
def test_placement_job_does_not_overwrite_a_save_made_while_it_ran(
    client: TestClient, t3d5: Path, gate: Gate, saved: str
) -> None:
    scene_id = _predicted(client, t3d5)
    doc = _scene(client, scene_id)
    laid_out = _save(client, scene_id, doc["revision"], _layout_edit(doc, 25.0))
    base = laid_out["revision"]

    job = _start(client, gate, scene_id, "placement")
    assert job["base_revision"] == base
    # The job read revision `base` and placed the objects; now someone saves on top of it.
    edit = _layout_edit(laid_out, 50.0) if saved == "layout" else _support_edit(laid_out)
    newer = _save(client, scene_id, base, edit)
    assert newer["revision"] == base + 1
    gate.open.set()

    finished = wait_for_job(client, job["id"], timeout=60)
    assert finished["status"] == "failed"
    assert finished["result_revision"] is None
    assert finished["error"] == (
        f"the scene changed while objects were being re-placed (revision {base} -> "
        f"{base + 1}); nothing was overwritten; run re-place again"
    )
    # The newer revision is intact and still the latest; no revision or GLB was added.
    current = _scene(client, scene_id)
    assert current["revision"] == newer["revision"]
    assert current["scene"] == newer["scene"]
    assert len(client.get(f"/api/scenes/{scene_id}/revisions").json()) == newer["revision"]
    files = _workbench(client).scenes.files
    assert not files.glb_path(scene_id, base + 2).exists()

    # Placing again starts from the newer revision and is stored.
    again = client.post(f"/api/scenes/{scene_id}/placement-jobs").json()
    placed = wait_for_job(client, again["id"], timeout=60)
    assert (placed["status"], placed["base_revision"]) == ("succeeded", newer["revision"])
    stored = _scene(client, scene_id)["scene"]
    assert stored["layout"] == newer["scene"]["layout"]
    assert stored["supports"] == newer["scene"]["supports"]


def test_pipeline_rerun_does_not_overwrite_a_layout_set_while_it_ran(
    client: TestClient, t3d5: Path, gate: Gate
) -> None:
    scene_id = _predicted(client, t3d5)
    doc = _scene(client, scene_id)

    job = _start(client, gate, scene_id, "pipeline")
    newer = _save(client, scene_id, doc["revision"], _layout_edit(doc, 25.0))
    gate.open.set()

    finished = wait_for_job(client, job["id"], timeout=60)
    assert finished["status"] == "failed"
    assert finished["error"].startswith(
        f"the room layout was set by hand while the pipeline ran (revision {doc['revision']} "
        f"-> {newer['revision']}); the run's result was not stored"
    )
    current = _scene(client, scene_id)
    assert current["revision"] == newer["revision"]
    assert current["scene"]["layout"]["source"] == "manual"
    assert current["scene"] == newer["scene"]


def test_pipeline_rerun_keeps_supports_set_while_it_ran(
    client: TestClient, t3d5: Path, gate: Gate
) -> None:
    """Support edits made during a whole re-run are merged into its result, as before: the
    run does not depend on them, and people's supporters win."""
    scene_id = _predicted(client, t3d5)
    doc = _scene(client, scene_id)

    job = _start(client, gate, scene_id, "pipeline")
    edit = _support_edit(doc)
    newer = _save(client, scene_id, doc["revision"], edit)
    gate.open.set()

    finished = wait_for_job(client, job["id"], timeout=60)
    assert finished["status"] == "succeeded", finished["error"]
    assert finished["result_revision"] == newer["revision"] + 1
    supports = {s["child"]: s for s in _scene(client, scene_id)["scene"]["supports"]}
    kept = supports[edit["child"]]
    assert (kept["parent"], kept["source"]) == (edit["parent"], "manual")


def test_store_refuses_a_placement_result_on_a_moved_scene(settings: Settings) -> None:
    """The store's side: a stale base writes nothing (no revision, no GLB), and a scene
    submitted meanwhile refuses the result before any file is written."""
    workbench = Workbench(settings)
    try:
        scenes = workbench.scenes
        scene_id = store_predicted_scene(scenes)
        base = scenes.document(scene_id)
        edit = _support_edit({"scene": base.scene.model_dump(mode="json")})
        request = EditRequest.model_validate(
            {"base_revision": base.revision, "author": "ann", "edits": [edit]}
        )
        scenes.apply_edits(scene_id, request)
        with pytest.raises(SceneChangedError) as raised:
            scenes.commit_placement_result(scene_id, base.revision, base.scene, b"glTF")
        assert (raised.value.base_revision, raised.value.current_revision) == (2, 3)
        assert scenes.document(scene_id).revision == 3
        assert not scenes.files.glb_path(scene_id, 3).exists()

        current = scenes.document(scene_id)
        ann = Actor("ann", "annotator")
        workbench.workflow.take(scene_id, ann)
        workbench.workflow.submit(scene_id, current.revision, ann)
        with pytest.raises(WorkflowError, match="not stored"):
            scenes.commit_placement_result(scene_id, current.revision, current.scene, b"glTF")
        assert scenes.document(scene_id).revision == current.revision
        assert not scenes.files.glb_path(scene_id, current.revision + 1).exists()
    finally:
        workbench.close()
