"""Scenes and their revision history.

Every write names the revision it was based on. The write is one transaction whose
conditional UPDATE moves `current_revision` only if it still equals that base, so of two
writers on the same base exactly one wins and the other gets a RevisionConflictError.
"""

from __future__ import annotations

import enum
import hashlib
import json
import uuid
from collections.abc import Callable, Sequence
from datetime import datetime
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import (
    Edit,
    EditRequest,
    Job,
    RevisionInfo,
    RevisionKind,
    Scene,
    SceneDocument,
    SceneState,
    SceneSummary,
)
from pydantic import TypeAdapter
from sqlalchemy import (
    ColumnElement,
    Connection,
    Engine,
    Integer,
    ScalarSelect,
    Select,
    Text,
    Update,
    bindparam,
    cast,
    func,
    select,
    update,
)
from sqlalchemy.orm import Session

from ..core.db import without_transaction
from ..core.errors import DomainError, NotFoundError
from ..editing.edits import (
    apply_edits,
    describe_edits,
    keep_manual_supports,
    needs_photo,
    restore_revisions,
    restored_scene_revision,
)
from ..editing.workflow_rules import SceneStatus, scene_uncertainty
from ..inputs import InputFiles, load_photo
from ..inputs.depth import DEPTH_FILE
from ..inputs.validation import IMPORT_NOTES_FILE
from ..pipeline.people import keep_people_objects, people_objects_changed_since
from .clock import as_utc, utcnow
from .files import GROUND_TRUTH_FILE, SceneFiles
from .revision_writes import WorkflowMove, add_revision, revision_values, write_at_once
from .scene_events import SceneHead, as_state, pipeline_committed, record_event
from .tables import SCENE_IN_USE, SCENE_NAME_LENGTH, RevisionRow, SceneEventRow, SceneRow

_EDITS = TypeAdapter(list[Edit])
# Runs inside a revision's write transaction, after the scene row moved to the new revision
# number (given); raising rolls the whole write back. The workflow checks and records state.
RevisionHook = Callable[[Session, int], None]
# Sees a scene's row before a save reads its revision (same connection); raising refuses it.
RowCheck = Callable[[Connection, SceneHead], None]


def _revision_query(joined: ColumnElement[bool]) -> Select[*tuple[Any, ...]]:
    """A scene's workflow state with the revision `joined` picks (NULLs when none), built
    once: the statement of every save and every page load."""
    return (
        select(
            SceneRow.id,
            SceneRow.state,
            SceneRow.assignee,
            SceneRow.annotation_round,
            SceneRow.current_revision,
            SceneRow.archived_by,
            RevisionRow.number,
            RevisionRow.created_at,
            # As text: pydantic reads JSON text in half the time it takes to check the dict
            # the driver would make of it.
            cast(RevisionRow.scene, Text).label("scene"),
        )
        .outerjoin(RevisionRow, (RevisionRow.scene_id == SceneRow.id) & joined)
        .where(SceneRow.id == bindparam("scene_id"))
    )


_NUMBER = bindparam("number", type_=Integer)
_CURRENT = _revision_query(RevisionRow.number == SceneRow.current_revision)
_NUMBERED = _revision_query(RevisionRow.number == _NUMBER)
# The current revision only if it is `number` (the base of a save): a stale save's answer,
# a 409, then costs no transfer of the whole scene.
_CURRENT_IF = _revision_query(
    (RevisionRow.number == SceneRow.current_revision) & (SceneRow.current_revision == _NUMBER)
)


class _Keep(enum.Enum):
    """The scene's scene.glb stays as it is (a revision that does not make or restore one)."""

    KEEP = enum.auto()


_KEEP = _Keep.KEEP


class SceneNotFoundError(NotFoundError):
    pass


class RevisionConflictError(DomainError):
    """A save based on a revision that is no longer the newest (HTTP 409); the client reads
    the current revision from the answer."""

    status = 409

    def __init__(self, current_revision: int) -> None:
        super().__init__(f"the scene is at revision {current_revision}")
        self.current_revision = current_revision

    def detail(self) -> dict[str, object]:
        return {
            "message": "this scene changed since you loaded it (someone else saved first); "
            "reload to see their changes, then apply yours again",
            "current_revision": self.current_revision,
        }


class SceneRowChangedError(Exception):
    """A write conditional on the scene's row (its workflow state) found the row changed,
    though not its revision: nothing was written, and the caller checks its rules again."""


class SceneChangedError(RevisionConflictError):
    """A job's result, computed on `base_revision`, was not stored: the scene moved on to
    `current_revision` with work the result would have overwritten."""

    def __init__(self, base_revision: int, current_revision: int) -> None:
        super().__init__(current_revision)
        self.base_revision = base_revision


def _last_event_at() -> ScalarSelect[datetime]:
    """The time of a scene's latest workflow event, as a column of a query on SceneRow."""
    return (
        select(func.max(SceneEventRow.at))
        .where(SceneEventRow.scene_id == SceneRow.id)
        .scalar_subquery()
    )


def photo_digest(photo: bytes) -> str:
    """A photo file's fingerprint (SHA-256, hex): scenes.photo_digest, migration 0011."""
    return hashlib.sha256(photo).hexdigest()


def _chunks(values: list[str], size: int = 500) -> list[list[str]]:
    """`values` in pieces small enough for one IN (...) of every database."""
    return [values[i : i + size] for i in range(0, len(values), size)]


class SceneStore:
    def __init__(self, engine: Engine, files: SceneFiles) -> None:
        self.engine = engine
        self.reads = without_transaction(engine)
        self.files = files
        self._photo_digests_complete = False

    # -- reading -------------------------------------------------------------------------

    def list_summaries(
        self, state: SceneState | None = None, archived: bool | None = False
    ) -> list[SceneSummary]:
        """The scenes, newest first: in use (`archived` False, the default: what lists,
        retraining and batch runs work on), archived only (True) or all (None)."""
        query = select(SceneRow, _last_event_at()).order_by(SceneRow.created_at.desc())
        if state is not None:
            query = query.where(SceneRow.state == state)
        if archived is not None:
            query = query.where(~SCENE_IN_USE if archived else SCENE_IN_USE)
        with Session(self.engine) as session:
            return [self._summary(row, None, last) for row, last in session.execute(query).all()]

    def summary(self, scene_id: str, latest_job: Job | None = None) -> SceneSummary:
        query = select(SceneRow, _last_event_at()).where(SceneRow.id == scene_id)
        with Session(self.engine) as session:
            found = session.execute(query).first()
            if found is None:
                raise SceneNotFoundError(f"no scene {scene_id!r}")
            return self._summary(found[0], latest_job, found[1])

    def document(self, scene_id: str, revision: int | None = None) -> SceneDocument:
        """A revision (the current one when None)."""
        if revision is None:
            return self._read_document(scene_id, _CURRENT, {})
        return self._read_document(scene_id, _NUMBERED, {"number": revision}, number=revision)

    def _read_document(
        self,
        scene_id: str,
        query: Select[*tuple[Any, ...]],
        params: dict[str, int],
        check: RowCheck | None = None,
        number: int | None = None,
    ) -> SceneDocument:
        """The revision `query` picks, read with the scene's workflow state in one statement,
        on a plain connection (an ORM session costs three times the CPU). `check` sees the
        scene's row first, on the same connection, and may raise: every save asks its
        workflow rules this way, so the rules and the revision cost one round trip."""
        with self.reads.connect() as connection:
            found = connection.execute(query, {"scene_id": scene_id, **params}).first()
            if found is None:
                raise SceneNotFoundError(f"no scene {scene_id!r}")
            if check is not None:
                check(connection, found)
        if found.number is None:
            missing = found.current_revision if number is None else number
            raise SceneNotFoundError(f"scene {scene_id} has no revision {missing}")
        return SceneDocument(
            scene_id=scene_id,
            revision=found.number,
            updated_at=as_utc(found.created_at),
            scene=Scene.model_validate_json(found.scene),
        )

    def revisions(self, scene_id: str) -> list[RevisionInfo]:
        with Session(self.engine) as session:
            self._row(session, scene_id)
            rows = session.scalars(
                select(RevisionRow)
                .where(RevisionRow.scene_id == scene_id)
                .order_by(RevisionRow.number)
            ).all()
            return [
                RevisionInfo(
                    number=r.number,
                    created_at=as_utc(r.created_at),
                    author=r.author,
                    kind=r.kind,
                    summary=r.summary,
                    edits=_EDITS.validate_python(r.edits) if r.edits is not None else None,
                )
                for r in rows
            ]

    def unused_name(self, name: str) -> str:
        """`name`, or "name 2", "name 3"... when scenes already have it: photos uploaded from
        different folders are often all called img.jpg."""
        stem = name[: SCENE_NAME_LENGTH - 8]  # room for " 1234567"
        with Session(self.engine) as session:
            taken = set(
                session.scalars(
                    select(SceneRow.name).where(
                        (SceneRow.name == name)
                        | SceneRow.name.startswith(f"{stem} ", autoescape=True)
                    )
                ).all()
            )
        number, candidate = 1, name
        while candidate in taken:
            number += 1
            suffix = f" {number}"
            candidate = name[: SCENE_NAME_LENGTH - len(suffix)] + suffix
        return candidate

    def imported_from(self, inputs: InputFiles) -> SceneSummary | None:
        """The scene these very files were imported as before (the oldest), or None."""
        with Session(self.engine) as session:
            row = session.scalars(
                select(SceneRow)
                .where(SceneRow.source_digest == inputs.digest)
                .order_by(SceneRow.created_at)
                .limit(1)
            ).first()
            return self._summary(row) if row is not None else None

    def first_with_photo(self, photo: bytes) -> SceneSummary | None:
        """The first scene stored with this very photo file, whatever its labels, or None."""
        self._record_missing_photo_digests()
        with Session(self.engine) as session:
            row = session.scalars(
                select(SceneRow)
                .where(SceneRow.photo_digest == photo_digest(photo))
                .order_by(SceneRow.created_at, SceneRow.id)
                .limit(1)
            ).first()
            return self._summary(row) if row is not None else None

    def set_archived(self, scene_id: str, archive: bool, actor: str) -> SceneSummary:
        """Archive the scene (an admin), or restore it; every revision stays, and the scene's
        workflow history says who did it and when (its state and annotator do not change)."""
        with Session(self.engine) as session:
            row = self._row(session, scene_id)
            if (row.archived_at is not None) != archive:
                row.archived_at = utcnow() if archive else None
                row.archived_by = actor if archive else None
                state = as_state(row.state)
                record_event(
                    session,
                    row,
                    action="archive" if archive else "unarchive",
                    to_state=state,
                    assignee=row.assignee,
                    actor=actor,
                    revision=row.current_revision,
                    from_state=state,
                )
            session.commit()
        return self.summary(scene_id)

    def image_path(self, scene_id: str) -> Path:
        with Session(self.engine) as session:
            row = self._row(session, scene_id)
            return self.files.folder(scene_id) / row.image_file

    def split_keys(self, scene_ids: Sequence[str]) -> dict[str, str]:
        """For each scene, the id of the first scene stored with the same photo (itself when
        none came before): the held-out split decides by it, so a scene imported again after
        an edit lands on the side of the scene it came from. Scenes without a recorded photo
        digest (stored before migration 0011) get one from their file first."""
        self._record_missing_photo_digests()
        digests: dict[str, str | None] = {}
        first: dict[str, tuple[datetime, str]] = {}
        with Session(self.engine) as session:
            for chunk in _chunks(list(dict.fromkeys(scene_ids))):
                rows = session.execute(
                    select(SceneRow.id, SceneRow.photo_digest).where(SceneRow.id.in_(chunk))
                )
                digests.update({scene_id: digest for scene_id, digest in rows})
            for chunk in _chunks(sorted({d for d in digests.values() if d is not None})):
                same_photo = session.execute(
                    select(SceneRow.id, SceneRow.photo_digest, SceneRow.created_at).where(
                        SceneRow.photo_digest.in_(chunk)
                    )
                )
                for scene_id, digest, created in same_photo:
                    candidate = (as_utc(created), scene_id)
                    if digest is not None and (digest not in first or candidate < first[digest]):
                        first[digest] = candidate
        return {
            scene_id: first[digest][1] if digest is not None else scene_id
            for scene_id, digest in digests.items()
        }

    def _record_missing_photo_digests(self) -> None:
        # Every scene stored since migration 0011 has its digest: once the older ones are
        # filled, this store never looks again (not a query per split or import).
        if self._photo_digests_complete:
            return
        with Session(self.engine) as session:
            missing = session.execute(
                select(SceneRow.id, SceneRow.image_file).where(SceneRow.photo_digest.is_(None))
            ).all()
        for scene_id, image_file in missing:
            path = self.files.folder(scene_id) / image_file
            if not path.is_file():  # a scene whose files are gone keeps its own id as key
                continue
            digest = photo_digest(path.read_bytes())
            with Session(self.engine) as session, session.begin():
                session.execute(
                    update(SceneRow).where(SceneRow.id == scene_id).values(photo_digest=digest)
                )
        self._photo_digests_complete = True

    def glb_file(self, scene_id: str) -> tuple[int, Path] | None:
        """The scene's GLB and the revision whose pipeline (or placement) run made it (edits
        after it are not in the file); None: none yet."""
        with Session(self.engine) as session:
            revision = self._row(session, scene_id).glb_revision
        return None if revision is None else (revision, self.files.glb_path(scene_id, revision))

    def glb_path(self, scene_id: str) -> Path | None:
        made = self.glb_file(scene_id)
        return None if made is None else made[1]

    # -- writing -------------------------------------------------------------------------

    def create(self, inputs: InputFiles, scene: Scene, author: str) -> SceneSummary:
        """Store a new scene: its input files and revision 1 (the import)."""
        scene_id = uuid.uuid4().hex[:12]
        now = utcnow()
        with self.files.new_folder(scene_id) as folder, Session(self.engine) as session:
            (folder / scene.image.file).write_bytes(inputs.photo.data)
            if inputs.K is not None:
                rows = "\n".join(" ".join(f"{v:.6f}" for v in row) for row in inputs.K)
                (folder / "cam_K.txt").write_text(rows + "\n")
            if inputs.detections is not None:
                # The class as mapped on import (a user's class map may have chosen it; a name
                # no vocabulary knew stays as it came, to be flagged again) and the name it
                # came with: a pipeline re-run reads the same classes back.
                # A mask given with a box (a labelled dataset's outline) is kept as the
                # contract's Mask JSON, so a re-run starts from it again.
                boxes = [
                    {
                        "bbox": list(d.bbox),
                        "class": d.cls if d.class_known else (d.source_class or d.cls),
                        "source_class": d.source_class or d.cls,
                        **({"mask": d.mask.model_dump(mode="json")} if d.mask else {}),
                    }
                    for d in inputs.detections
                ]
                (folder / "detections.json").write_text(json.dumps(boxes, indent=1))
            if inputs.depth is not None:
                (folder / DEPTH_FILE).write_bytes(inputs.depth.png)
            if inputs.ground_truth is not None:
                truth = inputs.ground_truth.model_dump_json(indent=1)
                (folder / GROUND_TRUTH_FILE).write_text(truth + "\n")
            if inputs.notes:  # what the import left out of the labels: every run shows it
                (folder / IMPORT_NOTES_FILE).write_text(json.dumps(list(inputs.notes), indent=1))
            row = SceneRow(
                id=scene_id,
                name=scene.name,
                created_at=now,
                updated_at=now,
                current_revision=1,
                image_file=scene.image.file,
                width=scene.image.width,
                height=scene.image.height,
                object_count=len(scene.objects),
                glb_revision=None,
                state="new",
                assignee=None,
                annotation_round=1,
                uncertainty=scene_uncertainty(scene),
                source_digest=inputs.digest,
                photo_digest=photo_digest(inputs.photo.data),
            )
            session.add(row)
            session.flush()
            first = revision_values(
                scene_id, 1, author, "import", "imported", None, scene, utcnow()
            )
            add_revision(session, first)
            record_event(
                session,
                row,
                action="import",
                to_state="new",
                assignee=None,
                actor=author,
                revision=1,
                from_state=None,
            )
            session.commit()
        return self.summary(scene_id)

    def apply_edits(
        self,
        scene_id: str,
        request: EditRequest,
        hook: RevisionHook | None = None,
        check: RowCheck | None = None,
    ) -> SceneDocument:
        """A new revision with the edits; raises RevisionConflictError on a stale base,
        InvalidEditError (from editing) on a bad edit, and whatever `check` (given the scene's
        row before anything else) or `hook` raise. Nothing is written on error."""
        base = self.document_for_write(scene_id, request.base_revision, check)
        edited = self.edited(scene_id, base.scene, request)
        return self.commit_edits(scene_id, request, edited, hook, before=base.scene)

    def edited(self, scene_id: str, base: Scene, request: EditRequest) -> Scene:
        """`base` with the request's edits (InvalidEditError on a bad edit); nothing written."""
        earlier = self._earlier_scenes(scene_id, restore_revisions(request.edits))
        photo = self._photo(scene_id) if needs_photo(request.edits) else None
        return apply_edits(base, request.edits, request.author, utcnow(), earlier, photo)

    def commit_edits(
        self,
        scene_id: str,
        request: EditRequest,
        edited: Scene,
        hook: RevisionHook | None = None,
        unchanged: SceneStatus | None = None,
        move: WorkflowMove | None = None,
        before: Scene | None = None,
    ) -> SceneDocument:
        """Store `edited` (the request's edits on its base revision, `before`: its summary
        tells a guess confirmed from a change) as the next revision.
        `unchanged`: the workflow status the scene must still have, for a write without a hook
        (else SceneRowChangedError, nothing written); `move`: the workflow move the rules
        allow from it, written with the revision. A restore of a whole earlier revision also
        brings back the scene.glb that revision had; its write cannot keep `unchanged` (the
        caller gives a hook instead)."""
        restored = restored_scene_revision(request.edits)
        glb: int | _Keep | None = (
            _KEEP if restored is None else self._glb_revision_at(scene_id, restored)
        )
        return self._commit_revision(
            scene_id,
            request.base_revision,
            edited,
            author=request.author,
            kind="edit",
            summary=describe_edits(request.edits, before),
            edits=request.edits,
            glb_revision=glb,
            hook=hook,
            unchanged=unchanged,
            move=move,
        )

    def commit_reset(
        self,
        scene_id: str,
        base_revision: int,
        scene: Scene,
        author: str,
        summary: str,
        hook: RevisionHook,
    ) -> SceneDocument:
        """A revision that puts the scene back to an earlier state of its supports (for a
        second annotation)."""
        return self._commit_revision(
            scene_id,
            base_revision,
            scene,
            author=author,
            kind="reset",
            summary=summary,
            edits=None,
            hook=hook,
        )

    def latest_pipeline_revision(self, scene_id: str) -> int | None:
        """The number of the newest revision the pipeline wrote, or None."""
        with Session(self.engine) as session:
            return session.scalar(
                select(RevisionRow.number)
                .where(RevisionRow.scene_id == scene_id, RevisionRow.kind == "pipeline")
                .order_by(RevisionRow.number.desc())
                .limit(1)
            )

    def latest_pipeline_document(self, scene_id: str) -> SceneDocument | None:
        """The newest revision the pipeline wrote, or None."""
        number = self.latest_pipeline_revision(scene_id)
        return self.document(scene_id, number) if number is not None else None

    def with_pipeline_result(self) -> set[str]:
        """The ids of the scenes the pipeline has stored a result on (a revision of its own,
        whatever people changed after it)."""
        with Session(self.engine) as session:
            return set(
                session.scalars(
                    select(RevisionRow.scene_id).where(RevisionRow.kind == "pipeline").distinct()
                )
            )

    def commit_pipeline_result(
        self,
        scene_id: str,
        result: Scene,
        glb: bytes | None,
        base_revision: int | None = None,
        attempts: int = 5,
        author: str = "pipeline",
    ) -> int:
        """Store a whole pipeline run as a new revision on top of whatever is current, keeping
        every manual support and every object people set meanwhile. Returns the new revision number.
        `author`: who started the run ("pipeline" for one nobody started, an import's).

        `base_revision`: the revision the run started from. A room layout set by hand after it
        cannot be merged (the run estimated its own): SceneChangedError, nothing written."""
        for _ in range(attempts):
            current = self.document(scene_id)
            if base_revision is not None and self._layout_set_since(scene_id, base_revision):
                raise SceneChangedError(base_revision, current.revision)
            # People's objects and supports set while the run worked are kept too.
            changed = people_objects_changed_since(result.objects, current.scene.objects)
            removed = current.scene.removed_by_person
            objects = keep_people_objects(result.objects, changed, removed)
            update = {"objects": objects, "removed_by_person": removed}
            merged = keep_manual_supports(result.model_copy(update=update), current.scene)
            try:
                return self._commit_result(scene_id, current.revision, merged, glb, author)
            except RevisionConflictError:
                continue  # an edit landed meanwhile: merge again on top of it
        raise RevisionConflictError(self.document(scene_id).revision)

    def commit_placement_result(
        self,
        scene_id: str,
        base_revision: int,
        result: Scene,
        glb: bytes | None,
        author: str = "pipeline",
        summary: str | None = None,
    ) -> int:
        """Store a placement run made on `base_revision`, only if the scene is still at that
        revision: the run carries that revision's layout, camera and supports, and storing it
        on top of a newer revision would silently undo what was saved since. Otherwise
        SceneChangedError, and nothing is written."""
        try:
            return self._commit_result(scene_id, base_revision, result, glb, author, summary)
        except RevisionConflictError as conflict:
            raise SceneChangedError(base_revision, conflict.current_revision) from conflict

    # -- helpers -------------------------------------------------------------------------

    def _commit_result(
        self,
        scene_id: str,
        base_revision: int,
        scene: Scene,
        glb: bytes | None,
        author: str = "pipeline",
        summary: str | None = None,
    ) -> int:
        """A pipeline or placement run as revision base_revision + 1, if the scene is still at
        `base_revision` (RevisionConflictError otherwise). The GLB is written once the revision
        number is ours, inside the transaction, and removed again if the transaction fails."""
        new_revision = base_revision + 1
        glb_path = self.files.glb_path(scene_id, new_revision)
        written = False

        def committed(session: Session, number: int) -> None:
            nonlocal written
            pipeline_committed(session, scene_id, number)  # refuses a submitted scene
            if glb is not None:
                self.files.write_atomic(glb_path, glb)
                written = True

        try:
            self._commit_revision(
                scene_id,
                base_revision,
                scene,
                author=author,
                kind="pipeline",
                summary=summary or f"pipeline: {', '.join(s.name for s in scene.stages)}",
                edits=None,
                glb_revision=new_revision if glb is not None else _KEEP,
                hook=committed,
            )
        except BaseException:
            if written:
                glb_path.unlink(missing_ok=True)
            raise
        return new_revision

    def _layout_set_since(self, scene_id: str, revision: int) -> bool:
        """Whether an edit after `revision` set the room layout by hand."""
        with Session(self.engine) as session:
            edits = session.scalars(
                select(RevisionRow.edits).where(
                    RevisionRow.scene_id == scene_id,
                    RevisionRow.number > revision,
                    RevisionRow.kind == "edit",
                )
            )
            return any(e.get("kind") == "set_layout" for batch in edits for e in batch or [])

    def _glb_revision_at(self, scene_id: str, number: int) -> int | None:
        """The revision whose scene.glb the scene had at revision `number` (None: none yet): a
        pipeline or placement run's that wrote one, else what the revision it restored (a
        revert) or the one before it had. Edits keep the GLB."""
        with Session(self.reads) as session:
            rows = session.execute(
                select(RevisionRow.number, RevisionRow.kind, RevisionRow.edits).where(
                    RevisionRow.scene_id == scene_id, RevisionRow.number <= number
                )
            ).all()
        by_number = {row.number: row for row in rows}
        while number in by_number:
            row = by_number[number]
            if row.kind == "pipeline" and self.files.glb_path(scene_id, number).is_file():
                return number
            # The stored edits as written (JSON): only a restore_scene's revision is wanted.
            restores = [
                e["from_revision"] for e in row.edits or [] if e.get("kind") == "restore_scene"
            ]
            restored = restores[-1] if restores else None
            number = restored if restored is not None and restored < number else number - 1
        return None

    def _earlier_scenes(self, scene_id: str, numbers: set[int]) -> dict[int, Scene]:
        """The scenes of these revisions; a number without a revision is left out."""
        found: dict[int, Scene] = {}
        for number in numbers:
            try:
                found[number] = self.document(scene_id, number).scene
            except SceneNotFoundError:
                continue
        return found

    def _photo(self, scene_id: str) -> np.ndarray:
        """The scene's photo, RGB."""
        return load_photo(self.image_path(scene_id).read_bytes()).rgb

    def document_for_write(
        self, scene_id: str, base_revision: int, check: RowCheck | None = None
    ) -> SceneDocument:
        """The current revision if it is `base_revision`, else RevisionConflictError (the
        loser of a race is told without the scene being read). `check` sees the scene's row
        first."""

        def check_then_base(connection: Connection, row: SceneHead) -> None:
            if check is not None:
                check(connection, row)
            if row.current_revision != base_revision:
                raise RevisionConflictError(row.current_revision)

        params = {"number": base_revision}
        return self._read_document(scene_id, _CURRENT_IF, params, check_then_base)

    def _commit_revision(
        self,
        scene_id: str,
        base_revision: int,
        scene: Scene,
        *,
        author: str,
        kind: RevisionKind,
        summary: str,
        edits: Sequence[Edit] | None,
        glb_revision: int | _Keep | None = _KEEP,
        hook: RevisionHook | None = None,
        unchanged: SceneStatus | None = None,
        move: WorkflowMove | None = None,
    ) -> SceneDocument:
        """Store `scene` as revision base_revision + 1 if the scene is still at `base_revision`
        (RevisionConflictError otherwise) and, without a hook, in the workflow status
        `unchanged` (SceneRowChangedError otherwise), with the workflow `move` from it when
        given, and return it as stored, without reading it back: a save's answer costs no
        second read of the whole scene (docs/benchmarks.md, concurrent writers)."""
        new_revision = base_revision + 1
        now = utcnow()
        revision = revision_values(scene_id, new_revision, author, kind, summary, edits, scene, now)
        objects, uncertainty = len(scene.objects), scene_uncertainty(scene)
        if hook is None and isinstance(glb_revision, _Keep):
            stored = write_at_once(
                self.reads, base_revision, revision, objects, uncertainty, unchanged, move
            )
        else:
            if unchanged is not None or move is not None:  # only the one statement checks them
                raise ValueError("a workflow status to keep needs a write without a hook or GLB")
            moved = (
                update(SceneRow)
                .where(SceneRow.id == scene_id, SceneRow.current_revision == base_revision)
                .values(
                    current_revision=new_revision,
                    updated_at=now,
                    object_count=objects,
                    uncertainty=uncertainty,
                    **({} if isinstance(glb_revision, _Keep) else {"glb_revision": glb_revision}),
                )
            )
            stored = self._write_with_hook(moved, revision, hook)
        if not stored:
            current = self.current_revision(scene_id)
            if current != base_revision or unchanged is None:
                raise RevisionConflictError(current)
            raise SceneRowChangedError(f"scene {scene_id} changed meanwhile")
        return SceneDocument(scene_id=scene_id, revision=new_revision, updated_at=now, scene=scene)

    def current_revision(self, scene_id: str) -> int:
        with Session(self.reads) as session:
            return self._row(session, scene_id).current_revision

    def _write_with_hook(
        self, moved: Update, revision: dict[str, Any], hook: RevisionHook | None
    ) -> bool:
        """Move the scene's row, run `hook` and add the revision in one transaction; False
        when the row did not match (nothing written)."""
        with Session(self.engine) as session:
            # RETURNING puts the moved row in the session, so a hook's session.get(SceneRow)
            # costs no SELECT.
            if session.scalar(moved.returning(SceneRow)) is None:
                session.rollback()
                return False
            if hook is not None:
                hook(session, revision["number"])
            add_revision(session, revision)
            session.commit()
        return True

    @staticmethod
    def _row(session: Session, scene_id: str) -> SceneRow:
        row = session.get(SceneRow, scene_id)
        if row is None:
            raise SceneNotFoundError(f"no scene {scene_id!r}")
        return row

    @staticmethod
    def _summary(
        row: SceneRow, latest_job: Job | None = None, last_event_at: datetime | None = None
    ) -> SceneSummary:
        updated = as_utc(row.updated_at)
        return SceneSummary(
            id=row.id,
            name=row.name,
            revision=row.current_revision,
            created_at=as_utc(row.created_at),
            updated_at=updated,
            last_activity_at=max(updated, as_utc(last_event_at)) if last_event_at else updated,
            width=row.width,
            height=row.height,
            object_count=row.object_count,
            state=as_state(row.state),
            assignee=row.assignee,
            annotation_round=row.annotation_round,
            uncertainty=row.uncertainty,
            archived_at=as_utc(row.archived_at) if row.archived_at is not None else None,
            archived_by=row.archived_by,
            latest_job=latest_job,
        )
