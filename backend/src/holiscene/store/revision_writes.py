"""Writing a scene's next revision: the scene row moves from the revision the write was based
on to the next one (a conditional UPDATE, so of two writers on the same base exactly one
wins), and the revision's row is added.

A save by the annotator holding the scene needs nothing checked in between, so it is written
at once (`write_at_once`): on PostgreSQL as one statement that commits by itself. So is the
save that takes the scene (its workflow move and history row go with the revision, guarded by
the state its rules were checked on), else twenty annotators starting at once each pay a
transaction of five round trips. Writes that must look at the scene inside their transaction
(a take whose guard failed, a job's result) go through `SceneStore` with a hook and add their
revision with `add_revision`.

The statements are built once, with parameters (building and caching a statement of this
size costs about as much CPU as sending it), and the scene goes to the database as the JSON
text pydantic writes, not as a dict the driver writes again (a sixth of the CPU for a scene
of 36 objects: docs/benchmarks.md, concurrent writers).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from datetime import datetime
from typing import Any, cast

from holiscene_schema import Edit, RevisionKind, Scene
from pydantic import TypeAdapter
from sqlalchemy import (
    JSON,
    ColumnElement,
    Connection,
    Engine,
    Insert,
    Table,
    Text,
    Update,
    bindparam,
    insert,
    select,
    update,
)
from sqlalchemy import cast as sql_cast
from sqlalchemy.orm import Session

from ..editing.workflow_rules import SceneStatus, Transition
from .scene_events import event_row
from .tables import RevisionRow, SceneEventRow, SceneRow

_EDITS = TypeAdapter(list[Edit])
REVISIONS = cast(Table, RevisionRow.__table__)
_COLUMNS = [c.name for c in REVISIONS.c if c.name != "id"]
EVENTS = cast(Table, SceneEventRow.__table__)
_EVENT_COLUMNS = [c.name for c in EVENTS.c if c.name != "id"]

# The statements' parameters are the revision's columns and the values below, all named
# with this prefix: a parameter named like a column of `scenes` would be taken as a value to
# SET by the UPDATE. The history row's parameters have a prefix of their own.
_P = "p_"
_E = "e_"


@dataclass(frozen=True)
class WorkflowMove:
    """A workflow transition written with the revision: the scene's new state and assignee,
    and who made the move (the history row's actor)."""

    transition: Transition
    actor: str


def revision_values(
    scene_id: str,
    number: int,
    author: str,
    kind: RevisionKind,
    summary: str,
    edits: Sequence[Edit] | None,
    scene: Scene,
    created_at: datetime,
) -> dict[str, Any]:
    """A row of `revisions`, by column; the scene as JSON text."""
    return {
        "scene_id": scene_id,
        "number": number,
        "created_at": created_at,
        "author": author,
        "kind": kind,
        "summary": summary,
        "edits": _EDITS.dump_python(list(edits), mode="json") if edits is not None else None,
        "scene": scene.model_dump_json(),
    }


def _value(name: str, postgres: bool) -> ColumnElement[Any]:
    """The parameter for a revision column. The scene comes as text: PostgreSQL needs it cast
    to json; SQLite keeps JSON as text anyway."""
    if name != "scene":
        return bindparam(f"{_P}{name}", type_=REVISIONS.c[name].type)
    text = bindparam(f"{_P}scene", type_=Text)
    return sql_cast(text, JSON) if postgres else text


def _moved(guarded: bool, moving: bool) -> Update:
    """The scene row's UPDATE to the next revision, if still at the base revision and, when
    `guarded`, in the workflow state the save's rules were checked on; `moving`: to the state
    and assignee of a workflow move too."""
    where = [
        SceneRow.id == bindparam(f"{_P}scene_id"),
        SceneRow.current_revision == bindparam(f"{_P}base"),
    ]
    if guarded:
        where += [
            SceneRow.state == bindparam(f"{_P}state"),
            SceneRow.assignee.is_not_distinct_from(bindparam(f"{_P}assignee")),
            SceneRow.annotation_round == bindparam(f"{_P}round"),
        ]
    values: dict[str, Any] = {
        "current_revision": bindparam(f"{_P}number"),
        "updated_at": bindparam(f"{_P}created_at"),
        "object_count": bindparam(f"{_P}object_count"),
        "uncertainty": bindparam(f"{_P}uncertainty"),
    }
    if moving:
        values |= {"state": bindparam(f"{_E}to_state"), "assignee": bindparam(f"{_E}assignee")}
    return update(SceneRow).where(*where).values(values)


def _event_value(name: str) -> ColumnElement[Any]:
    return bindparam(f"{_E}{name}", type_=EVENTS.c[name].type)


def _moved_and_added(guarded: bool, moving: bool) -> Insert:
    """PostgreSQL: the UPDATE and the INSERT of the revision (and of the history row of a
    workflow move) in one statement. The INSERTs take their scene id from the UPDATE's
    RETURNING, so they add nothing when the UPDATE moved nothing, and the statement is
    written whole or not at all."""
    scene_moved = _moved(guarded, moving).returning(SceneRow.id).cte("scene_moved")
    row = [scene_moved.c.id if c == "scene_id" else _value(c, postgres=True) for c in _COLUMNS]
    added = insert(REVISIONS).from_select(_COLUMNS, select(*row)).returning(REVISIONS.c.number)
    if not moving:
        return added
    event = [scene_moved.c.id if c == "scene_id" else _event_value(c) for c in _EVENT_COLUMNS]
    recorded = insert(EVENTS).from_select(_EVENT_COLUMNS, select(*event)).cte("event_added")
    return added.add_cte(recorded)


_KINDS = [(guarded, moving) for guarded in (False, True) for moving in (False, True)]
_MOVED = {kind: _moved(*kind) for kind in _KINDS}
_MOVED_AND_ADDED = {kind: _moved_and_added(*kind) for kind in _KINDS}
_ADDED = {
    postgres: insert(REVISIONS).values({c: _value(c, postgres) for c in _COLUMNS})
    for postgres in (False, True)
}
_EVENT_ADDED = insert(EVENTS).values({c: _event_value(c) for c in _EVENT_COLUMNS})


def _params(values: dict[str, Any]) -> dict[str, Any]:
    return {f"{_P}{name}": value for name, value in values.items()}


def _event_params(
    move: WorkflowMove, seen: SceneStatus, revision: dict[str, Any]
) -> dict[str, Any]:
    """The history row of `move`, made on `revision` from the status `seen`."""
    values = event_row(
        revision["scene_id"],
        at=revision["created_at"],
        action=move.transition.action,
        to_state=move.transition.to_state,
        assignee=move.transition.assignee,
        actor=move.actor,
        revision=revision["number"],
        from_state=seen.state,
        annotation_round=seen.annotation_round,
    )
    return {f"{_E}{name}": value for name, value in values.items()}


def add_revision(db: Session | Connection, revision: dict[str, Any]) -> None:
    """INSERT `revision` (revision_values) in the session's or connection's transaction."""
    bind = db.get_bind() if isinstance(db, Session) else db
    postgres = bind.dialect.name == "postgresql"
    db.execute(_ADDED[postgres], _params(revision))


def write_at_once(
    engine: Engine,
    base_revision: int,
    revision: dict[str, Any],
    object_count: int,
    uncertainty: float | None,
    unchanged: SceneStatus | None,
    move: WorkflowMove | None = None,
) -> bool:
    """Move the scene's row to `revision` (revision_values) and add it, if the row is still
    at `base_revision` and, when given, in the workflow status `unchanged`; False (nothing
    written) when it is not. `move` (needs `unchanged`): the workflow move the rules allowed
    from that status, written with its history row. `engine`: one without transactions on
    PostgreSQL (each statement commits by itself): one round trip instead of four (BEGIN,
    UPDATE, INSERT, COMMIT), each a wait for another process that 20 writers on two cores
    feel."""
    if move is not None and unchanged is None:
        raise ValueError("a workflow move is written only from the status it was checked on")
    values = {**revision, "base": base_revision}
    values |= {"object_count": object_count, "uncertainty": uncertainty}
    if unchanged is not None:
        values |= {
            "state": unchanged.state,
            "assignee": unchanged.assignee,
            "round": unchanged.annotation_round,
        }
    params = _params(values)
    if move is not None and unchanged is not None:
        params |= _event_params(move, unchanged, revision)
    kind = (unchanged is not None, move is not None)
    if engine.dialect.name == "postgresql":
        with engine.connect() as connection:
            added = connection.execute(_MOVED_AND_ADDED[kind], params)
            return added.first() is not None
    with engine.begin() as connection:  # SQLite: no UPDATE inside WITH
        if connection.execute(_MOVED[kind], params).rowcount != 1:
            return False  # the UPDATE changed nothing: nothing to roll back
        if move is not None:
            connection.execute(_EVENT_ADDED, params)
        add_revision(connection, revision)
    return True
