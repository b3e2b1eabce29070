"""A scene with no object that needs a supporter is the most uncertain (1, not 0), so "Next
scene" offers it first.

Revision ID: 0005
Revises: 0004
"""

from typing import Any

from alembic import op
from holiscene.store.migration_scenes import current_scenes, set_uncertainty

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
    for scene_id, data in current_scenes(bind):
        if _without_objects(data):
            set_uncertainty(bind, scene_id, value)


def upgrade() -> None:
    _set_uncertainty_of_scenes_without_objects(1.0)


def downgrade() -> None:
    _set_uncertainty_of_scenes_without_objects(0.0)
