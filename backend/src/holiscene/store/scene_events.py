"""Workflow state changes inside a scene's write transaction: the row of `scenes` and its
history row in `scene_events` are written together or not at all."""

from __future__ import annotations

from datetime import datetime
from typing import Any, Protocol

from holiscene_schema import SceneState, WorkflowAction
from sqlalchemy.orm import Session

from ..editing.workflow_rules import STATES, SceneStatus, WorkflowError, check_pipeline_allowed
from .clock import utcnow
from .tables import SceneEventRow, SceneRow

PIPELINE_ACTOR = "pipeline"


def as_state(value: str) -> SceneState:
    for state in STATES:
        if value == state:
            return state
    raise ValueError(f"unknown scene state {value!r} in the database")


class SceneHead(Protocol):
    """What the workflow reads of a scene's row: a SceneRow, or a row of a plain SELECT of
    these columns (the hot reads of every save)."""

    @property
    def id(self) -> str: ...
    @property
    def state(self) -> str: ...
    @property
    def assignee(self) -> str | None: ...
    @property
    def annotation_round(self) -> int: ...
    @property
    def current_revision(self) -> int: ...
    @property
    def archived_by(self) -> str | None: ...


def status_of(row: SceneHead) -> SceneStatus:
    return SceneStatus(
        state=as_state(row.state),
        assignee=row.assignee,
        annotation_round=row.annotation_round,
        archived_by=row.archived_by,
    )


def event_row(
    scene_id: str,
    *,
    at: datetime,
    action: WorkflowAction,
    to_state: SceneState,
    assignee: str | None,
    actor: str,
    revision: int,
    from_state: SceneState | None,
    annotation_round: int,
    comment: str | None = None,
) -> dict[str, Any]:
    """A row of `scene_events` by column (the id aside): written here through the session,
    and by revision_writes in the statement of a save that takes the scene."""
    return {
        "scene_id": scene_id,
        "at": at,
        "actor": actor,
        "action": action,
        "from_state": from_state,
        "to_state": to_state,
        "assignee": assignee,
        "revision": revision,
        "annotation_round": annotation_round,
        "comment": comment,
    }


def record_event(
    session: Session,
    row: SceneRow,
    *,
    action: WorkflowAction,
    to_state: SceneState,
    assignee: str | None,
    actor: str,
    revision: int,
    from_state: SceneState | None,
    comment: str | None = None,
) -> None:
    """Move the scene to `to_state` (and `assignee`) and write the history row."""
    row.state = to_state
    row.assignee = assignee
    values = event_row(
        row.id,
        at=utcnow(),
        action=action,
        to_state=to_state,
        assignee=assignee,
        actor=actor,
        revision=revision,
        from_state=from_state,
        annotation_round=row.annotation_round,
        comment=comment,
    )
    session.add(SceneEventRow(**values))


def pipeline_committed(session: Session, scene_id: str, revision: int) -> None:
    """A pipeline run is being stored as `revision`: a new scene becomes predicted. A scene a
    reviewer is judging (or accepted) must not change under them: WorkflowError."""
    row = session.get(SceneRow, scene_id)  # the revision's UPDATE loaded it: no SELECT
    if row is None:
        return
    status = status_of(row)
    try:
        check_pipeline_allowed(status)
    except WorkflowError as exc:
        raise WorkflowError(f"{exc}; this run's result was not stored") from exc
    if status.state == "new":
        record_event(
            session,
            row,
            action="predict",
            to_state="predicted",
            assignee=None,
            actor=PIPELINE_ACTOR,
            revision=revision,
            from_state="new",
        )
