"""The model registry on a real SQLite database: register, list, promote, roll back, seed,
atomic registration, and the promoted model's folder for the pipeline."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest
from holiscene.core.db import make_engine, migrate
from holiscene.core.settings import Settings
from holiscene.store import model_registry as registry_module
from holiscene.store.model_registry import (
    NO_MODEL_MESSAGE,
    InvalidModelDirError,
    ModelNotFoundError,
    ModelStore,
    NoActiveModelError,
    Registration,
    active_model_dir,
    require_active_model_dir,
)
from sqlalchemy import Engine
from sqlalchemy.exc import StatementError

from ..model_helpers import fake_model_dir

# The store, as the server uses it, on SQLite and on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases


@pytest.fixture()
def settings(tmp_path: Path, database_url: str | None) -> Settings:
    return Settings(data_dir=tmp_path / "data", database_url=database_url)


@pytest.fixture()
def engine(settings: Settings) -> Iterator[Engine]:
    settings.data_dir.mkdir(parents=True)
    engine = make_engine(settings.resolved_database_url)
    migrate(engine)
    yield engine
    engine.dispose()


@pytest.fixture()
def store(engine: Engine, settings: Settings) -> ModelStore:
    return ModelStore(engine, settings.data_dir / "models", default_dir=None)


def _register(store: ModelStore, source: Path, **fields: object) -> str:
    promote = bool(fields.pop("promote", False))
    expected = fields.pop("expected_active", None)
    registration = Registration(**{"status": "accepted", **fields})  # type: ignore[arg-type]
    info = store.register(
        source, registration, promote=promote, expected_active=expected, actor="tester"
    )
    return info.id


def test_empty_registry_says_so(store: ModelStore, settings: Settings) -> None:
    assert store.list_models() == []
    assert store.active_or_none() is None
    with pytest.raises(NoActiveModelError, match=NO_MODEL_MESSAGE):
        store.active()
    assert active_model_dir(settings) is None
    with pytest.raises(NoActiveModelError, match="no Relation Network model is registered"):
        require_active_model_dir(settings)


def test_active_model_dir_without_a_database(tmp_path: Path) -> None:
    settings = Settings(data_dir=tmp_path / "nothing-here")
    assert active_model_dir(settings) is None
    assert not (tmp_path / "nothing-here").exists(), "a lookup must not create a database"


def test_seed_from_default_model(engine: Engine, settings: Settings, tmp_path: Path) -> None:
    default = fake_model_dir(tmp_path / "default", b"default-model")
    store = ModelStore(engine, settings.data_dir / "models", default_dir=default)
    seeded = store.seed_if_empty()
    assert seeded is not None
    assert (seeded.version, seeded.status, seeded.active) == (1, "default", True)
    assert seeded.validation_accuracy == 0.5
    assert seeded.has_curve
    assert store.seed_if_empty() is None, "only an empty registry is seeded"
    folder = store.folder(seeded.id)
    for name in ("model.onnx", "metrics.json", "data.json", "priors.json", "curve.png"):
        assert (folder / name).read_bytes() == (default / name).read_bytes()
    assert active_model_dir(settings) == folder
    assert require_active_model_dir(settings) == folder
    [event] = store.events()
    assert (event.action, event.actor, event.model_version) == ("seed", "system", 1)


def test_no_default_model_leaves_registry_empty(
    engine: Engine, settings: Settings, tmp_path: Path
) -> None:
    store = ModelStore(engine, settings.data_dir / "models", default_dir=tmp_path / "missing")
    assert store.seed_if_empty() is None
    assert store.list_models() == []


def test_register_promote_and_roll_back_keep_history(store: ModelStore, tmp_path: Path) -> None:
    v1 = store.register(
        fake_model_dir(tmp_path / "a", b"one"),
        Registration(status="default"),
        promote=True,
        action="seed",
    ).id
    v2 = _register(
        store,
        fake_model_dir(tmp_path / "b", b"two"),
        promote=True,
        expected_active=v1,
        parent_id=v1,
        heldout_accuracy=0.8,
        parent_heldout_accuracy=0.6,
        data={"training_scenes": ["s1@r2", "s2@r3"], "heldout_scenes": ["s3@r2"]},
    )
    v3 = _register(
        store,
        fake_model_dir(tmp_path / "c", b"three", curve=False),
        status="rejected",
        parent_id=v2,
        heldout_accuracy=0.7,
        parent_heldout_accuracy=0.8,
    )
    models = store.list_models()
    assert [(m.version, m.status, m.active) for m in models] == [
        (3, "rejected", False),
        (2, "accepted", True),
        (1, "default", False),
    ]
    second = store.get(v2)
    assert (second.parent_id, second.parent_version) == (v1, 1)
    assert (second.training_scenes, second.heldout_scenes) == (2, 1)
    assert (second.heldout_accuracy, second.parent_heldout_accuracy) == (0.8, 0.6)
    assert not store.get(v3).has_curve
    assert store.file(v3, "model.onnx").read_bytes() == b"three"

    assert store.promote(v1, "alice", "v2 misplaces lamps").active  # roll back
    assert store.active().id == v1
    assert store.promote(v3, "bob").active  # forward, to a model that was rejected
    assert store.promote(v3, "bob").active  # already active: no new event
    events = store.events()
    assert [(e.action, e.actor, e.model_version, e.previous_version) for e in events] == [
        ("promote", "bob", 3, 1),
        ("rollback", "alice", 1, 2),
        ("promote", "tester", 2, 1),
        ("seed", "system", 1, None),
    ]
    assert events[1].note == "v2 misplaces lamps"
    with pytest.raises(ModelNotFoundError):
        store.promote("nope", "alice")


def test_promotion_needs_the_model_it_was_compared_with(store: ModelStore, tmp_path: Path) -> None:
    v1 = _register(store, fake_model_dir(tmp_path / "a"), promote=True)
    v2 = _register(store, fake_model_dir(tmp_path / "b"))
    store.promote(v2, "alice")
    # Trained while v1 was active; an admin switched to v2 meanwhile: keep v2 active.
    v3 = _register(store, fake_model_dir(tmp_path / "c"), promote=True, expected_active=v1)
    info = store.get(v3)
    assert (info.status, info.active) == ("candidate", False)
    assert info.note and "active model changed" in info.note
    assert store.active().id == v2


def test_failed_copy_leaves_no_row_and_no_folder(
    store: ModelStore, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    source = fake_model_dir(tmp_path / "a")
    real_copy = registry_module._copy_durably

    def disk_full_at_curve(src: Path, dst: Path) -> None:
        if src.name == "curve.png":
            raise OSError(28, "No space left on device")
        real_copy(src, dst)

    monkeypatch.setattr(registry_module, "_copy_durably", disk_full_at_curve)
    with pytest.raises(OSError, match="No space left"):
        _register(store, source, promote=True)
    assert store.list_models() == []
    assert store.active_or_none() is None
    assert list(store.root.iterdir()) == []


def test_failed_insert_removes_the_copied_folder(store: ModelStore, tmp_path: Path) -> None:
    # The row cannot be written; SQLite's driver wraps the error, PostgreSQL's raises it as is.
    with pytest.raises((StatementError, TypeError), match="not JSON serializable"):
        _register(store, fake_model_dir(tmp_path / "a"), data={"bad": object()})
    assert store.list_models() == []
    assert list(store.root.iterdir()) == []


def test_refuses_a_folder_without_a_model(store: ModelStore, tmp_path: Path) -> None:
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(InvalidModelDirError, match=r"model\.onnx"):
        _register(store, empty)
    broken = fake_model_dir(tmp_path / "broken")
    (broken / "metrics.json").write_text("{not json")
    with pytest.raises(InvalidModelDirError, match="not valid JSON"):
        _register(store, broken)
    assert store.list_models() == []
    assert list(store.root.iterdir()) == []


def test_files_only_of_registered_models(store: ModelStore, tmp_path: Path) -> None:
    model = _register(store, fake_model_dir(tmp_path / "a", curve=False), promote=True)
    assert json.loads(store.file(model, "metrics.json").read_text())["validation_accuracy"] == 0.5
    for model_id, name in [
        (model, "curve.png"),  # not written by this model
        (model, "secret.txt"),  # not a model file
        ("../" + model, "model.onnx"),
        ("unknown", "model.onnx"),
    ]:
        with pytest.raises(ModelNotFoundError):
            store.file(model_id, name)


def test_start_up_removes_incomplete_folders(store: ModelStore, tmp_path: Path) -> None:
    model = _register(store, fake_model_dir(tmp_path / "a"), promote=True)
    staging = store.root / ".staging-crashed"
    orphan = store.root / "0123456789ab"  # renamed into place, then the process died
    fake_model_dir(staging)
    fake_model_dir(orphan)
    removed = store.remove_leftovers()
    assert sorted(removed) == sorted([staging, orphan])
    assert [p.name for p in store.root.iterdir()] == [model]
