"""A scene with no object that needs a supporter is the most uncertain (1, not 0), so "Next
scene" offers it first.

Revision ID: 0005
Revises: 0004
"""

import json
from typing import Any

import sqlalchemy as sa
from alembic import op

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None

# A frozen copy of the rule at the time of this migration (the code may change later).
_STRUCTURAL = {"wall", "floor", "ceiling"}


def _without_objects(scene: dict[str, Any]) -> bool:
    return all(o.get("class") in _STRUCTURAL for o in scene.get("objects", []))


def _set_uncertainty_of_scenes_without_objects(value: float) -> None:
    bind = op.get_bind()
    rows = bind.execute(
        sa.text(
            "SELECT s.id, r.scene FROM scenes s JOIN revisions r "
            "ON r.scene_id = s.id AND r.number = s.current_revision"
        )
    ).all()
    for scene_id, scene in rows:
        data = json.loads(scene) if isinstance(scene, str) else scene
        if _without_objects(data):
            bind.execute(
                sa.text("UPDATE scenes SET uncertainty = :u WHERE id = :id"),
                {"u": value, "id": scene_id},
            )


def upgrade() -> None:
    _set_uncertainty_of_scenes_without_objects(1.0)


def downgrade() -> None:
    _set_uncertainty_of_scenes_without_objects(0.0)
