"""The annotation workflow in the store: taking scenes (by editing them or "Next scene"),
submitting, reviewing, second annotations, each scene's history and the dashboard.

Every state change is one transaction that also writes its `scene_events` row, and names the
revision it concerns: a submission, acceptance or rejection of anything but the latest
revision is refused (RevisionConflictError), so nobody submits or accepts what they did not
see.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Callable, Sequence
from typing import cast, get_args

from holiscene_schema import (
    Dashboard,
    EditRequest,
    PersonStats,
    Role,
    SceneAgreement,
    SceneDocument,
    SceneState,
    SceneSummary,
    SceneWorkflow,
    WorkflowAction,
    WorkflowEvent,
)
from sqlalchemy import Connection, Engine, and_, func, or_, select, update
from sqlalchemy.orm import Session

from ..core.errors import DomainError, NotFoundError
from ..editing import workflow_rules
from ..editing.edits import restored_scene_revision
from ..editing.workflow_rules import STATES, Actor, SceneStatus, Transition, WorkflowError
from .clock import as_utc
from .revision_writes import WorkflowMove
from .scene_events import SceneHead, as_state, record_event, status_of
from .scenes import (
    RevisionConflictError,
    SceneNotFoundError,
    SceneRowChangedError,
    SceneStore,
)
from .tables import SCENE_IN_USE, SceneEventRow, SceneRow

_ACTIONS = get_args(WorkflowAction)


class NoSceneWaitingError(NotFoundError):
    """Next scene found nothing to annotate (HTTP 404 with the message)."""


class WorkflowCommentError(DomainError, ValueError):
    """A rejection without a comment (HTTP 422)."""


class WorkflowStore:
    def __init__(self, engine: Engine, scenes: SceneStore) -> None:
        self.engine = engine
        self.scenes = scenes

    # -- reading -------------------------------------------------------------------------

    def scene_workflow(self, scene_id: str) -> SceneWorkflow:
        with Session(self.engine) as session:
            row = _row(session, scene_id)
            events = [
                _event(e)
                for e in session.scalars(
                    select(SceneEventRow)
                    .where(SceneEventRow.scene_id == scene_id)
                    .order_by(SceneEventRow.id)
                )
            ]
            return SceneWorkflow(
                scene_id=scene_id,
                state=as_state(row.state),
                assignee=row.assignee,
                annotation_round=row.annotation_round,
                revision=row.current_revision,
                review_comment=_open_rejection(events),
                events=events,
                archived_by=row.archived_by,
            )

    def edit_refusal(self, scene_id: str, actor: Actor, revision: int | None = None) -> str | None:
        """Why the actor may not edit the scene now, or None when they may. `revision`: the
        revision they look at; edits apply to the latest only."""
        with Session(self.scenes.reads) as session:  # asked on every save and scene load
            row = _row(session, scene_id)
            if revision is not None and revision != row.current_revision:
                return (
                    f"revision {revision} is an earlier one: edits apply to the latest "
                    f"(revision {row.current_revision})"
                )
            return workflow_rules.edit_refusal(
                status_of(row), actor, _earlier_annotators(session, row)
            )

    def check_job_allowed(self, scene_id: str, actor: Actor) -> None:
        """WorkflowError when the actor may not start a pipeline or placement job now."""
        with Session(self.engine) as session:
            workflow_rules.check_job_allowed(status_of(_row(session, scene_id)), actor)

    # -- annotators ----------------------------------------------------------------------

    def edit(self, scene_id: str, request: EditRequest, actor: Actor) -> SceneDocument:
        """Apply an annotator's edits; the first edit takes the scene (predicted -> in
        annotation, or rejected -> in annotation again). In the same transaction.

        A scene the actor may not edit is refused (WorkflowError) before the edits are even
        looked at, on the row read with the revision. The rules hold again when the revision
        is written: it is written, with the take when the save takes the scene, only if the
        state, assignee and round are still those the rules saw (one statement, no
        transaction on PostgreSQL); else the save checks the rules again inside a write
        transaction."""
        # The status seen, and the move the rules allow from it (None: the actor holds it).
        seen: list[tuple[SceneStatus, WorkflowMove | None]] = []

        def refuse(connection: Connection, row: SceneHead) -> None:
            status = status_of(row)
            earlier = _earlier_annotators(connection, row)
            transition = workflow_rules.take_for_annotation(status, actor, earlier)
            seen.append(
                (status, None if transition is None else WorkflowMove(transition, actor.name))
            )

        def take(session: Session, revision: int) -> None:
            # The revision's UPDATE already holds the scene's row; the take is still a
            # compare-and-set, so it cannot overwrite a take that committed in between.
            row = _row(session, scene_id)
            transition = workflow_rules.take_for_annotation(
                status_of(row), actor, _earlier_annotators(session, row)
            )
            if transition is not None and not _apply_if_unchanged(
                session, row, transition, actor, revision
            ):
                raise WorkflowError("the scene changed meanwhile; reload it and try again")

        base = self.scenes.document_for_write(scene_id, request.base_revision, refuse)
        edited = self.scenes.edited(scene_id, base.scene, request)
        # A revert also moves the scene's GLB: not in the one statement, so under the hook.
        if seen and restored_scene_revision(request.edits) is None:
            status, move = seen[0]
            try:
                return self.scenes.commit_edits(
                    scene_id, request, edited, unchanged=status, move=move, before=base.scene
                )
            except SceneRowChangedError:
                pass  # submitted, rejected or taken meanwhile: the rules once more, in a
                # transaction that says who took it
        return self.scenes.commit_edits(scene_id, request, edited, hook=take, before=base.scene)

    def take(self, scene_id: str, actor: Actor) -> SceneSummary:
        """Take a scene for annotation without editing it yet (an admin: also take it over)."""
        with Session(self.engine) as session:
            row = _row(session, scene_id)
            transition = workflow_rules.take_for_annotation(
                status_of(row), actor, _earlier_annotators(session, row), taking=True
            )
            if transition is not None:
                if _apply_if_unchanged(session, row, transition, actor, row.current_revision):
                    session.commit()
                else:
                    session.rollback()
                    _refuse_unless_taken_by(session, scene_id, actor)
        return self.scenes.summary(scene_id)

    def next_scene(self, actor: Actor) -> SceneSummary:
        """The annotator's next scene, now assigned to them: first one of theirs a reviewer
        rejected (oldest first), else the predicted scene the pipeline is least sure of; the
        scenes they gave back come after all others."""
        for _ in range(20):  # another annotator may take a candidate first: try the next
            with Session(self.engine) as session:
                candidates = self._next_candidates(session, actor)
                if not candidates:
                    raise NoSceneWaitingError(
                        "no scene is waiting for annotation: every predicted scene is taken"
                    )
                for row in candidates:
                    try:
                        transition = workflow_rules.take_for_annotation(
                            status_of(row), actor, _earlier_annotators(session, row)
                        )
                    except WorkflowError:
                        continue  # e.g. an earlier round of this scene was theirs
                    if transition is None:
                        continue
                    if _apply_if_unchanged(session, row, transition, actor, row.current_revision):
                        session.commit()
                        return self.scenes.summary(row.id)
                    session.rollback()
                    break  # taken meanwhile: read the candidates again
                else:
                    raise NoSceneWaitingError(
                        "no scene is waiting for annotation by you: the predicted scenes left "
                        "were annotated by you in an earlier round"
                    )
        raise NoSceneWaitingError("every candidate was taken by someone else; try again")

    def next_to_review(self, actor: Actor, after: str | None = None) -> SceneSummary:
        """The scene waiting longest for review that the reviewer did not annotate (any, in
        single-user mode). Nothing changes: reviewing needs no claim, and a scene opened but
        not judged stays for the next reviewer.

        `after`: the scene the reviewer has open; the one waiting next after it comes back
        (round the queue to the oldest), never that scene itself: a reviewer who skips a
        scene moves on through the queue instead of being handed the same one again."""
        query = select(SceneRow).where(SceneRow.state == "submitted", SCENE_IN_USE)
        if not actor.local:
            query = query.where(SceneRow.assignee.is_distinct_from(actor.name))
        in_queue_order = (SceneRow.updated_at, SceneRow.id)
        with Session(self.engine) as session:
            current = session.get(SceneRow, after) if after else None
            row = None
            if current is not None:
                later = or_(
                    SceneRow.updated_at > current.updated_at,
                    and_(SceneRow.updated_at == current.updated_at, SceneRow.id > current.id),
                )
                row = session.scalars(query.where(later).order_by(*in_queue_order).limit(1)).first()
                query = query.where(SceneRow.id != current.id)
            if row is None:
                row = session.scalars(query.order_by(*in_queue_order).limit(1)).first()
        if row is None:
            other = " other than this one" if current is not None else ""
            raise NoSceneWaitingError(f"no scene{other} is waiting for your review")
        return self.scenes.summary(row.id)

    @staticmethod
    def _next_candidates(session: Session, actor: Actor) -> list[SceneRow]:
        mine = select(SceneRow).where(
            SceneRow.state == "rejected", SceneRow.assignee == actor.name, SCENE_IN_USE
        )
        rejected = list(session.scalars(mine.order_by(SceneRow.updated_at)))
        predicted = session.scalars(
            select(SceneRow)
            .where(SceneRow.state == "predicted", SCENE_IN_USE)
            .order_by(
                SceneRow.uncertainty.is_(None),  # unknown last
                SceneRow.uncertainty.desc(),
                SceneRow.object_count > 0,  # of the most uncertain, scenes without objects first
                SceneRow.created_at,
            )
            .limit(50)
        ).all()
        given_back = set(
            session.scalars(
                select(SceneEventRow.scene_id).where(
                    SceneEventRow.action == "release", SceneEventRow.actor == actor.name
                )
            )
        )
        # Given back as taken by mistake: offering it straight back would trap them in it.
        return rejected + sorted(predicted, key=lambda row: row.id in given_back)

    def release(self, scene_id: str, revision: int, actor: Actor) -> SceneWorkflow:
        """Give back a scene in annotation: unassigned, predicted again (new when the pipeline
        never ran on it), its revisions kept."""
        predicted = self.scenes.latest_pipeline_revision(scene_id) is not None
        with Session(self.engine) as session:
            sent_back = _rejected_this_round(session, _row(session, scene_id))
        return self._change(
            scene_id,
            revision,
            lambda status: workflow_rules.release(status, actor, predicted, sent_back),
            actor,
        )

    def submit(self, scene_id: str, revision: int, actor: Actor) -> SceneWorkflow:
        return self._change(
            scene_id, revision, lambda status: workflow_rules.submit(status, actor), actor
        )

    def withdraw(self, scene_id: str, revision: int, actor: Actor) -> SceneWorkflow:
        return self._change(
            scene_id, revision, lambda status: workflow_rules.withdraw(status, actor), actor
        )

    # -- reviewers -----------------------------------------------------------------------

    def accept(
        self, scene_id: str, revision: int, actor: Actor, comment: str | None
    ) -> SceneWorkflow:
        return self._change(
            scene_id,
            revision,
            lambda s: workflow_rules.review(s, actor, accept=True),
            actor,
            comment,
        )

    def reject(self, scene_id: str, revision: int, actor: Actor, comment: str) -> SceneWorkflow:
        if not comment.strip():
            raise WorkflowCommentError("a rejection needs a comment saying what went wrong")
        return self._change(
            scene_id,
            revision,
            lambda s: workflow_rules.review(s, actor, accept=False),
            actor,
            comment.strip(),
        )

    def second_annotation(
        self, scene_id: str, revision: int, actor: Actor, comment: str | None
    ) -> SceneWorkflow:
        """Ask for an independent second annotation: a new revision with the pipeline's own
        guesses as supports, the next annotation round, predicted again for someone else."""
        current = self.scenes.document(scene_id)
        if current.revision != revision:
            raise RevisionConflictError(current.revision)
        pipeline = self.scenes.latest_pipeline_document(scene_id)
        if pipeline is None:
            raise WorkflowError("the pipeline never ran on this scene: nothing to start from")
        reset = workflow_rules.pipeline_supports_only(current.scene, pipeline.scene)

        def reopen(session: Session, new_revision: int) -> None:
            row = _row(session, scene_id)
            status = status_of(row)
            workflow_rules.check_not_archived(status)
            transition = workflow_rules.second_annotation(status)
            row.annotation_round += 1
            _apply(session, row, transition, actor, new_revision, comment)

        self.scenes.commit_reset(
            scene_id,
            revision,
            reset,
            author=actor.name,
            summary=f"supports reset to the pipeline's (revision {pipeline.revision}) for a "
            "second annotation",
            hook=reopen,
        )
        return self.scene_workflow(scene_id)

    def _change(
        self,
        scene_id: str,
        revision: int,
        rule: Callable[[workflow_rules.SceneStatus], Transition],
        actor: Actor,
        comment: str | None = None,
    ) -> SceneWorkflow:
        with Session(self.engine) as session:
            row = _row(session, scene_id)
            if row.current_revision != revision:
                raise RevisionConflictError(row.current_revision)
            status = status_of(row)
            workflow_rules.check_not_archived(status)  # no step of the workflow until restored
            transition = rule(status)
            if not _apply_if_unchanged(session, row, transition, actor, revision, comment):
                session.rollback()
                raise WorkflowError("the scene changed meanwhile; reload it and try again")
            session.commit()
        return self.scene_workflow(scene_id)

    # -- the dashboard -------------------------------------------------------------------

    def dashboard(self, roles: dict[str, Role]) -> Dashboard:
        with Session(self.engine) as session:
            counts = {
                state: count
                for state, count in session.execute(
                    select(SceneRow.state, func.count())
                    .where(SCENE_IN_USE)
                    .group_by(SceneRow.state)
                )
            }
            states: dict[SceneState, int] = {s: int(counts.get(s, 0)) for s in STATES}
            events = session.scalars(select(SceneEventRow).order_by(SceneEventRow.id)).all()
            annotating = {
                name: count
                for name, count in session.execute(
                    select(SceneRow.assignee, func.count())
                    .where(
                        SceneRow.state == "in_annotation",
                        SceneRow.assignee.is_not(None),
                        SCENE_IN_USE,
                    )
                    .group_by(SceneRow.assignee)
                )
            }
            names = {s.id: s.name for s in session.scalars(select(SceneRow))}
        # Everyone with an account is listed, even with nothing done yet.
        people: dict[str, dict[str, int]] = {name: defaultdict(int) for name in roles}
        people = defaultdict(lambda: defaultdict(int), people)
        for name, count in annotating.items():
            if name is not None:
                people[name]["in_annotation"] = int(count)
        for event in events:
            if event.action == "submit":
                people[event.actor]["submitted"] += 1
            elif event.action == "withdraw":  # taken back: a submission that never was
                people[event.actor]["submitted"] -= 1
            elif event.action in ("accept", "reject") and event.assignee:
                people[event.assignee]["accepted" if event.action == "accept" else "rejected"] += 1
                people[event.actor]["reviewed"] += 1
        stats = [
            PersonStats(
                name=name,
                role=roles.get(name),
                in_annotation=c["in_annotation"],
                submitted=c["submitted"],
                accepted=c["accepted"],
                rejected=c["rejected"],
                reviewed=c["reviewed"],
            )
            for name, c in sorted(people.items())
        ]
        agreement = self._agreement(events, names)
        mean = sum(a.agreement for a in agreement) / len(agreement) if agreement else None
        return Dashboard(
            states=states,
            people=stats,
            agreement=agreement,
            mean_agreement=round(mean, 6) if mean is not None else None,
        )

    def _agreement(
        self, events: Sequence[SceneEventRow], names: dict[str, str]
    ) -> list[SceneAgreement]:
        """Per scene labelled twice: the last submission of round 1 against the last of
        round 2, when different people made them."""
        last: dict[str, dict[int, SceneEventRow]] = defaultdict(dict)
        for event in events:
            if event.action == "submit":
                last[event.scene_id][event.annotation_round] = event
        out = []
        for scene_id, rounds in last.items():
            first, second = rounds.get(1), rounds.get(2)
            if first is None or second is None or first.actor == second.actor:
                continue
            a = self.scenes.document(scene_id, first.revision).scene
            b = self.scenes.document(scene_id, second.revision).scene
            result = workflow_rules.support_agreement(a, b)
            if result.objects == 0:
                continue
            out.append(
                SceneAgreement(
                    scene_id=scene_id,
                    name=names.get(scene_id, scene_id),
                    annotators=[first.actor, second.actor],
                    revisions=[first.revision, second.revision],
                    objects=result.objects,
                    matching=result.matching,
                    agreement=round(result.share, 6),
                )
            )
        return sorted(out, key=lambda a: a.agreement)


def _open_rejection(events: list[WorkflowEvent]) -> str | None:
    """The reviewer's comment the annotator is still working on: from the last rejection,
    until the scene is submitted again (or the round ends)."""
    for event in reversed(events):
        if event.action == "reject":
            return event.comment
        if event.action in ("submit", "accept", "second_annotation"):
            return None
    return None


def _row(session: Session, scene_id: str) -> SceneRow:
    row = session.get(SceneRow, scene_id)
    if row is None:
        raise SceneNotFoundError(f"no scene {scene_id!r}")
    return row


def _earlier_annotators(db: Session | Connection, row: SceneHead) -> set[str]:
    """Who submitted the scene in an earlier annotation round."""
    if row.annotation_round <= 1:
        return set()  # rounds count from 1: asked on every save, so no query for the first
    return set(
        db.scalars(
            select(SceneEventRow.actor).where(
                SceneEventRow.scene_id == row.id,
                SceneEventRow.action == "submit",
                SceneEventRow.annotation_round < row.annotation_round,
            )
        )
    )


def _rejected_this_round(session: Session, row: SceneRow) -> bool:
    """Whether a reviewer rejected the scene in its current annotation round."""
    found = session.scalar(
        select(SceneEventRow.id)
        .where(
            SceneEventRow.scene_id == row.id,
            SceneEventRow.action == "reject",
            SceneEventRow.annotation_round == row.annotation_round,
        )
        .limit(1)
    )
    return found is not None


def _apply(
    session: Session,
    row: SceneRow,
    transition: Transition,
    actor: Actor,
    revision: int,
    comment: str | None = None,
) -> None:
    record_event(
        session,
        row,
        action=transition.action,
        to_state=transition.to_state,
        assignee=transition.assignee,
        actor=actor.name,
        revision=revision,
        from_state=as_state(row.state),
        comment=comment,
    )


def _apply_if_unchanged(
    session: Session,
    row: SceneRow,
    transition: Transition,
    actor: Actor,
    revision: int,
    comment: str | None = None,
) -> bool:
    """Apply the transition only if the scene's state, assignee and revision are still the
    ones the rule was checked against (a compare-and-set, so two people taking the same
    scene at once cannot both get it)."""
    same_assignee = (
        SceneRow.assignee.is_(None) if row.assignee is None else SceneRow.assignee == row.assignee
    )
    moved = session.execute(
        update(SceneRow)
        .where(
            SceneRow.id == row.id,
            SceneRow.state == row.state,
            SceneRow.current_revision == revision,
            same_assignee,
        )
        .values(state=transition.to_state, assignee=transition.assignee)
        .execution_options(synchronize_session=False)
    )
    if moved.rowcount != 1:  # type: ignore[attr-defined]
        return False
    _apply(session, row, transition, actor, revision, comment)
    return True


def _refuse_unless_taken_by(session: Session, scene_id: str, actor: Actor) -> None:
    """After a take lost its compare-and-set: fine if the actor holds the scene now (their
    own take from another tab won), else WorkflowError saying who does."""
    now = _row(session, scene_id)
    if now.state == "in_annotation" and now.assignee == actor.name:
        return
    if now.assignee and now.assignee != actor.name:
        raise WorkflowError(f"{now.assignee} took this scene first")
    raise WorkflowError("the scene changed meanwhile; reload it and try again")


def _as_action(value: str) -> WorkflowAction:
    if value not in _ACTIONS:
        raise ValueError(f"unknown workflow action {value!r} in the database")
    return cast(WorkflowAction, value)


def _event(row: SceneEventRow) -> WorkflowEvent:
    return WorkflowEvent(
        id=row.id,
        at=as_utc(row.at),
        actor=row.actor,
        action=_as_action(row.action),
        from_state=as_state(row.from_state) if row.from_state else None,
        to_state=as_state(row.to_state),
        assignee=row.assignee,
        revision=row.revision,
        annotation_round=row.annotation_round,
        comment=row.comment,
    )
