"""Retraining the object detector on stored scenes with real (tiny) training runs: a detector
not worse on the held-out scenes is promoted, a worse one registered but refused, rollback
works, and the Relation Network's active model never moves. Which boxes count as confirmed."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from holiscene.evaluation.detection_2d import ScoredBox
from holiscene.learning.detector.runtime import COCO_DETECTOR_DIR
from holiscene.services.detector_retraining import (
    DetectorRetrainConfig,
    boxed_scenes,
    without_unconfirmed,
)
from holiscene.services.heldout import heldout_split
from holiscene.services.workbench import Workbench
from holiscene.store import model_registry as registry_module
from holiscene.store.model_registry import Registration, active_model_dir
from holiscene.store.tables import ModelRow, SceneRow
from holiscene_schema import AddObject, EditRequest, Job, RetrainRequest
from sqlalchemy import update
from sqlalchemy.orm import Session

from ..conftest import wait_for_job
from ..detector_helpers import BOXED_SEEDS, never_detecting_dir, store_boxed_scene

# One epoch on two synthetic rooms (validated on two more) and the stored scenes.
TINY = DetectorRetrainConfig(synthetic_rooms=2, epochs=1, stored_repeats=1)


@pytest.fixture(scope="module")
def rooms_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Rendered synthetic rooms, shared by this module's jobs (rendering is the slow part)."""
    return tmp_path_factory.mktemp("detector-rooms")


def _workbench(settings: Settings, default_detector: Path) -> Workbench:
    return Workbench(settings, default_detector_dir=default_detector)


def _run(workbench: Workbench, config: DetectorRetrainConfig, author: str = "admin") -> Job:
    """One detector retrain job, run to its end in this thread (a better detector made active
    by itself whatever the number of held-out boxes)."""
    job = workbench.jobs.create_retrain("detector_retrain")
    retrain = workbench.retrain_detector_job(job.id, RetrainRequest(author=author))
    assert retrain.promote_min_items == workbench.settings.promote_min_heldout_items
    retrain.config = config
    retrain.promote_min_items = 1
    retrain.run()
    return workbench.jobs.get(job.id)


@pytest.fixture()
def never_detecting(tmp_path: Path) -> Path:
    return never_detecting_dir(tmp_path / "never-detects")


def test_retrain_keeps_a_tied_detector_as_a_candidate_to_promote_and_roll_back(
    settings: Settings, never_detecting: Path, rooms_cache: Path
) -> None:
    workbench = _workbench(settings, never_detecting)
    try:
        relation = workbench.models.active()
        [seeded] = workbench.detectors.list_models()
        assert (seeded.kind, seeded.version, seeded.status, seeded.active) == (
            "detector",
            1,
            "default",
            True,
        )
        scene_ids = [store_boxed_scene(workbench.scenes, seed) for seed in BOXED_SEEDS[:3]]
        guessed = store_boxed_scene(workbench.scenes, BOXED_SEEDS[3], source="detector")

        job = _run(workbench, dataclasses.replace(TINY, cache_dir=rooms_cache), "alice")
        assert job.status == "succeeded", job.error
        assert (job.kind, job.progress) == ("detector_retrain", 1.0)
        new = workbench.detectors.get(job.result_model_id or "")
        assert new.parent_id == seeded.id and new.parent_heldout_accuracy == 0.0
        assert new.parent_heldout_recall == 0.0
        assert new.heldout_accuracy is not None and new.heldout_recall is not None
        # Against the detector that never detects: made active if it found anything on the
        # held-out scenes (which of the random scene ids are held out decides); if it found
        # nothing either, a tie: the active one stays and the new one waits as a candidate.
        if (new.heldout_accuracy, new.heldout_recall) == (0.0, 0.0):
            assert (new.version, new.status, new.active) == (2, "candidate", False)
            assert (new.note or "").startswith("the same held-out scores as v1")
            assert workbench.detectors.active().id == seeded.id
            assert job.message and job.message.startswith("detector v2 kept as a candidate")
            workbench.detectors.promote(new.id, "alice", "made active by hand")
            new = workbench.detectors.get(new.id)
        else:
            assert (new.version, new.status) == (2, "accepted"), job.log
            assert job.message and job.message.startswith("detector v2 is active"), job.log
        assert new.kind == "detector" and new.active
        assert new.heldout_accuracy is not None and new.validation_accuracy is not None
        # The split is decided by a hash of the (random) scene ids: 1 or 2 of the 3 are held out.
        trained_ids, heldout_ids = heldout_split(scene_ids, workbench.scenes.split_keys(scene_ids))
        assert (new.training_scenes, new.heldout_scenes) == (len(trained_ids), len(heldout_ids))
        assert new.training_scenes >= 1 and new.heldout_scenes >= 1
        assert new.heldout_items is not None and new.heldout_items >= new.heldout_scenes
        assert new.has_curve and new.metrics["curve"][0]["epoch"] == 1
        for line in ("3 scenes with confirmed boxes", "epoch 1", "new detector: mAP@0.5"):
            assert line in job.log, job.log
        with Session(workbench.engine) as session:
            data = session.get(ModelRow, new.id).data  # type: ignore[union-attr]
        keys = data["training_scenes"] + data["heldout_scenes"]
        assert sorted(k.split("@")[0] for k in keys) == sorted(scene_ids)
        assert guessed not in {k.split("@")[0] for k in keys}, (
            "the pipeline's guesses are no labels"
        )
        assert data["started_by"] == "alice"
        assert active_model_dir(settings, "detector") == workbench.detectors.folder(new.id)
        assert (workbench.detectors.folder(new.id) / "metadata.json").is_file()
        assert not any(workbench.training_dir.iterdir()), "training folders are removed"

        # Roll back to the seeded detector: the history keeps both.
        workbench.detectors.promote(seeded.id, "bob", "the new one misses chairs")
        assert workbench.detectors.active().id == seeded.id
        events = workbench.detectors.events()
        assert [(e.action, e.actor, e.model_version) for e in events] == [
            ("rollback", "bob", 1),
            ("promote", "alice", 2),
            ("seed", "system", 1),
        ]
        assert workbench.models.active() == relation, "the Relation Network stays"
        assert [e.action for e in workbench.models.events()] == ["seed"]
    finally:
        workbench.close()


def test_retrain_refuses_a_worse_detector(settings: Settings, rooms_cache: Path) -> None:
    """Against the COCO detector, an untrained head alone (no COCO share) finds nothing."""
    workbench = _workbench(settings, COCO_DETECTOR_DIR)
    try:
        coco = workbench.detectors.active()
        for seed in BOXED_SEEDS[:3]:
            store_boxed_scene(workbench.scenes, seed, source="given")
        worse = dataclasses.replace(TINY, coco_weight=0.0, cache_dir=rooms_cache)
        job = _run(workbench, worse)
        assert job.status == "succeeded", job.error
        model = workbench.detectors.get(job.result_model_id or "")
        assert (model.version, model.status, model.active) == (2, "rejected", False), job.log
        assert model.parent_heldout_accuracy is not None and model.heldout_accuracy is not None
        assert model.heldout_accuracy < model.parent_heldout_accuracy
        assert job.message and "rejected" in job.message
        assert workbench.detectors.active().id == coco.id
        assert (workbench.detectors.folder(model.id) / "model.onnx").is_file()
    finally:
        workbench.close()


def test_retrain_measures_every_other_detector_on_the_same_held_out_scenes(
    settings: Settings, never_detecting: Path, rooms_cache: Path
) -> None:
    """A registered detector that is neither active nor the new one gets figures too: the
    admin choosing which to make active has them side by side."""
    workbench = _workbench(settings, COCO_DETECTOR_DIR)
    try:
        coco = workbench.detectors.active()
        idle = workbench.detectors.register(never_detecting, Registration(status="candidate"))
        for seed in BOXED_SEEDS[:3]:
            store_boxed_scene(workbench.scenes, seed, source="given")
        job = _run(workbench, dataclasses.replace(TINY, cache_dir=rooms_cache))
        assert job.status == "succeeded", job.error
        new = workbench.detectors.get(job.result_model_id or "")
        assert [(f.model_id, f.accuracy, f.recall) for f in new.heldout_others] == [
            (idle.id, 0.0, 0.0)
        ], "the parent's figures are its own fields; the detector that never detects scores 0"
        assert f"detector v{idle.version}: mAP@0.5 0.0%, recall 0.0%" in job.log
        assert new.parent_id == coco.id
        assert workbench.detectors.get(coco.id).heldout_others == []
    finally:
        workbench.close()


def test_detector_retrain_through_the_api(
    settings: Settings, never_detecting: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(registry_module, "DEFAULT_DETECTOR_DIRS", (never_detecting,))
    monkeypatch.setattr(registry_module, "OFFERED_DETECTOR_DIRS", ())
    with TestClient(create_app(settings)) as client:
        workbench: Workbench = client.app.state.workbench  # type: ignore[attr-defined]
        store_boxed_scene(workbench.scenes, BOXED_SEEDS[0])
        refused = client.post("/api/models/retrain?kind=detector", json={"max_epochs": 1})
        assert refused.status_code == 422 and "1 found" in refused.json()["detail"]
        store_boxed_scene(workbench.scenes, BOXED_SEEDS[1])
        started = client.post(
            "/api/models/retrain?kind=detector",
            json={"author": "bob", "max_epochs": 1, "synthetic_scenes": 0},
        )
        assert started.status_code == 202, started.text
        job = started.json()
        assert (job["kind"], job["scene_id"]) == ("detector_retrain", None)
        assert "queued by bob: epochs=1, synthetic_rooms=0" in job["log"]
        busy = client.post("/api/models/retrain", json={"max_epochs": 1})
        assert busy.status_code == 409, "one retrain job at a time, whatever the kind"
        assert client.get("/api/models/retrain").json() is None
        assert client.get("/api/models/retrain?kind=detector").json()["id"] == job["id"]

        done = wait_for_job(client, job["id"], timeout=120)
        assert done["status"] == "succeeded", done
        new = client.get(f"/api/models/{done['result_model_id']}").json()
        if not new["active"]:  # a tie with the detector that never detects
            assert new["status"] == "candidate", done["log"]
            promoted = client.post(f"/api/models/{new['id']}/promote", json={"note": "by hand"})
            assert promoted.status_code == 200, promoted.text
        active = client.get("/api/models/active?kind=detector").json()
        assert (active["id"], active["kind"], active["version"]) == (
            done["result_model_id"],
            "detector",
            2,
        )
        assert (settings.data_dir / "detector-rooms").is_dir(), "rooms are cached in the data dir"
        metadata = client.get(f"/api/models/{active['id']}/metadata.json").json()
        assert metadata["label_space"] == "nyu40"


def test_confirmed_boxes(settings: Settings, never_detecting: Path) -> None:
    """Drawn and given boxes count, and accepted suggestions; the pipeline's detections
    count only in a scene a reviewer accepted; walls never."""
    workbench = _workbench(settings, never_detecting)
    try:
        scenes = workbench.scenes
        scene_id = store_boxed_scene(scenes, BOXED_SEEDS[0], source="detector")
        objects = scenes.document(scene_id).scene.objects
        assert not boxed_scenes(scenes), "detections no one accepted are no labels"
        accepted = AddObject(id="s1", cls="chair", bbox=[10, 20, 60, 90], source="detector")
        drawn = AddObject(id="m1", cls="table", bbox=[100, 120, 200, 220])
        wall = AddObject(id="m2", cls="wall", bbox=[0, 0, 50, 50])
        scenes.apply_edits(
            scene_id, EditRequest(base_revision=1, author="ann", edits=[accepted, drawn, wall])
        )
        [item] = boxed_scenes(scenes)
        assert (item.key, item.classes) == (f"{scene_id}@r2", ("chair", "table"))
        assert item.boxes == ((10, 20, 60, 90), (100, 120, 200, 220))
        assert len(item.unconfirmed) == len(objects)

        with Session(workbench.engine) as session:
            session.execute(update(SceneRow).values(state="accepted"))
            session.commit()
        [reviewed] = boxed_scenes(scenes)
        assert len(reviewed.boxes) == len(objects) + 2 and not reviewed.unconfirmed

        # A reviewer who rejects the scene says its labels are wrong: none of them count.
        with Session(workbench.engine) as session:
            session.execute(update(SceneRow).values(state="rejected"))
            session.commit()
        assert not boxed_scenes(scenes)
    finally:
        workbench.close()


def test_predictions_on_unconfirmed_boxes_are_left_out() -> None:
    truth = [ScoredBox((0, 0, 10, 10), "chair")]
    found = [
        ScoredBox((0, 0, 10, 10), "chair", 0.9),  # on a confirmed box: kept
        ScoredBox((50, 50, 70, 70), "lamp", 0.8),  # on an unconfirmed one: left out
        ScoredBox((100, 100, 120, 120), "sofa", 0.7),  # on nothing: a false alarm, kept
    ]
    kept = without_unconfirmed(found, truth, [(50, 50, 70, 71)], iou=0.5)
    assert [box.cls for box in kept] == ["chair", "sofa"]
    assert without_unconfirmed(found, truth, [], iou=0.5) == found
