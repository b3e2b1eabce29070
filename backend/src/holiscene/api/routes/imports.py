"""Datasets uploaded as a .zip: start an import, follow it."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, File, Form, UploadFile
from holiscene_schema import ErrorMessage, ImportJob

from ..deps import AnnotatorDep, WorkbenchDep

router = APIRouter(prefix="/api/imports", tags=["imports"])


@router.post(
    "",
    status_code=202,
    response_model=ImportJob,
    responses={
        413: {"model": ErrorMessage},
        415: {"model": ErrorMessage},
        422: {"model": ErrorMessage},
    },
)
def start_import(
    workbench: WorkbenchDep,
    user: AnnotatorDep,
    archive: Annotated[
        UploadFile,
        File(
            description="A .zip of a COCO or LabelMe dataset, SUN RGB-D image folders or "
            "input folders"
        ),
    ],
    run_pipeline: Annotated[bool, Form()] = True,
) -> ImportJob:
    """Unpack and recognise the zip now (413 too large, 415 not a zip, 422 unsafe paths,
    links, or nothing importable; NYU Depth v2's .mat is for `holiscene import`), then import
    its photos in the background: follow them with GET /api/imports/{id}."""
    return workbench.imports.start(
        archive.file, archive.filename or "upload.zip", run_pipeline, user.name
    )


@router.get("/{job_id}", response_model=ImportJob, responses={404: {"model": ErrorMessage}})
def get_import(job_id: str, workbench: WorkbenchDep) -> ImportJob:
    """How far the import got: photos done of the total, the scenes made, the photos
    skipped as imported before, and each photo's error."""
    return workbench.imports.jobs.get(job_id)
