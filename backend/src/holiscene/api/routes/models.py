"""The model registry: list, files, retrain, promote and roll back, for each kind of model.

Two kinds are registered, each with its own versions, active model and history: the Relation
Network (`kind=relation`, the default, so the routes read as before) and the object detector
(`kind=detector`). Routes about a kind take it as a query parameter (`?kind=detector`); routes
about one model find its kind from its id.

Any logged-in user may read the registry and fetch model files (the browser scores supports
with the active model); retraining and changing the active model are for admins.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query
from fastapi.responses import FileResponse
from holiscene_schema import (
    ErrorMessage,
    Job,
    ModelEvent,
    ModelInfo,
    ModelKind,
    PromoteRequest,
    RetrainReadiness,
    RetrainRequest,
)

from ...services.workbench import RETRAIN_JOB_KINDS
from ...store.model_registry import DETECTOR_FILES, MODEL_FILES
from ..deps import AdminDep, WorkbenchDep

router = APIRouter(prefix="/api/models", tags=["models"])

_404: dict[int | str, dict[str, object]] = {404: {"model": ErrorMessage}}
# A model's files never change under its id, so browsers and proxies may keep them for good.
_IMMUTABLE = {"Cache-Control": "public, max-age=31536000, immutable"}
_MEDIA_TYPES = {*MODEL_FILES.values(), *DETECTOR_FILES.values()}

KindQuery = Annotated[
    ModelKind,
    Query(description="relation: the Relation Network; detector: the object detector"),
]


@router.get("", response_model=list[ModelInfo])
def list_models(workbench: WorkbenchDep, kind: KindQuery = "relation") -> list[ModelInfo]:
    """Every registered model of a kind, newest first, with metrics, status and the active
    flag."""
    return workbench.registry(kind).list_models()


@router.get("/active", response_model=ModelInfo, responses=_404)
def active_model(workbench: WorkbenchDep, kind: KindQuery = "relation") -> ModelInfo:
    """The model of a kind the pipeline (and, for the Relation Network, the browser) uses;
    404 when none is registered."""
    return workbench.registry(kind).active()


@router.get("/events", response_model=list[ModelEvent])
def model_events(workbench: WorkbenchDep, kind: KindQuery = "relation") -> list[ModelEvent]:
    """Who made which model of a kind active and when, newest first."""
    return workbench.registry(kind).events()


@router.get("/retrain", response_model=Job | None)
def latest_retrain_job(workbench: WorkbenchDep, kind: KindQuery = "relation") -> Job | None:
    """The newest retrain job of a kind (so a page opened later can follow a running one),
    or null."""
    return workbench.jobs.latest_retrain(RETRAIN_JOB_KINDS[kind])


@router.get("/retrain/readiness", response_model=RetrainReadiness)
def retrain_readiness(workbench: WorkbenchDep, kind: KindQuery = "relation") -> RetrainReadiness:
    """How many stored scenes a retraining of the kind would learn from, how many it needs,
    and what counts as one."""
    return workbench.retrain_readiness(kind)


@router.post(
    "/retrain",
    status_code=202,
    response_model=Job,
    responses={409: {"model": ErrorMessage}, 422: {"model": ErrorMessage}},
)
def start_retrain(
    workbench: WorkbenchDep,
    user: AdminDep,
    request: RetrainRequest | None = None,
    kind: KindQuery = "relation",
) -> Job:
    """Start retraining a kind of model on the stored scenes people labelled (the detector:
    their confirmed boxes); follow it at GET /api/jobs/{id}. 409 while another retrain job
    (of either kind) runs, 422 when fewer than two scenes are labelled."""
    request = request or RetrainRequest()
    if not user.local:  # with accounts, the account is the author
        request = request.model_copy(update={"author": user.name})
    return workbench.start_retrain(request, kind)


@router.post(
    "/retrain/{job_id}/cancel",
    response_model=Job,
    responses={404: {"model": ErrorMessage}, 409: {"model": ErrorMessage}},
)
def cancel_retrain(job_id: str, workbench: WorkbenchDep, user: AdminDep) -> Job:
    """Cancel a queued or running retrain job: it stops at its next step or epoch, ends with
    status cancelled ("cancelled by ...") and registers nothing. 409 once it has ended."""
    return workbench.cancel_retrain(job_id, user.name)


@router.get("/{model_id}", response_model=ModelInfo, responses=_404)
def get_model(model_id: str, workbench: WorkbenchDep) -> ModelInfo:
    return workbench.registry_of(model_id).get(model_id)


@router.post("/{model_id}/promote", response_model=ModelInfo, responses=_404)
def promote_model(
    model_id: str, workbench: WorkbenchDep, user: AdminDep, request: PromoteRequest | None = None
) -> ModelInfo:
    """Make any registered model the active one of its kind (promote a newer, or roll back to
    an older); the other kind's active model stays."""
    request = request or PromoteRequest()
    author = request.author if user.local else user.name
    return workbench.registry_of(model_id).promote(model_id, author, request.note)


@router.get(
    "/{model_id}/{file_name}",
    responses={200: {"content": {media: {} for media in _MEDIA_TYPES}}, **_404},
)
def model_file(model_id: str, file_name: str, workbench: WorkbenchDep) -> FileResponse:
    """A model's files: model.onnx, curve.png, metrics.json, and priors.json, data.json (a
    Relation Network) or metadata.json, LICENSE (a detector)."""
    registry = workbench.registry_of(model_id)
    path = registry.file(model_id, file_name)
    return FileResponse(path, media_type=registry.files[file_name], headers=_IMMUTABLE)
