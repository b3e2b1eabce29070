"""The HTTP API: import, pipeline job, edits with revisions, conflicts, and refusals."""

from __future__ import annotations

from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.core.settings import Settings

from ...bad_inputs import BAD_DETECTIONS, NOT_AN_IMAGE, png_header_only, truncated
from ...conftest import upload, wait_for_job


def _imported(client: TestClient, folder: Path) -> tuple[str, dict]:  # type: ignore[type-arg]
    result = upload(client, folder, name="t3d-5")
    job = wait_for_job(client, result["job"]["id"])
    assert job["status"] == "succeeded", job
    doc = client.get(f"/api/scenes/{result['scene']['id']}").json()
    return result["scene"]["id"], doc


def _edit(client: TestClient, scene_id: str, base: int, *edits: dict, author: str = "ann"):  # type: ignore[no-untyped-def, type-arg]
    body = {"base_revision": base, "author": author, "edits": list(edits)}
    return client.post(f"/api/scenes/{scene_id}/edits", json=body)


def test_import_runs_pipeline_and_serves_files(client: TestClient, t3d5: Path) -> None:
    scene_id, doc = _imported(client, t3d5)
    assert doc["revision"] == 2  # 1 = import, 2 = pipeline
    scene = doc["scene"]
    assert [o["class"] for o in scene["objects"]] == ["bed", "night_stand", "dresser", "dresser"]
    assert all(o["mask"] is not None for o in scene["objects"])
    assert len(scene["supports"]) == 4
    # The stored guesses name the model that made them, as the model registry counts it.
    models = {run["name"]: run["model"] for run in scene["stages"]}
    assert models["supports_from_network"] == "Relation Network v1"
    assert models["masks_grabcut"] is None
    listed = client.get("/api/scenes").json()
    assert [s["id"] for s in listed] == [scene_id]
    assert listed[0]["latest_job"]["status"] == "succeeded"
    image = client.get(f"/api/scenes/{scene_id}/image")
    assert image.status_code == 200 and image.content == (t3d5 / "img.jpg").read_bytes()
    glb = client.get(f"/api/scenes/{scene_id}/scene.glb")
    assert glb.status_code == 200 and glb.content[:4] == b"glTF"


@pytest.mark.both_databases
def test_edit_creates_revision_with_history(client: TestClient, t3d5: Path) -> None:
    scene_id, doc = _imported(client, t3d5)
    response = _edit(
        client,
        scene_id,
        doc["revision"],
        {"kind": "set_support", "child": "o1", "parent": "o0", "type": "behind"},
    )
    assert response.status_code == 200, response.text
    edited = response.json()
    assert edited["revision"] == doc["revision"] + 1
    support = next(s for s in edited["scene"]["supports"] if s["child"] == "o1")
    assert (support["parent"], support["type"], support["source"], support["author"]) == (
        "o0",
        "behind",
        "manual",
        "ann",
    )
    assert support["time"] is not None

    history = client.get(f"/api/scenes/{scene_id}/revisions").json()
    assert [r["kind"] for r in history] == ["import", "pipeline", "edit"]
    assert history[-1]["author"] == "ann"
    assert history[-1]["edits"][0]["parent"] == "o0"
    before = client.get(f"/api/scenes/{scene_id}/revisions/{doc['revision']}").json()
    assert next(s for s in before["scene"]["supports"] if s["child"] == "o1")["parent"] == "floor"


@pytest.mark.both_databases
def test_stale_write_gets_409_and_changes_nothing(client: TestClient, t3d5: Path) -> None:
    scene_id, doc = _imported(client, t3d5)
    base = doc["revision"]
    first = _edit(
        client,
        scene_id,
        base,
        {"kind": "set_support", "child": "o1", "parent": "wall", "type": "behind"},
    )
    assert first.status_code == 200
    second = _edit(
        client,
        scene_id,
        base,
        {"kind": "set_support", "child": "o2", "parent": "wall", "type": "behind"},
    )
    assert second.status_code == 409
    assert second.json()["detail"]["current_revision"] == base + 1
    now = client.get(f"/api/scenes/{scene_id}").json()
    assert now["revision"] == base + 1
    assert next(s for s in now["scene"]["supports"] if s["child"] == "o2")["parent"] == "floor"


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        ({"kind": "set_support", "child": "o1", "parent": "o1", "type": "below"}, "itself"),
        ({"kind": "set_support", "child": "o9", "parent": "floor", "type": "below"}, "no object"),
        ({"kind": "set_support", "child": "o1", "parent": "sky", "type": "below"}, "neither"),
        ({"kind": "set_support", "child": "o1", "parent": "floor", "type": "above"}, "type"),
        # Types no part of the room holds anything up by.
        (
            {"kind": "set_support", "child": "o1", "parent": "floor", "type": "behind"},
            "the floor holds objects up from below only",
        ),
        (
            {"kind": "set_support", "child": "o1", "parent": "wall", "type": "below"},
            "the wall holds objects up from behind only",
        ),
        (
            {"kind": "set_support", "child": "o1", "parent": "ceiling", "type": "below"},
            "the ceiling holds objects up from behind only",
        ),
    ],
)
def test_invalid_edits_are_refused(
    client: TestClient, t3d5: Path, edit: dict, message: str
) -> None:  # type: ignore[type-arg]
    scene_id, doc = _imported(client, t3d5)
    response = _edit(client, scene_id, doc["revision"], edit)
    assert response.status_code == 422
    assert message in response.json()["detail"]
    assert client.get(f"/api/scenes/{scene_id}").json()["revision"] == doc["revision"]


@pytest.mark.both_databases
def test_edit_closing_a_cycle_is_refused_whole(client: TestClient, t3d5: Path) -> None:
    scene_id, doc = _imported(client, t3d5)
    response = _edit(
        client,
        scene_id,
        doc["revision"],
        {"kind": "set_support", "child": "o1", "parent": "o2", "type": "below"},
        {"kind": "set_support", "child": "o2", "parent": "o1", "type": "below"},
    )
    assert response.status_code == 422
    assert "cycle" in response.json()["detail"]
    assert client.get(f"/api/scenes/{scene_id}/revisions").json()[-1]["kind"] == "pipeline"


@pytest.mark.both_databases
def test_manual_support_survives_pipeline_rerun(client: TestClient, t3d5: Path) -> None:
    scene_id, doc = _imported(client, t3d5)
    edited = _edit(
        client,
        scene_id,
        doc["revision"],
        {"kind": "set_support", "child": "o3", "parent": "o2", "type": "below"},
    ).json()
    job = client.post(f"/api/scenes/{scene_id}/pipeline-jobs").json()
    assert wait_for_job(client, job["id"])["status"] == "succeeded"
    after = client.get(f"/api/scenes/{scene_id}").json()
    assert after["revision"] == edited["revision"] + 1
    kept = next(s for s in after["scene"]["supports"] if s["child"] == "o3")
    assert (kept["parent"], kept["source"]) == ("o2", "manual")
    # The run is listed under the person who started it, as a placement run is.
    revision = client.get(f"/api/scenes/{scene_id}/revisions").json()[-1]
    assert job["started_by"] not in ("", "pipeline")
    assert (revision["kind"], revision["author"]) == ("pipeline", job["started_by"])


def _stored_state(client: TestClient, settings: Settings) -> tuple[int, list[str]]:
    folders = sorted(p.name for p in (settings.data_dir / "scenes").iterdir())
    return len(client.get("/api/scenes").json()), folders


@pytest.mark.parametrize(
    ("image", "status", "message"),
    [
        (lambda real: NOT_AN_IMAGE, 415, "not a JPEG or PNG"),
        (truncated, 422, "cannot be decoded"),
        (lambda real: png_header_only(20000, 20000), 413, "too large"),
    ],
)
def test_bad_photos_are_refused_and_nothing_is_stored(  # type: ignore[no-untyped-def]
    client: TestClient, settings: Settings, t3d5: Path, image, status: int, message: str
) -> None:
    before = _stored_state(client, settings)
    data = image((t3d5 / "img.jpg").read_bytes())
    response = client.post("/api/scenes", files={"image": ("img.jpg", data, "image/jpeg")})
    assert response.status_code == status
    assert message in response.json()["detail"]
    assert _stored_state(client, settings) == before


@pytest.mark.parametrize("case", sorted(BAD_DETECTIONS))
def test_bad_detections_are_refused_and_nothing_is_stored(
    client: TestClient, settings: Settings, t3d5: Path, case: str
) -> None:
    before = _stored_state(client, settings)
    data, message = BAD_DETECTIONS[case]
    files = {
        "image": ("img.jpg", (t3d5 / "img.jpg").read_bytes(), "image/jpeg"),
        "detections": ("detections.json", data, "application/json"),
    }
    response = client.post("/api/scenes", files=files)
    assert response.status_code == 422
    assert message in response.json()["detail"]
    assert _stored_state(client, settings) == before


def test_missing_image_field_gets_readable_422(client: TestClient) -> None:
    response = client.post("/api/scenes", data={"name": "x"})
    assert response.status_code == 422
    assert "image" in response.json()["detail"]


def test_unknown_scene_and_job_get_404(client: TestClient) -> None:
    assert client.get("/api/scenes/nope").status_code == 404
    assert client.get("/api/jobs/nope").status_code == 404
    assert "no scene" in client.get("/api/scenes/nope/revisions").json()["detail"]


@pytest.mark.both_databases
def test_edits_are_kept_across_a_restart(settings: Settings, t3d5: Path) -> None:
    from holiscene.api.app import create_app

    with TestClient(create_app(settings)) as client:
        scene_id, doc = _imported(client, t3d5)
        _edit(
            client,
            scene_id,
            doc["revision"],
            {"kind": "set_support", "child": "o1", "parent": "wall", "type": "behind"},
        )
    with TestClient(create_app(settings)) as client:
        again = client.get(f"/api/scenes/{scene_id}").json()
        assert next(s for s in again["scene"]["supports"] if s["child"] == "o1")["parent"] == "wall"


@pytest.mark.both_databases
def test_unfinished_jobs_fail_clearly_after_restart(settings: Settings, t3d5: Path) -> None:
    from holiscene.api.app import create_app
    from holiscene.services.workbench import Workbench

    with TestClient(create_app(settings)) as client:
        scene_id, _ = _imported(client, t3d5)
    workbench = Workbench(settings)
    stuck = workbench.jobs.create(scene_id, 2)  # queued, never run: as if the server died
    workbench.close()
    with TestClient(create_app(settings)) as client:
        job = client.get(f"/api/jobs/{stuck.id}").json()
        assert job["status"] == "failed"
        assert "server stopped" in job["error"]


@pytest.mark.both_databases
def test_a_restart_leaves_a_running_batch_its_jobs(settings: Settings, t3d5: Path) -> None:
    """A server that starts while `holiscene batch` runs fails only its own leftovers: the
    batch's jobs are the batch's to finish; once no batch holds its lock they are failed too."""
    from holiscene.api.app import create_app
    from holiscene.core.data_dir_owner import batch_presence
    from holiscene.services.workbench import Workbench
    from holiscene.store.jobs import BATCH_STAGE

    with TestClient(create_app(settings)) as client:
        on_batch_scene, _ = _imported(client, t3d5)
        left_scene, _ = _imported(client, t3d5)
    workbench = Workbench(settings)
    on_batch = workbench.jobs.create(on_batch_scene, 2, started_by="import")
    workbench.jobs.progress(on_batch.id, BATCH_STAGE, 0.0)  # out on a batch's worker
    left = workbench.jobs.create(left_scene, 2)  # queued, never run: as if the server died
    workbench.close()
    with batch_presence(settings.data_dir), TestClient(create_app(settings)) as client:
        assert client.get(f"/api/jobs/{on_batch.id}").json()["status"] == "running"
        assert client.get(f"/api/jobs/{left.id}").json()["status"] == "failed"
    with TestClient(create_app(settings)) as client:  # the batch is gone (its lock with it)
        job = client.get(f"/api/jobs/{on_batch.id}").json()
        # The server never ran it: the error says what a new batch does with it.
        assert job["status"] == "failed" and "a new batch takes it" in job["error"]


def test_scene_list_shows_the_newest_job(client: TestClient, t3d5: Path) -> None:
    scene_id, _ = _imported(client, t3d5)
    rerun = client.post(f"/api/scenes/{scene_id}/pipeline-jobs").json()
    wait_for_job(client, rerun["id"])
    listed = client.get("/api/scenes").json()
    assert listed[0]["latest_job"]["id"] == rerun["id"]


def test_a_photo_stored_before_is_imported_again_and_named_in_the_answer(
    client: TestClient, t3d5: Path
) -> None:
    first = upload(client, t3d5, name="t3d-5", run_pipeline="false")
    assert first["same_photo"] is None
    second = upload(client, t3d5, name="t3d-5 again", run_pipeline="false")
    assert second["scene"]["id"] != first["scene"]["id"]  # a second scene of the photo
    assert second["same_photo"]["id"] == first["scene"]["id"]
    assert second["same_photo"]["name"] == "t3d-5"
