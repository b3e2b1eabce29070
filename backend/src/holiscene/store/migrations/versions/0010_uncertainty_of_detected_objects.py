"""An object the detector made and no person has touched counts as doubtful as the chance it
is not real, besides its supporter: stored scenes get their uncertainty again by that rule.

Revision ID: 0010
Revises: 0009
"""

from typing import Any

from alembic import op
from holiscene.store.migration_scenes import current_scenes, set_uncertainty

revision = "0010"
down_revision = "0009"
branch_labels = None
depends_on = None

# Frozen copies of the rules before and after this migration (the code may change later).
_STRUCTURAL = {"wall", "floor", "ceiling"}
_UNKNOWN = 0.5


def _object_doubt(obj: dict[str, Any], support: dict[str, Any] | None, detected: bool) -> float:
    if support is None:
        doubt = 1.0
    elif support.get("source") == "auto":
        confidence = support.get("confidence")
        doubt = 1.0 - (_UNKNOWN if confidence is None else confidence)
    else:
        return 0.0
    if detected and obj.get("source") == "detector" and not obj.get("set_by_person"):
        score = obj.get("score")
        doubt = 1.0 - (1.0 - doubt) * (_UNKNOWN if score is None else score)
    return doubt


def _uncertainty(scene: dict[str, Any], detected: bool) -> float:
    objects = [o for o in scene.get("objects", []) if o.get("class") not in _STRUCTURAL]
    if not objects:
        return 1.0
    supports = {s["child"]: s for s in scene.get("supports", [])}
    total = sum(_object_doubt(o, supports.get(o["id"]), detected) for o in objects)
    return round(total / len(objects), 6)


def _set_uncertainties(detected: bool) -> None:
    bind = op.get_bind()
    for scene_id, data in current_scenes(bind):
        if not any(o.get("source") == "detector" for o in data.get("objects", [])):
            continue  # the rules agree on it: leave it as stored
        set_uncertainty(bind, scene_id, _uncertainty(data, detected))


def upgrade() -> None:
    _set_uncertainties(detected=True)


def downgrade() -> None:
    _set_uncertainties(detected=False)
