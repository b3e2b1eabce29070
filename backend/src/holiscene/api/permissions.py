"""What the user asking may do with a scene, added to the answers about it."""

from __future__ import annotations

from typing import TypeVar

from holiscene_schema import SceneDocument, SceneWorkflow

from ..editing.workflow_rules import Actor
from ..services.workbench import Workbench

AboutScene = TypeVar("AboutScene", SceneDocument, SceneWorkflow)


def with_edit_permission(answer: AboutScene, workbench: Workbench, user: Actor) -> AboutScene:
    """The answer with `editable` and `editable_reason` for this user and revision."""
    refusal = workbench.workflow.edit_refusal(answer.scene_id, user, answer.revision)
    return answer.model_copy(update={"editable": refusal is None, "editable_reason": refusal})
