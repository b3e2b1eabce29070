"""Each pipeline stage that warned raises a scene's doubt by a tenth of what is still trusted
(`editing/workflow_rules.py`, WARNING_DOUBT): stored scenes with warnings get their
uncertainty again by that rule, so "Next scene" and the list rank them as new ones are.

Revision ID: 0012
Revises: 0011
"""

import importlib.util
from pathlib import Path
from types import ModuleType

from alembic import op
from holiscene.store.migration_scenes import current_scenes, set_uncertainty

revision = "0012"
down_revision = "0011"
branch_labels = None
depends_on = None

# Frozen: the doubt per stage warning when this migration was written (the code may change).
_WARNING_DOUBT = 0.1


def _rule_of_0010() -> ModuleType:
    """Migration 0010's frozen rule (the mean doubt of the objects), loaded from its file."""
    path = Path(__file__).with_name("0010_uncertainty_of_detected_objects.py")
    spec = importlib.util.spec_from_file_location("_uncertainty_0010", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _set_uncertainties(with_warnings: bool) -> None:
    mean_doubt = _rule_of_0010()._uncertainty
    bind = op.get_bind()
    for scene_id, data in current_scenes(bind):
        warnings = sum(1 for stage in data.get("stages", []) if stage.get("warning"))
        if warnings == 0:
            continue  # the rules agree on it: leave it as stored
        mean = mean_doubt(data, True)
        kept = (1.0 - _WARNING_DOUBT) ** warnings if with_warnings else 1.0
        set_uncertainty(bind, scene_id, round(1.0 - (1.0 - mean) * kept, 6))


def upgrade() -> None:
    _set_uncertainties(with_warnings=True)


def downgrade() -> None:
    _set_uncertainties(with_warnings=False)
