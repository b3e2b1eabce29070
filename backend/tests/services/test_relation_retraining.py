"""Retraining on stored labelled scenes with real (tiny) training runs: a better model is
promoted, a worse one registered but refused, the held-out split is fixed, and neither a
restart nor a shutdown mid-training leaves a half-written model in use."""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from holiscene.learning.training_api import TrainConfig
from holiscene.services.relation_retraining import heldout_verdict, labelled_scenes
from holiscene.services.workbench import Workbench
from holiscene.store import model_registry as registry_module
from holiscene.store.model_registry import Registration, active_model_dir
from holiscene.store.tables import ModelRow
from holiscene_schema import Job, RetrainRequest
from holiscene_schema.api import FEW_HELDOUT_ITEMS
from sqlalchemy.orm import Session

from ..conftest import wait_for_job
from ..model_helpers import (
    LABELLED_SEEDS,
    always_wrong_model_dir,
    fake_model_dir,
    store_labelled_scene,
    store_unlabelled_scene,
)

# Small enough for a short run (the ONNX export takes most of it), large enough that the
# trained network beats an untrained one on every one of LABELLED_SEEDS by a wide margin.
TINY = TrainConfig(synthetic_scenes=40, max_epochs=8, patience=20)
UNTRAINED = TrainConfig(synthetic_scenes=4, max_epochs=0)  # the initial weights: a bad model


@pytest.fixture()
def no_default_model(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(registry_module, "DEFAULT_MODEL_DIR", tmp_path / "not-committed")


@pytest.fixture()
def workbench(settings: Settings, no_default_model: None) -> Iterator[Workbench]:
    workbench = Workbench(settings)
    yield workbench
    workbench.close()


def _run(
    workbench: Workbench, config: TrainConfig, author: str = "admin", promote_min_items: int = 1
) -> Job:
    """One retrain job, run to its end in this thread (a better model made active by itself
    whatever the number of held-out objects, unless `promote_min_items` says otherwise)."""
    job = workbench.jobs.create_retrain()
    retrain = workbench.retrain_job(job.id, RetrainRequest(author=author))
    assert retrain.promote_min_items == workbench.settings.promote_min_heldout_items
    retrain.config = config
    retrain.promote_min_items = promote_min_items
    retrain.run()
    return workbench.jobs.get(job.id)


def test_a_new_model_is_made_active_only_when_it_does_better_on_the_held_out_scenes() -> None:
    enough = FEW_HELDOUT_ITEMS
    assert heldout_verdict([0.5, 0.2], None, None, 4).status == "accepted"  # nothing to compare
    assert heldout_verdict([0.5, 0.2], [0.4, 0.9], 1, enough).promote  # the first score decides
    assert heldout_verdict([0.5, 0.3], [0.5, 0.2], 1, enough).promote  # the next breaks its tie
    assert heldout_verdict([0.4, 0.9], [0.5, 0.2], 1, enough).status == "rejected"
    tie = heldout_verdict([0.5, 0.2], [0.5 + 1e-12, 0.2], 3, enough)
    assert (tie.status, tie.promote) == ("candidate", False)
    assert tie.note == "the same held-out scores as v3, which stays active"
    # A tie on one item says how little it rests on.
    one = heldout_verdict([1.0], [1.0], 1, 1, 4)
    assert one.note == "the same held-out scores as v1 on 1 held-out item only, which stays active"
    # Better on a handful of items only: kept as a candidate, the active model stays.
    few = heldout_verdict([0.75, 0.2], [0.5, 0.2], 2, 4)
    assert (few.status, few.promote) == ("candidate", False)
    assert few.note == (
        "better on 4 held-out items only, too few to tell it from v2, which stays active"
    )
    assert heldout_verdict([0.25, 0.2], [0.5, 0.2], 2, 4).status == "rejected"


def test_only_supports_set_by_people_are_labels(workbench: Workbench) -> None:
    labelled = store_labelled_scene(workbench.scenes, LABELLED_SEEDS[0])
    store_unlabelled_scene(workbench.scenes, LABELLED_SEEDS[1])
    [found] = labelled_scenes(workbench.scenes)
    assert (found.scene_id, found.key) == (labelled, f"{labelled}@r1")
    assert all(s.source == "manual" for s in found.scene.supports)


def test_retrain_promotes_a_better_model_and_refuses_a_worse_one(workbench: Workbench) -> None:
    scene_ids = [store_labelled_scene(workbench.scenes, seed) for seed in LABELLED_SEEDS]
    unlabelled = store_unlabelled_scene(workbench.scenes, 4201)

    # A deliberately bad active model: it answers "each object holds itself up".
    bad = workbench.models.register(
        always_wrong_model_dir(workbench.settings.data_dir.parent / "always-wrong"),
        Registration(status="default"),
        promote=True,
        action="seed",
    )

    # A trained one beats it, but on fewer held-out objects than an automatic switch needs:
    # kept as a candidate, the active model stays.
    few_job = _run(workbench, TINY, author="alice", promote_min_items=10_000)
    few = workbench.models.get(few_job.result_model_id or "")
    assert (few.version, few.status, few.active) == (2, "candidate", False), few_job.log
    assert few.note == (
        f"better on {few.heldout_items} held-out items only, too few to tell it from v1, "
        "which stays active"
    )
    assert workbench.models.active().id == bad.id

    # On enough held-out objects it is registered and made active.
    good_job = _run(workbench, TINY, author="alice")
    assert good_job.status == "succeeded", good_job.error
    good = workbench.models.get(good_job.result_model_id or "")
    assert (good.version, good.status, good.active, good.parent_id) == (3, "accepted", True, bad.id)
    assert good.heldout_accuracy is not None and good.parent_heldout_accuracy is not None
    assert good.parent_heldout_accuracy == 0.0
    assert good.heldout_accuracy > 0.5, good_job.log
    assert good_job.message and good_job.message.startswith("v3 is active")
    assert "epoch 8" in good_job.log and "held-out accuracy" in good_job.log
    assert good_job.progress == 1.0
    assert active_model_dir(workbench.settings) == workbench.models.folder(good.id)

    # Another untrained one is worse: registered (to inspect) but the active model stays.
    worse_job = _run(workbench, UNTRAINED)
    assert worse_job.status == "succeeded", worse_job.error
    worse = workbench.models.get(worse_job.result_model_id or "")
    assert (worse.version, worse.status, worse.active) == (4, "rejected", False)
    assert worse.parent_heldout_accuracy == good.heldout_accuracy
    assert worse.heldout_accuracy is not None and worse.heldout_accuracy < good.heldout_accuracy
    assert worse.parent_id == good.id
    assert worse_job.message and "rejected" in worse_job.message
    assert workbench.models.active().id == good.id
    assert (workbench.models.folder(worse.id) / "model.onnx").is_file()

    # The data it saw: labelled scenes only, split the same way every time.
    with Session(workbench.engine) as session:
        good_data = session.get(ModelRow, good.id).data  # type: ignore[union-attr]
        worse_data = session.get(ModelRow, worse.id).data  # type: ignore[union-attr]
    keys = good_data["training_scenes"] + good_data["heldout_scenes"]
    assert sorted(k.split("@")[0] for k in keys) == sorted(scene_ids)
    assert unlabelled not in {k.split("@")[0] for k in keys}
    assert good_data["heldout_scenes"] == worse_data["heldout_scenes"]
    # How many labelled objects the held-out figures rest on, shown beside them.
    assert good.heldout_items is not None and good.heldout_items >= 1
    assert worse.heldout_items == good.heldout_items
    assert good_data["started_by"] == "alice"
    seen = json.loads((workbench.models.folder(good.id) / "data.json").read_text())
    assert sorted(seen["labelled_scenes"]) == sorted(good_data["training_scenes"])
    events = workbench.models.events()
    assert [(e.action, e.actor, e.model_version) for e in events] == [
        ("promote", "alice", 3),
        ("seed", "system", 1),
    ]
    assert not any(workbench.training_dir.iterdir()), "training folders are removed"


def test_retrain_through_the_api(settings: Settings, no_default_model: None) -> None:
    with TestClient(create_app(settings)) as client:
        workbench: Workbench = client.app.state.workbench  # type: ignore[attr-defined]
        for seed in LABELLED_SEEDS[:3]:
            store_labelled_scene(workbench.scenes, seed)
        started = client.post(
            "/api/models/retrain",
            json={"author": "bob", "max_epochs": 1, "synthetic_scenes": 4},
        )
        assert started.status_code == 202, started.text
        job = started.json()
        assert (job["kind"], job["scene_id"]) == ("retrain", None)
        # The worker may pick the job up before the response is written.
        assert job["status"] in ("queued", "running")
        assert "queued by bob: max_epochs=1, synthetic_scenes=4" in job["log"]
        again = client.post("/api/models/retrain")
        assert again.status_code == 409 and job["id"] in again.json()["detail"]

        done = wait_for_job(client, job["id"], timeout=120)
        assert done["status"] == "succeeded", done
        assert done["result_model_id"] and "labelled scenes" in done["log"]
        active = client.get("/api/models/active").json()
        assert (active["id"], active["version"], active["status"]) == (
            done["result_model_id"],
            1,
            "accepted",
        )
        assert active["has_curve"] and active["metrics"]["epochs"] == 1
        onnx = client.get(f"/api/models/{active['id']}/model.onnx")
        folder = workbench.models.folder(active["id"])
        assert onnx.content == (folder / "model.onnx").read_bytes()
        assert client.get(f"/api/models/{active['id']}/curve.png").content[:4] == b"\x89PNG"
        assert client.get("/api/models/retrain").json()["id"] == job["id"]
    assert active_model_dir(settings) == folder


def test_restart_fails_an_unfinished_retrain_and_registers_nothing(
    settings: Settings, no_default_model: None
) -> None:
    workbench = Workbench(settings)
    job = workbench.jobs.create_retrain()
    workbench.jobs.progress(job.id, "training", 0.4)
    half = workbench.training_dir / job.id / "model"
    half.mkdir(parents=True)
    (half / "model.onnx").write_bytes(b"half a network")  # as if the process died mid-export
    staging = workbench.models.root / ".staging-crashed"
    fake_model_dir(staging)
    workbench.close()

    with TestClient(create_app(settings)) as client:
        after = client.get(f"/api/jobs/{job.id}").json()
        assert after["status"] == "failed"
        assert "no model was registered" in after["error"]
        assert client.get("/api/models").json() == []
        assert client.get("/api/models/active").status_code == 404
    assert not workbench.training_dir.exists()
    assert not staging.exists()
    assert active_model_dir(settings) is None


def test_restart_keeps_a_model_registered_just_before_it(
    settings: Settings, no_default_model: None, tmp_path: Path
) -> None:
    workbench = Workbench(settings)
    job = workbench.jobs.create_retrain()
    workbench.jobs.progress(job.id, "evaluating on the held-out scenes", 0.95)
    model = workbench.models.register(
        fake_model_dir(tmp_path / "finished"),
        Registration(status="accepted", job_id=job.id),
        promote=True,
    )
    workbench.close()  # died before marking the job succeeded

    with TestClient(create_app(settings)) as client:
        after = client.get(f"/api/jobs/{job.id}").json()
        assert (after["status"], after["result_model_id"]) == ("succeeded", model.id)
        assert client.get("/api/models/active").json()["id"] == model.id


def test_shutdown_during_training_fails_the_job(settings: Settings, no_default_model: None) -> None:
    workbench = Workbench(settings)
    for seed in LABELLED_SEEDS[:2]:
        store_labelled_scene(workbench.scenes, seed)
    job = workbench.start_retrain(
        RetrainRequest(author="admin", max_epochs=500, synthetic_scenes=4)
    )
    deadline = time.monotonic() + 60
    while workbench.jobs.get(job.id).stage != "training":
        assert time.monotonic() < deadline, "the job never started training"
        time.sleep(0.05)
    workbench.close()  # the server stops: training ends at its next progress report

    after = Workbench(settings)
    try:
        stopped = after.jobs.get(job.id)
        assert stopped.status == "failed"
        assert stopped.error and "server stopped" in stopped.error
        assert after.models.list_models() == []
        assert not (after.training_dir / job.id).exists()
    finally:
        after.close()
