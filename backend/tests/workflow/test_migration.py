"""Migration 0003 on a database of scenes stored before accounts and states existed."""

from __future__ import annotations

import json
from pathlib import Path

from alembic import command
from alembic.config import Config
from holiscene.core.db import MIGRATIONS_DIR, make_engine
from sqlalchemy import text

from .scenes import make_scene


def _upgrade(engine: object, target: str) -> None:
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS_DIR))
    with engine.begin() as connection:  # type: ignore[attr-defined]
        config.attributes["connection"] = connection
        command.upgrade(config, target)


def test_existing_scenes_get_a_state_and_an_uncertainty(tmp_path: Path) -> None:
    engine = make_engine(f"sqlite:///{tmp_path / 'old.db'}")
    _upgrade(engine, "0002")
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
    _upgrade(engine, "head")
    with engine.connect() as connection:
        rows = connection.execute(
            text("SELECT id, state, assignee, annotation_round, uncertainty FROM scenes")
        ).all()
    assert {row[0]: tuple(row[1:]) for row in rows} == {
        "imported": ("new", None, 1, 0.85),
        "predicted": ("predicted", None, 1, 0.85),
        "edited": ("in_annotation", None, 1, 0.85),
    }
    engine.dispose()
