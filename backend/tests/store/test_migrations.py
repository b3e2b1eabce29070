"""Migrations on databases written by earlier versions: 0003 on scenes stored before accounts
and states existed, 0004 on accounts and sessions stored before idle timeouts and disabling,
0005 on scenes without objects stored as the least uncertain, 0007 on scenes with several
jobs waiting, 0010 on scenes with objects the detector made, 0012 on scenes with pipeline
warnings."""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator

import pytest
from alembic import command
from alembic.config import Config
from holiscene.core.db import MIGRATIONS_DIR, make_engine
from holiscene.core.settings import Settings
from holiscene.editing.workflow_rules import scene_uncertainty
from holiscene_schema import Scene, StageRun
from sqlalchemy import Engine, inspect, text
from sqlalchemy.exc import IntegrityError

from ..stored_scenes import make_scene

# Written for SQLite first: each migration must also run on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases


@pytest.fixture()
def engine(settings: Settings) -> Iterator[Engine]:
    """The test's empty database (SQLite or PostgreSQL), not migrated yet."""
    settings.data_dir.mkdir(parents=True)
    made = make_engine(settings.resolved_database_url)
    yield made
    made.dispose()


def _migrate(
    engine: object, target: str, step: Callable[[Config, str], None] = command.upgrade
) -> None:
    """Migrate up to `target` (or down to it, with `step=command.downgrade`)."""
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS_DIR))
    with engine.begin() as connection:  # type: ignore[attr-defined]
        config.attributes["connection"] = connection
        step(config, target)


def test_existing_scenes_get_a_state_and_an_uncertainty(engine: Engine) -> None:
    _migrate(engine, "0002")
    predicted = make_scene([("o0", "floor", "below")], {"o0": 0.6})  # (0.4 + 1 * 3) / 4
    kinds = {"imported": ["import"], "predicted": ["import", "pipeline"]}
    kinds["edited"] = [*kinds["predicted"], "edit"]
    with engine.begin() as connection:
        for scene_id, revisions in kinds.items():
            connection.execute(
                text(
                    "INSERT INTO scenes VALUES (:id, :id, '2026-01-01', '2026-01-01', :n, "
                    "'img.png', 64, 48, 5, NULL)"
                ),
                {"id": scene_id, "n": len(revisions)},
            )
            for number, kind in enumerate(revisions, 1):
                connection.execute(
                    text(
                        "INSERT INTO revisions (scene_id, number, created_at, author, kind, "
                        "summary, scene) VALUES (:id, :n, '2026-01-01', 'x', :kind, '', :scene)"
                    ),
                    {
                        "id": scene_id,
                        "n": number,
                        "kind": kind,
                        "scene": json.dumps(predicted.model_dump(mode="json")),
                    },
                )
    _migrate(engine, "head")
    with engine.connect() as connection:
        rows = connection.execute(
            text("SELECT id, state, assignee, annotation_round, uncertainty FROM scenes")
        ).all()
    assert {row[0]: tuple(row[1:]) for row in rows} == {
        "imported": ("new", None, 1, 0.85),
        "predicted": ("predicted", None, 1, 0.85),
        "edited": ("in_annotation", None, 1, 0.85),
    }


def test_open_sessions_get_a_last_seen_time_and_accounts_stay_enabled(engine: Engine) -> None:
    _migrate(engine, "0003")
    with engine.begin() as connection:
        connection.execute(
            text(
                "INSERT INTO users (id, name, role, password_hash, created_at) "
                "VALUES (1, 'ada', 'admin', 'x', '2026-01-01 00:00:00')"
            )
        )
        connection.execute(
            text(
                "INSERT INTO sessions VALUES ('h', 1, '2026-01-02 10:00:00', '2026-01-09 10:00:00')"
            )
        )
    _migrate(engine, "head")
    with engine.connect() as connection:
        session = connection.execute(text("SELECT created_at, last_seen_at FROM sessions")).one()
        disabled = connection.execute(text("SELECT disabled_at FROM users")).scalar_one()
        # The index on sessions.user_id survives the copy of the table.
        indexes = [index["name"] for index in inspect(connection).get_indexes("sessions")]
    assert session[1] == session[0] and disabled is None
    assert "ix_sessions_user_id" in indexes

    # And back: 0004 can be undone.
    _migrate(engine, "0003", step=command.downgrade)
    with engine.connect() as connection:
        columns = [column["name"] for column in inspect(connection).get_columns("sessions")]
    assert "last_seen_at" not in columns and len(columns) == 4


def test_scenes_without_objects_become_the_most_uncertain(engine: Engine) -> None:
    _migrate(engine, "0004")
    predicted = make_scene([("o0", "floor", "below")], {"o0": 0.6})  # (0.4 + 1 * 3) / 4
    walls = [o for o in predicted.objects if o.cls == "wall"]
    stored = {
        "objects": (predicted, 0.85),
        "empty": (predicted.model_copy(update={"objects": [], "supports": []}), 0.0),
        "walls": (predicted.model_copy(update={"objects": walls, "supports": []}), 0.0),
    }
    _store_scenes(engine, stored)
    _migrate(engine, "head")
    assert _uncertainties(engine) == {"objects": 0.85, "empty": 1.0, "walls": 1.0}
    _migrate(engine, "0004", step=command.downgrade)
    assert _uncertainties(engine) == {"objects": 0.85, "empty": 0.0, "walls": 0.0}


def test_scenes_with_detected_objects_get_their_doubt(engine: Engine) -> None:
    _migrate(engine, "0009")
    given = make_scene([("o0", "floor", "below")], {"o0": 0.6})  # (0.4 + 1 * 3) / 4
    detected = given.model_copy(
        update={
            "objects": [
                o.model_copy(update={"source": "detector", "score": 0.5}) if o.id == "o0" else o
                for o in given.objects
            ]
        }
    )
    _store_scenes(engine, {"given": (given, 0.85), "detected": (detected, 0.85)})
    _migrate(engine, "head")
    # o0 real with chance 0.5 and on the floor with 0.6: doubt 0.7 instead of 0.4.
    assert _uncertainties(engine) == {"given": 0.85, "detected": pytest.approx(0.925)}
    _migrate(engine, "0009", step=command.downgrade)
    assert _uncertainties(engine) == {"given": 0.85, "detected": pytest.approx(0.85)}


def test_scenes_with_pipeline_warnings_get_their_doubt(engine: Engine) -> None:
    _migrate(engine, "0011")
    sure = make_scene(
        [
            ("o0", "floor", "below"),
            ("o1", "floor", "below"),
            ("o2", "floor", "below"),
            ("o3", "floor", "below"),
        ],
        dict.fromkeys(("o0", "o1", "o2", "o3"), 1.0),
    )
    warned = sure.model_copy(
        update={
            "stages": [
                StageRun(name="masks_grabcut", seconds=0.1, note="2 boxes left", warning=True),
                StageRun(name="heights_by_metrology", seconds=0.1, note="1", warning=True),
                StageRun(name="placement", seconds=0.1, note="placed", warning=False),
            ]
        }
    )
    _store_scenes(engine, {"sure": (sure, 0.0), "warned": (warned, 0.0)})
    _migrate(engine, "head")
    # Two warnings: 1 - (1 - 0) * 0.9 ** 2, as the live rule gives it.
    assert _uncertainties(engine) == {"sure": 0.0, "warned": pytest.approx(0.19)}
    assert scene_uncertainty(warned) == pytest.approx(0.19)
    _migrate(engine, "0011", step=command.downgrade)
    assert _uncertainties(engine) == {"sure": 0.0, "warned": pytest.approx(0.0)}


def _store_scenes(engine: Engine, stored: dict[str, tuple[Scene, float]]) -> None:
    """Scenes as an earlier version stored them: id -> (revision 1, stored uncertainty)."""
    with engine.begin() as connection:
        for scene_id, (scene, uncertainty) in stored.items():
            connection.execute(
                text(
                    "INSERT INTO scenes (id, name, created_at, updated_at, current_revision, "
                    "image_file, width, height, object_count, state, annotation_round, "
                    "uncertainty) VALUES (:id, :id, '2026-01-01', '2026-01-01', 1, 'img.png', "
                    "64, 48, :count, 'predicted', 1, :u)"
                ),
                {"id": scene_id, "count": len(scene.objects), "u": uncertainty},
            )
            connection.execute(
                text(
                    "INSERT INTO revisions (scene_id, number, created_at, author, kind, "
                    "summary, scene) VALUES (:id, 1, '2026-01-01', 'x', 'pipeline', '', :scene)"
                ),
                {"id": scene_id, "scene": json.dumps(scene.model_dump(mode="json"))},
            )


def _uncertainties(engine: Engine) -> dict[str, float]:
    with engine.connect() as connection:
        rows = connection.execute(text("SELECT id, uncertainty FROM scenes")).all()
    return {row[0]: row[1] for row in rows}


def test_a_scene_keeps_only_its_newest_waiting_job(engine: Engine) -> None:
    """0007: a scene may have one pipeline or placement job queued or running; of several
    from before, the newest stays and the others are failed, saying why."""
    _migrate(engine, "0006")
    jobs = {
        "old": ("pipeline", "queued", "2026-01-01 10:00:00"),
        "older": ("placement", "running", "2026-01-01 09:00:00"),
        "newest": ("pipeline", "queued", "2026-01-01 11:00:00"),
        "done": ("pipeline", "succeeded", "2026-01-01 12:00:00"),
    }
    with engine.begin() as connection:
        connection.execute(
            text(
                "INSERT INTO scenes (id, name, created_at, updated_at, current_revision, "
                "image_file, width, height, object_count, state, annotation_round) VALUES "
                "('s', 's', '2026-01-01', '2026-01-01', 1, 'img.png', 64, 48, 0, 'new', 1)"
            )
        )
        for job_id, (kind, status, created) in jobs.items():
            connection.execute(
                text(
                    "INSERT INTO jobs (id, scene_id, kind, status, progress, created_at) "
                    "VALUES (:id, 's', :kind, :status, 0, :created)"
                ),
                {"id": job_id, "kind": kind, "status": status, "created": created},
            )
    _migrate(engine, "head")
    with engine.connect() as connection:
        rows = connection.execute(text("SELECT id, status, error, started_by FROM jobs")).all()
    statuses = {row[0]: row[1] for row in rows}
    assert statuses == {"old": "failed", "older": "failed", "newest": "queued", "done": "succeeded"}
    assert all("a newer job of this scene" in row[2] for row in rows if row[0] in ("old", "older"))
    assert {row[3] for row in rows} == {None}  # nobody knows who started them

    # The database itself refuses a second waiting job on the scene now.
    with pytest.raises(IntegrityError), engine.begin() as connection:
        connection.execute(
            text(
                "INSERT INTO jobs (id, scene_id, kind, status, progress, created_at) "
                "VALUES ('second', 's', 'placement', 'queued', 0, '2026-01-02')"
            )
        )
    _migrate(engine, "0006", step=command.downgrade)
    assert "started_by" not in {c["name"] for c in inspect(engine).get_columns("jobs")}
