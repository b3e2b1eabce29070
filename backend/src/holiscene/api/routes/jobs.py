"""Background jobs: status and progress."""

from __future__ import annotations

from fastapi import APIRouter
from holiscene_schema import ErrorMessage, Job

from ..deps import WorkbenchDep

router = APIRouter(prefix="/api/jobs", tags=["jobs"])


@router.get("/{job_id}", response_model=Job, responses={404: {"model": ErrorMessage}})
def get_job(job_id: str, workbench: WorkbenchDep) -> Job:
    return workbench.jobs.get(job_id)
