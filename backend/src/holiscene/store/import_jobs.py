"""Import jobs: datasets uploaded as a .zip, imported in the background. Their own table, not
`jobs`: a pipeline job belongs to one scene and one revision, an import makes many scenes and
reports per photo."""

from __future__ import annotations

import uuid
from collections.abc import Sequence
from typing import Any, Literal

from holiscene_schema import ImportedPhoto, ImportJob, PhotoError, SceneSummary
from sqlalchemy import Engine
from sqlalchemy.orm import Session

from ..core.errors import NotFoundError
from .clock import as_utc, utcnow
from .job_rows import fail_job, fail_unfinished_jobs, set_job_columns
from .tables import ImportJobRow

Outcome = Literal["imported", "skipped"]


class ImportJobNotFoundError(NotFoundError):
    pass


class ImportJobStore:
    def __init__(self, engine: Engine) -> None:
        self.engine = engine

    def create(
        self, archive: str, format: str, total: int, run_pipeline: bool, started_by: str
    ) -> ImportJob:
        row = ImportJobRow(
            id=uuid.uuid4().hex[:16],
            status="queued",
            archive=archive[:200],
            format=format[:64],
            total=total,
            done=0,
            run_pipeline=run_pipeline,
            imported=[],
            skipped=[],
            errors=[],
            started_by=started_by,
            created_at=utcnow(),
        )
        with Session(self.engine) as session:
            session.add(row)
            session.commit()
            return _import_job(row)

    def get(self, job_id: str) -> ImportJob:
        with Session(self.engine) as session:
            row = session.get(ImportJobRow, job_id)
            if row is None:
                raise ImportJobNotFoundError(f"no import job {job_id!r}")
            return _import_job(row)

    def start(self, job_id: str) -> None:
        self._set(job_id, status="running")

    def photo_done(
        self,
        job_id: str,
        outcome: Outcome,
        name: str,
        scene: SceneSummary,
        notes: Sequence[str] = (),
    ) -> None:
        """One photo stored as a scene (with notes on what its labels lost), or skipped as
        imported before as that scene."""
        entry: dict[str, Any] = {"name": name, "scene_id": scene.id, "scene_name": scene.name}
        if notes:
            entry["notes"] = list(notes)
        self._append(job_id, outcome, entry)

    def photo_failed(self, job_id: str, name: str, message: str) -> None:
        self._append(job_id, "errors", {"name": name, "message": message})

    def _append(self, job_id: str, column: str, entry: dict[str, Any]) -> None:
        # A read-modify-write: each import job has one writer, its worker.
        with Session(self.engine) as session:
            row = session.get(ImportJobRow, job_id)
            if row is None:
                raise ImportJobNotFoundError(f"no import job {job_id!r}")
            setattr(row, column, [*getattr(row, column), entry])
            row.done += 1
            row.total = max(row.total, row.done)  # the count before reading was an estimate
            session.commit()

    def finish(self, job_id: str) -> None:
        with Session(self.engine) as session:
            row = session.get(ImportJobRow, job_id)
            if row is None:
                raise ImportJobNotFoundError(f"no import job {job_id!r}")
            row.status = "succeeded"
            row.total = row.done  # what was read in the end
            row.finished_at = utcnow()
            session.commit()

    def fail(self, job_id: str, error: str) -> None:
        fail_job(self.engine, ImportJobRow, job_id, error)

    def fail_unfinished(self, reason: str) -> int:
        """Mark every queued or running import failed (after a restart nothing runs them)."""
        return fail_unfinished_jobs(self.engine, ImportJobRow, reason)

    def _set(self, job_id: str, **values: object) -> None:
        set_job_columns(self.engine, ImportJobRow, job_id, **values)


def _import_job(row: ImportJobRow) -> ImportJob:
    return ImportJob(
        id=row.id,
        status=row.status,
        archive=row.archive,
        format=row.format,
        total=row.total,
        done=row.done,
        run_pipeline=row.run_pipeline,
        imported=[ImportedPhoto(**entry) for entry in row.imported],
        skipped=[ImportedPhoto(**entry) for entry in row.skipped],
        errors=[PhotoError(**entry) for entry in row.errors],
        error=row.error,
        started_by=row.started_by,
        created_at=as_utc(row.created_at),
        finished_at=as_utc(row.finished_at) if row.finished_at else None,
    )
