"""Background jobs (pipeline runs, retraining): status, progress and log in the database, so any
request (or a restart) sees them."""

from __future__ import annotations

import uuid
from collections.abc import Mapping
from typing import ClassVar

from holiscene_schema import Job, JobKind
from sqlalchemy import Engine, func, or_, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from ..core.errors import DomainError, NotFoundError
from .clock import as_utc, utcnow
from .job_rows import fail_job, fail_unfinished_jobs, set_job_columns
from .tables import JobRow


class JobNotFoundError(NotFoundError):
    pass


# The stage of a pipeline job a batch made (`holiscene batch`), queued until its photo is out
# on a worker, then running: the batch, not a server, finishes it.
BATCH_STAGE = "batch"
# Why such a job failed once no batch runs (the next batch, or a server start, fails it).
BATCH_ORPHANED = "the batch that ran this scene was killed before it was done; a new batch takes it"

# Jobs that train a model; only one of them runs at a time, whatever its kind.
RETRAIN_KINDS: tuple[JobKind, ...] = ("retrain", "detector_retrain")


class RetrainFinishedError(DomainError):
    """A cancel of a retrain job that has ended (or that another server process runs)."""

    status = 409


class RetrainRunningError(DomainError):
    """Only one retrain job at a time (of any model kind): training uses the whole machine."""

    status = 409

    def __init__(self, job_id: str, what: str = "a retrain job") -> None:
        super().__init__(f"{what} is already running (job {job_id}); wait for it to finish")
        self.job_id = job_id


_RETRAINED = {"retrain": "the Relation Network", "detector_retrain": "the object detector"}


def _retrain_text(row: JobRow) -> str:
    """What a queued or running retrain job retrains, who started it and how far it is."""
    what = f"a retrain of {_RETRAINED.get(row.kind, row.kind)}"
    if row.started_by:
        what += f" started by {row.started_by}"
    progress = f"{round(100 * row.progress)}%" if row.status == "running" else "queued"
    return f"{what} ({progress})"


# Jobs on one scene; at most one of them waits or runs per scene (migration 0007).
SCENE_JOB_KINDS: tuple[JobKind, ...] = ("pipeline", "placement")
_WAITING = ("queued", "running")


class SceneJobRunningError(DomainError):
    """A scene's pipeline or placement job is already queued or running (HTTP 409): a second
    one would rewrite the scene under the first."""

    status = 409

    def __init__(self, job_id: str) -> None:
        super().__init__(
            f"a pipeline or placement job is already queued or running on this scene "
            f"({job_id}); wait for it to finish"
        )
        self.job_id = job_id


class JobQueueFullError(DomainError):
    """Too many pipeline and placement jobs wait already (HTTP 503): one worker runs them."""

    status = 503
    headers: ClassVar[Mapping[str, str]] = {"Retry-After": "60"}

    def __init__(self, waiting: int) -> None:
        super().__init__(
            f"{waiting} pipeline jobs are queued or running, the most this server takes; "
            "try again when some have finished"
        )


# A job's log keeps its newest lines within this many characters (a long training run
# reports every epoch; the page only needs the recent ones and the start).
MAX_LOG_CHARS = 20_000


class JobStore:
    def __init__(self, engine: Engine) -> None:
        self.engine = engine

    def create(
        self,
        scene_id: str,
        base_revision: int,
        kind: JobKind = "pipeline",
        started_by: str | None = None,
        max_waiting: int | None = None,
        stage: str | None = None,
    ) -> Job:
        """A queued pipeline job (or placement job) on a scene's revision, in `stage` if given
        (a batch's job is the batch's from the start). SceneJobRunningError when the scene has
        one queued or running (the database refuses a second); JobQueueFullError when
        `max_waiting` of them wait on all scenes (the caller serialises this count and the
        insert with a lock)."""
        if kind not in SCENE_JOB_KINDS:
            raise ValueError(f"{kind!r} is not a scene job kind")
        with Session(self.engine) as session:
            if max_waiting is not None:
                _check_queue_room(session, max_waiting)
            row = self._new(
                JobRow(
                    scene_id=scene_id,
                    kind=kind,
                    base_revision=base_revision,
                    started_by=started_by,
                    stage=stage,
                )
            )
            session.add(row)
            try:
                session.commit()
            except IntegrityError as exc:
                session.rollback()
                running = self._waiting_on(session, scene_id)
                if running is None:  # not the one-job index: some other fault
                    raise
                raise SceneJobRunningError(running) from exc
            return _job(row)

    def check_queue_room(self, max_waiting: int) -> None:
        """JobQueueFullError when `max_waiting` pipeline or placement jobs wait or run."""
        with Session(self.engine) as session:
            _check_queue_room(session, max_waiting)

    @staticmethod
    def _waiting_on(session: Session, scene_id: str) -> str | None:
        return session.scalar(
            select(JobRow.id).where(
                JobRow.scene_id == scene_id,
                JobRow.kind.in_(SCENE_JOB_KINDS),
                JobRow.status.in_(_WAITING),
            )
        )

    def create_retrain(self, kind: JobKind = "retrain", started_by: str | None = None) -> Job:
        """A queued retrain job ("retrain": the Relation Network, "detector_retrain": the object
        detector), unless a retrain job of either kind is queued or running: then
        RetrainRunningError.

        The check and the insert are one transaction; the caller also serialises them with a
        lock, since SQLite's default isolation does not stop two transactions reading alike."""
        if kind not in RETRAIN_KINDS:
            raise ValueError(f"{kind!r} is not a retrain job kind")
        with Session(self.engine) as session:
            running = session.scalar(
                select(JobRow).where(
                    JobRow.kind.in_(RETRAIN_KINDS), JobRow.status.in_(["queued", "running"])
                )
            )
            if running is not None:
                # Named: an admin on the other model's tab would not know of it otherwise.
                raise RetrainRunningError(running.id, _retrain_text(running))
            row = self._new(
                JobRow(scene_id=None, kind=kind, base_revision=None, started_by=started_by)
            )
            session.add(row)
            session.commit()
            return _job(row)

    @staticmethod
    def _new(row: JobRow) -> JobRow:
        row.id = uuid.uuid4().hex[:16]
        row.status = "queued"
        row.progress = 0.0
        row.created_at = utcnow()
        return row

    def get(self, job_id: str) -> Job:
        with Session(self.engine) as session:
            row = session.get(JobRow, job_id)
            if row is None:
                raise JobNotFoundError(f"no job {job_id!r}")
            return _job(row)

    def latest_for_scenes(self) -> dict[str, Job]:
        """Each scene's newest job (the scene list shows it, and the app polls the list)."""
        newest = (
            select(JobRow.scene_id, func.max(JobRow.created_at).label("created_at"))
            .where(JobRow.scene_id.is_not(None))
            .group_by(JobRow.scene_id)
            .subquery()
        )
        query = select(JobRow).join(
            newest,
            (JobRow.scene_id == newest.c.scene_id) & (JobRow.created_at == newest.c.created_at),
        )
        with Session(self.engine) as session:
            return {row.scene_id: _job(row) for row in session.scalars(query) if row.scene_id}

    def latest_retrain(self, kind: JobKind = "retrain") -> Job | None:
        query = select(JobRow).where(JobRow.kind == kind).order_by(JobRow.created_at.desc())
        with Session(self.engine) as session:
            row = session.scalars(query.limit(1)).first()
            return _job(row) if row is not None else None

    def other_retrain(self, kind: str) -> str | None:
        """The queued or running retrain job of another kind than `kind`, described; one
        retrain runs at a time, so the models page says why this kind's must wait."""
        query = select(JobRow).where(
            JobRow.kind.in_(RETRAIN_KINDS),
            JobRow.kind != kind,
            JobRow.status.in_(["queued", "running"]),
        )
        with Session(self.engine) as session:
            row = session.scalars(query.limit(1)).first()
            return _retrain_text(row) if row is not None else None

    def unfinished(self, kind: str) -> list[Job]:
        query = select(JobRow).where(JobRow.kind == kind, JobRow.status.in_(["queued", "running"]))
        with Session(self.engine) as session:
            return [_job(row) for row in session.scalars(query)]

    def append_log(self, job_id: str, line: str, replace_last: bool = False) -> None:
        """Add a line to the job's log, or replace its last line (a counter moving on).
        A read-modify-write: each job has one writer, its worker."""
        with Session(self.engine) as session:
            row = session.get(JobRow, job_id)
            if row is None:
                raise JobNotFoundError(f"no job {job_id!r}")
            log = row.log or ""
            if replace_last:
                log = log[: log.rstrip("\n").rfind("\n") + 1]
            log += line.rstrip("\n") + "\n"
            if len(log) > MAX_LOG_CHARS:
                log = "…\n" + log[-MAX_LOG_CHARS:].split("\n", 1)[-1]
            row.log = log
            session.commit()

    def progress(self, job_id: str, stage: str, fraction: float) -> None:
        self._set(job_id, status="running", stage=stage, progress=round(fraction, 4))

    def succeed(self, job_id: str, result_revision: int, message: str) -> None:
        self._set(
            job_id,
            status="succeeded",
            progress=1.0,
            stage=None,
            result_revision=result_revision,
            message=message,
            finished_at=utcnow(),
        )

    def succeed_retrain(self, job_id: str, model_id: str, message: str) -> None:
        self._set(
            job_id,
            status="succeeded",
            progress=1.0,
            stage=None,
            result_model_id=model_id,
            message=message,
            finished_at=utcnow(),
        )

    def cancelled(self, job_id: str, message: str) -> None:
        """The job stopped because someone asked; not a failure, so not shown as one."""
        self._set(job_id, status="cancelled", stage=None, message=message, finished_at=utcnow())

    def fail(self, job_id: str, error: str) -> None:
        fail_job(self.engine, JobRow, job_id, error)

    def fail_unfinished(self, reason: str, batch_jobs: bool | None = None) -> int:
        """Mark queued or running jobs failed (after a restart nothing runs them): all of
        them, or only those out on a batch (`batch_jobs` True: their stage is BATCH_STAGE),
        or all but those (False)."""
        if batch_jobs is None:
            return fail_unfinished_jobs(self.engine, JobRow, reason)
        on_batch = JobRow.stage == BATCH_STAGE
        only = on_batch if batch_jobs else or_(JobRow.stage.is_(None), JobRow.stage != BATCH_STAGE)
        return fail_unfinished_jobs(self.engine, JobRow, reason, only)

    def _set(self, job_id: str, **values: object) -> None:
        set_job_columns(self.engine, JobRow, job_id, **values)


def _check_queue_room(session: Session, max_waiting: int) -> None:
    waiting = session.scalar(
        select(func.count())
        .select_from(JobRow)
        .where(JobRow.kind.in_(SCENE_JOB_KINDS), JobRow.status.in_(_WAITING))
    )
    if waiting is not None and waiting >= max_waiting:
        raise JobQueueFullError(waiting)


def _job(row: JobRow) -> Job:
    return Job(
        id=row.id,
        scene_id=row.scene_id,
        kind=row.kind,
        status=row.status,
        progress=row.progress,
        stage=row.stage,
        message=row.message,
        error=row.error,
        log=row.log or "",
        base_revision=row.base_revision,
        result_revision=row.result_revision,
        result_model_id=row.result_model_id,
        started_by=row.started_by,
        created_at=as_utc(row.created_at),
        finished_at=as_utc(row.finished_at) if row.finished_at else None,
    )
