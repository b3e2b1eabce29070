"""The Relation Network model registry: list, files, retrain, promote and roll back.

Any logged-in user may read the registry and fetch model files (the browser scores supports
with the active model); retraining and changing the active model are for admins.
"""

from __future__ import annotations

from fastapi import APIRouter
from fastapi.responses import FileResponse
from holiscene_schema import (
    ErrorMessage,
    Job,
    ModelEvent,
    ModelInfo,
    PromoteRequest,
    RetrainRequest,
)

from ...store.models import MODEL_FILES
from ..deps import AdminDep, WorkbenchDep

router = APIRouter(prefix="/api/models", tags=["models"])

_404: dict[int | str, dict[str, object]] = {404: {"model": ErrorMessage}}
# A model's files never change under its id, so browsers and proxies may keep them for good.
_IMMUTABLE = {"Cache-Control": "public, max-age=31536000, immutable"}


@router.get("", response_model=list[ModelInfo])
def list_models(workbench: WorkbenchDep) -> list[ModelInfo]:
    """Every registered model, newest first, with metrics, status and the active flag."""
    return workbench.models.list_models()


@router.get("/active", response_model=ModelInfo, responses=_404)
def active_model(workbench: WorkbenchDep) -> ModelInfo:
    """The model the pipeline and the browser use; 404 when none is registered."""
    return workbench.models.active()


@router.get("/events", response_model=list[ModelEvent])
def model_events(workbench: WorkbenchDep) -> list[ModelEvent]:
    """Who made which model active and when, newest first."""
    return workbench.models.events()


@router.get("/retrain", response_model=Job | None)
def latest_retrain_job(workbench: WorkbenchDep) -> Job | None:
    """The newest retrain job (so a page opened later can follow a running one), or null."""
    return workbench.jobs.latest_retrain()


@router.post(
    "/retrain",
    status_code=202,
    response_model=Job,
    responses={409: {"model": ErrorMessage}, 422: {"model": ErrorMessage}},
)
def start_retrain(
    workbench: WorkbenchDep, user: AdminDep, request: RetrainRequest | None = None
) -> Job:
    """Start retraining on the stored labelled scenes; follow it at GET /api/jobs/{id}.
    409 while another retrain job runs, 422 when fewer than two scenes are labelled."""
    request = request or RetrainRequest()
    if not user.local:  # with accounts, the account is the author
        request = request.model_copy(update={"author": user.name})
    return workbench.start_retrain(request)


@router.get("/{model_id}", response_model=ModelInfo, responses=_404)
def get_model(model_id: str, workbench: WorkbenchDep) -> ModelInfo:
    return workbench.models.get(model_id)


@router.post("/{model_id}/promote", response_model=ModelInfo, responses=_404)
def promote_model(
    model_id: str, workbench: WorkbenchDep, user: AdminDep, request: PromoteRequest | None = None
) -> ModelInfo:
    """Make any registered model the active one (promote a newer, or roll back to an older)."""
    request = request or PromoteRequest()
    author = request.author if user.local else user.name
    return workbench.models.promote(model_id, author, request.note)


@router.get(
    "/{model_id}/{file_name}",
    responses={
        200: {"content": {media: {} for media in set(MODEL_FILES.values())}},
        **_404,
    },
)
def model_file(model_id: str, file_name: str, workbench: WorkbenchDep) -> FileResponse:
    """A model's files: model.onnx, curve.png, metrics.json, priors.json, data.json."""
    path = workbench.models.file(model_id, file_name)
    return FileResponse(path, media_type=MODEL_FILES[file_name], headers=_IMMUTABLE)
