"""What the data migrations that recompute a stored figure share (migrations 0005, 0010,
0012): each scene's current revision read as plain JSON, and one scene's uncertainty written.
Plain SQL and dicts, not the models: a migration must run on the tables as they were."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import sqlalchemy as sa
from sqlalchemy.engine import Connection


def current_scenes(bind: Connection) -> Iterator[tuple[str, dict[str, Any]]]:
    """(scene id, its current revision's scene as a dict), for every stored scene."""
    rows = bind.execute(
        sa.text(
            "SELECT s.id, r.scene FROM scenes s JOIN revisions r "
            "ON r.scene_id = s.id AND r.number = s.current_revision"
        )
    ).all()
    for scene_id, scene in rows:
        yield scene_id, json.loads(scene) if isinstance(scene, str) else scene


def set_uncertainty(bind: Connection, scene_id: str, value: float) -> None:
    bind.execute(
        sa.text("UPDATE scenes SET uncertainty = :u WHERE id = :id"), {"u": value, "id": scene_id}
    )
