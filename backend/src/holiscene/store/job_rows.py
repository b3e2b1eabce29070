"""Updates shared by the two job tables (pipeline jobs and dataset imports): both rows have an
id, a status, an error and a finish time, and a restart fails whatever was left running."""

from __future__ import annotations

from sqlalchemy import ColumnElement, Engine, update
from sqlalchemy.orm import Session

from .clock import utcnow
from .tables import ImportJobRow, JobRow

JobTable = type[JobRow] | type[ImportJobRow]


def set_job_columns(engine: Engine, table: JobTable, job_id: str, **values: object) -> None:
    with Session(engine) as session:
        session.execute(update(table).where(table.id == job_id).values(**values))
        session.commit()


def fail_job(engine: Engine, table: JobTable, job_id: str, error: str) -> None:
    set_job_columns(engine, table, job_id, status="failed", error=error, finished_at=utcnow())


def fail_unfinished_jobs(
    engine: Engine, table: JobTable, reason: str, *only: ColumnElement[bool]
) -> int:
    """Mark every queued or running job of `table` (that meets the conditions `only`) failed:
    after a restart nothing runs them; how many there were."""
    with Session(engine) as session:
        result = session.execute(
            update(table)
            .where(table.status.in_(["queued", "running"]), *only)
            .values(status="failed", error=reason, finished_at=utcnow())
        )
        session.commit()
        return int(result.rowcount)  # type: ignore[attr-defined]
