"""Model kinds in the registry: the Relation Network and the object detector keep their own
versions, active model, history and files; the migration makes existing models Relation
Networks; the API takes the kind; the pipeline uses the active detector."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest
from alembic import command
from alembic.config import Config
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.db import MIGRATIONS_DIR, make_engine, migrate
from holiscene.core.settings import Settings
from holiscene.services.workbench import Workbench
from holiscene.store import model_registry as registry_module
from holiscene.store.model_registry import (
    ModelNotFoundError,
    ModelStore,
    NoActiveModelError,
    Registration,
    active_model_dir,
)
from sqlalchemy import Engine, text
from sqlalchemy.exc import IntegrityError

from ..conftest import wait_for_job
from ..detector_helpers import fake_detector_dir, store_boxed_scene
from ..model_helpers import fake_model_dir

# The store, as the server uses it, on SQLite and on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases


def _migrate(engine: Engine, target: str, downgrade: bool = False) -> None:
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS_DIR))
    with engine.begin() as connection:
        config.attributes["connection"] = connection
        (command.downgrade if downgrade else command.upgrade)(config, target)


@pytest.fixture()
def engine(settings: Settings) -> Iterator[Engine]:
    settings.data_dir.mkdir(parents=True)
    engine = make_engine(settings.resolved_database_url)
    migrate(engine)
    yield engine
    engine.dispose()


def _stores(engine: Engine, settings: Settings) -> tuple[ModelStore, ModelStore]:
    relation = ModelStore(engine, settings.data_dir / "models", default_dir=None)
    detector = ModelStore(engine, settings.data_dir / "detectors", None, kind="detector")
    return relation, detector


def test_migration_makes_existing_models_relation_networks(settings: Settings) -> None:
    settings.data_dir.mkdir(parents=True)
    engine = make_engine(settings.resolved_database_url)
    _migrate(engine, "0005")
    with engine.begin() as connection:
        for number, model_id in enumerate(["old1", "old2"], 1):
            connection.execute(
                text(
                    "INSERT INTO models (id, version, created_at, status, metrics, data) "
                    "VALUES (:id, :v, '2026-01-01 00:00:00', 'default', '{}', '{}')"
                ),
                {"id": model_id, "v": number},
            )
        connection.execute(
            text(
                "INSERT INTO model_events (at, action, actor, model_id) "
                "VALUES ('2026-01-01 00:00:00', 'seed', 'system', 'old2')"
            )
        )
    _migrate(engine, "head")
    with engine.connect() as connection:
        kinds = connection.execute(text("SELECT id, kind FROM models ORDER BY id")).all()
        # Every event still names a model (0006 copies the events aside and back).
        orphans = connection.execute(
            text(
                "SELECT e.id FROM model_events e LEFT JOIN models m ON m.id = e.model_id "
                "WHERE m.id IS NULL"
            )
        ).all()
        assert not orphans
    assert [tuple(row) for row in kinds] == [("old1", "relation"), ("old2", "relation")]
    relation, detector = _stores(engine, settings)
    assert [m.version for m in relation.list_models()] == [2, 1]
    assert relation.active().id == "old2" and relation.active().kind == "relation"
    assert detector.list_models() == [] and detector.active_or_none() is None

    # Versions count per kind; within a kind they stay unique.
    with engine.begin() as connection:
        connection.execute(
            text(
                "INSERT INTO models (id, kind, version, created_at, status, metrics, data) "
                "VALUES ('det1', 'detector', 1, '2026-01-02 00:00:00', 'default', '{}', '{}')"
            )
        )
    with pytest.raises(IntegrityError), engine.begin() as connection:
        connection.execute(
            text(
                "INSERT INTO models (id, version, created_at, status, metrics, data) "
                "VALUES ('old3', 2, '2026-01-02 00:00:00', 'default', '{}', '{}')"
            )
        )

    # Down again: the detectors go, the Relation Networks stay.
    _migrate(engine, "0005", downgrade=True)
    with engine.connect() as connection:
        ids = connection.execute(text("SELECT id FROM models ORDER BY id")).scalars().all()
        events = connection.execute(text("SELECT model_id FROM model_events")).scalars().all()
    assert (ids, events) == (["old1", "old2"], ["old2"])
    engine.dispose()


def test_kinds_keep_their_own_versions_active_model_and_history(
    engine: Engine, settings: Settings, tmp_path: Path
) -> None:
    relation, detector = _stores(engine, settings)
    r1 = relation.register(
        fake_model_dir(tmp_path / "r1"), Registration(status="default"), promote=True
    )
    d1 = detector.register(
        fake_detector_dir(tmp_path / "d1"), Registration(status="default"), promote=True
    )
    d2 = detector.register(fake_detector_dir(tmp_path / "d2", b"v2"), Registration("rejected"))
    assert (r1.kind, r1.version, d1.kind, d1.version, d2.version) == (
        "relation",
        1,
        "detector",
        1,
        2,
    )
    detector.promote(d2.id, "alice")
    assert detector.active().id == d2.id
    assert relation.active().id == r1.id, "promoting a detector leaves the Relation Network"
    detector.promote(d1.id, "bob")  # roll back
    assert [e.action for e in detector.events()] == ["rollback", "promote", "promote"]
    assert [e.action for e in relation.events()] == ["promote"]
    assert [m.id for m in detector.list_models()] == [d2.id, d1.id]
    assert [m.id for m in relation.list_models()] == [r1.id]

    # Each registry knows only its own models, files and folders.
    with pytest.raises(ModelNotFoundError):
        relation.promote(d1.id, "mallory")
    with pytest.raises(ModelNotFoundError):
        detector.get(r1.id)
    assert detector.file(d1.id, "metadata.json").is_file()
    assert detector.file(d1.id, "LICENSE").read_text() == "a licence\n"
    with pytest.raises(ModelNotFoundError):
        detector.file(d1.id, "priors.json")
    assert detector.folder(d1.id).parent == settings.data_dir / "detectors"
    assert active_model_dir(settings, "detector") == detector.folder(d1.id)
    assert active_model_dir(settings) == relation.folder(r1.id)
    assert relation.remove_leftovers() == [] and detector.remove_leftovers() == []


def test_an_empty_detector_registry_says_so(engine: Engine, settings: Settings) -> None:
    _, detector = _stores(engine, settings)
    with pytest.raises(NoActiveModelError, match="no object detector model is registered"):
        detector.active()
    assert active_model_dir(settings, "detector") is None


def test_the_detector_kind_is_seeded_from_the_committed_detector(settings: Settings) -> None:
    workbench = Workbench(settings)
    try:
        seeded, *offered = sorted(workbench.detectors.list_models(), key=lambda m: m.version)
        assert (seeded.kind, seeded.version, seeded.status, seeded.active) == (
            "detector",
            1,
            "default",
            True,
        )
        # The detectors shipped beside it (the NYU-40 head, the COCO CenterNet) wait for an
        # admin to choose one.
        shipped = registry_module.OFFERED_DETECTOR_DIRS
        assert [(m.version, m.status, m.active) for m in offered] == [
            (2 + index, "candidate", False) for index in range(len(shipped))
        ]
        for model, folder in zip(offered, shipped, strict=True):
            copied = workbench.detectors.file(model.id, "model.onnx").read_bytes()
            assert copied == (folder / "model.onnx").read_bytes()
        # Each says which network it is (the models page shows it under the version).
        names = [m.name for m in (seeded, *offered)]
        folders = [registry_module.default_detector_dir(), *shipped]
        assert names == [json.loads((f / "metadata.json").read_text())["name"] for f in folders]
        assert len(set(names)) == len(names) and workbench.models.list_models()[0].name is None
        source = registry_module.default_detector_dir()
        assert source is not None
        copied = workbench.detectors.file(seeded.id, "model.onnx")
        assert copied.read_bytes() == (source / "model.onnx").read_bytes()
        assert workbench.detectors.seed_if_empty() is None, "seeded once"
        assert workbench.models.active().kind == "relation"
    finally:
        workbench.close()


def test_a_registry_seeded_before_a_new_default_is_offered_it_once(
    settings: Settings, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    old_default = fake_detector_dir(tmp_path / "old", b"old-default")
    shipped_beside = fake_detector_dir(tmp_path / "beside", b"shipped-beside")
    new_default = fake_detector_dir(tmp_path / "new", b"new-default")
    monkeypatch.setattr(registry_module, "DEFAULT_DETECTOR_DIRS", (old_default,))
    monkeypatch.setattr(registry_module, "OFFERED_DETECTOR_DIRS", (shipped_beside,))
    Workbench(settings).close()
    # The code moves on: a new default, the old one now shipped beside it.
    monkeypatch.setattr(registry_module, "DEFAULT_DETECTOR_DIRS", (new_default,))
    monkeypatch.setattr(registry_module, "OFFERED_DETECTOR_DIRS", (shipped_beside, old_default))
    for _ in range(2):  # the second start adds nothing
        workbench = Workbench(settings)
        try:
            models = sorted(workbench.detectors.list_models(), key=lambda m: m.version)
            contents = [workbench.detectors.file(m.id, "model.onnx").read_bytes() for m in models]
            assert contents == [b"old-default", b"shipped-beside", b"new-default"]
            assert [(m.status, m.active) for m in models] == [
                ("default", True),
                ("candidate", False),
                ("candidate", False),
            ], "the admin chooses; the active detector does not change under people"
            assert "the default shipped with the code now" in (models[2].note or "")
        finally:
            workbench.close()


@pytest.fixture()
def client(
    settings: Settings, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> Iterator[TestClient]:
    monkeypatch.setattr(registry_module, "DEFAULT_MODEL_DIR", fake_model_dir(tmp_path / "rn"))
    detector = fake_detector_dir(tmp_path / "detector", b"default-detector")
    monkeypatch.setattr(registry_module, "DEFAULT_DETECTOR_DIRS", (detector,))
    monkeypatch.setattr(registry_module, "OFFERED_DETECTOR_DIRS", ())
    with TestClient(create_app(settings)) as test_client:
        yield test_client


def test_the_api_takes_the_kind(client: TestClient, tmp_path: Path) -> None:
    [relation] = client.get("/api/models").json()
    assert client.get("/api/models?kind=relation").json() == [relation]
    [detector] = client.get("/api/models?kind=detector").json()
    assert (relation["kind"], detector["kind"]) == ("relation", "detector")
    assert client.get("/api/models/active?kind=detector").json() == detector
    assert client.get(f"/api/models/{detector['id']}").json() == detector
    [event] = client.get("/api/models/events?kind=detector").json()
    assert (event["action"], event["model_id"]) == ("seed", detector["id"])
    onnx = client.get(f"/api/models/{detector['id']}/model.onnx")
    assert onnx.content == b"default-detector" and "immutable" in onnx.headers["cache-control"]
    assert client.get(f"/api/models/{detector['id']}/metadata.json").json()["label_space"]
    assert client.get(f"/api/models/{detector['id']}/priors.json").status_code == 404
    assert client.get(f"/api/models/{relation['id']}/metadata.json").status_code == 404

    workbench: Workbench = client.app.state.workbench  # type: ignore[attr-defined]
    newer = workbench.detectors.register(
        fake_detector_dir(tmp_path / "newer", b"newer"), Registration(status="rejected")
    )
    promoted = client.post(f"/api/models/{newer.id}/promote", json={"author": "alice"})
    assert promoted.status_code == 200 and promoted.json()["active"] is True
    assert client.get("/api/models/active").json()["id"] == relation["id"]
    rolled = client.post(f"/api/models/{detector['id']}/promote").json()
    assert rolled["active"] and rolled["kind"] == "detector"
    events = client.get("/api/models/events?kind=detector").json()
    assert [e["action"] for e in events] == ["rollback", "promote", "seed"]
    assert [e["action"] for e in client.get("/api/models/events").json()] == ["seed"]


def test_a_bad_kind_is_refused(client: TestClient) -> None:
    for method, path in [
        ("GET", "/api/models?kind=surface"),
        ("GET", "/api/models/active?kind=Detector"),
        ("GET", "/api/models/events?kind="),
        ("GET", "/api/models/retrain?kind=x"),
        ("POST", "/api/models/retrain?kind=segmenter"),
    ]:
        response = client.request(method, path)
        assert response.status_code == 422, path
        assert "kind" in response.json()["detail"]


def test_pipeline_jobs_use_the_active_detector(
    client: TestClient, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """A promoted detector whose model file is no network makes the pipeline fail, naming
    its folder in the server log: the pipeline loads the registry's active detector."""
    workbench: Workbench = client.app.state.workbench  # type: ignore[attr-defined]
    broken = workbench.detectors.register(
        fake_detector_dir(tmp_path / "broken", b"not a network"), Registration(status="rejected")
    )
    assert client.post(f"/api/models/{broken.id}/promote").status_code == 200
    scene_id = store_boxed_scene(workbench.scenes, 4102)
    job = client.post(f"/api/scenes/{scene_id}/pipeline-jobs").json()
    failed = wait_for_job(client, job["id"], timeout=60)
    assert failed["status"] == "failed"
    folder = str(workbench.detectors.folder(broken.id))
    assert folder in caplog.text and folder not in failed["error"]  # no server paths


def test_restart_settles_detector_retrain_jobs(settings: Settings, tmp_path: Path) -> None:
    """A detector registered just before a restart completes its job; a job that registered
    nothing fails."""
    workbench = Workbench(settings)
    finished = workbench.jobs.create_retrain("detector_retrain")
    model = workbench.detectors.register(
        fake_detector_dir(tmp_path / "finished"),
        Registration(status="accepted", job_id=finished.id),
        promote=True,
        expected_active=workbench.detectors.active().id,
    )
    workbench.close()
    with TestClient(create_app(settings)) as client:
        done = client.get(f"/api/jobs/{finished.id}").json()
        assert (done["status"], done["result_model_id"]) == ("succeeded", model.id)
        workbench = client.app.state.workbench  # type: ignore[attr-defined]
        unfinished = workbench.jobs.create_retrain("detector_retrain")
    with TestClient(create_app(settings)) as client:
        failed = client.get(f"/api/jobs/{unfinished.id}").json()
        assert failed["status"] == "failed" and "no model was registered" in failed["error"]
        assert client.get("/api/models/active?kind=detector").json()["id"] == model.id
        assert client.get("/api/models/retrain?kind=detector").json()["id"] == unfinished.id
