"""What the user asking may do with a scene, added to the answers about it."""

from __future__ import annotations

from typing import TypeVar

from holiscene_schema import SceneDocument, SceneWorkflow

from ..editing.workflow_rules import Actor
from ..services.workbench import Workbench

AboutScene = TypeVar("AboutScene", SceneDocument, SceneWorkflow)


def with_edit_permission(
    answer: AboutScene, workbench: Workbench, user: Actor, *, by_number: bool = False
) -> AboutScene:
    """The answer with `editable` and `editable_reason` for this user.

    An answer about the latest revision is judged by the scene's state and the user alone: a
    colleague's save landing between reading it and asking here does not make it read only
    (the page learns of that revision when it saves, and merges). `by_number`: the
    answer is a revision the user asked for by number, editable only while it is the latest."""
    revision = answer.revision if by_number else None
    refusal = workbench.workflow.edit_refusal(answer.scene_id, user, revision)
    return answer.model_copy(update={"editable": refusal is None, "editable_reason": refusal})
