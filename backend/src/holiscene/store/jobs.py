"""Pipeline jobs: status and progress in the database, so any request (or a restart) sees them."""

from __future__ import annotations

import uuid

from holiscene_schema import Job
from sqlalchemy import Engine, func, select, update
from sqlalchemy.orm import Session

from .clock import as_utc, utcnow
from .tables import JobRow


class JobNotFoundError(LookupError):
    pass


class JobStore:
    def __init__(self, engine: Engine) -> None:
        self.engine = engine

    def create(self, scene_id: str, base_revision: int) -> Job:
        row = JobRow(
            id=uuid.uuid4().hex[:16],
            scene_id=scene_id,
            kind="pipeline",
            status="queued",
            progress=0.0,
            base_revision=base_revision,
            created_at=utcnow(),
        )
        with Session(self.engine) as session:
            session.add(row)
            session.commit()
            return _job(row)

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
            .group_by(JobRow.scene_id)
            .subquery()
        )
        query = select(JobRow).join(
            newest,
            (JobRow.scene_id == newest.c.scene_id) & (JobRow.created_at == newest.c.created_at),
        )
        with Session(self.engine) as session:
            return {row.scene_id: _job(row) for row in session.scalars(query)}

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

    def fail(self, job_id: str, error: str) -> None:
        self._set(job_id, status="failed", error=error, finished_at=utcnow())

    def fail_unfinished(self, reason: str) -> int:
        """Mark every queued or running job failed (after a restart nothing runs them)."""
        with Session(self.engine) as session:
            result = session.execute(
                update(JobRow)
                .where(JobRow.status.in_(["queued", "running"]))
                .values(status="failed", error=reason, finished_at=utcnow())
            )
            session.commit()
            return int(result.rowcount)  # type: ignore[attr-defined]

    def _set(self, job_id: str, **values: object) -> None:
        with Session(self.engine) as session:
            session.execute(update(JobRow).where(JobRow.id == job_id).values(**values))
            session.commit()


def _job(row: JobRow) -> Job:
    return Job(
        id=row.id,
        scene_id=row.scene_id,
        kind="pipeline",
        status=row.status,
        progress=row.progress,
        stage=row.stage,
        message=row.message,
        error=row.error,
        base_revision=row.base_revision,
        result_revision=row.result_revision,
        created_at=as_utc(row.created_at),
        finished_at=as_utc(row.finished_at) if row.finished_at else None,
    )
