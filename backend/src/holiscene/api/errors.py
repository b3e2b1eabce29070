"""Domain errors -> HTTP answers with a readable `detail`."""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse

from ..editing.edits import InvalidEditError
from ..inputs import InputError
from ..pipeline import PipelineBuildError
from ..segmentation.refine import RefineInputError
from ..services.relation_retraining import NotEnoughLabelsError
from ..services.workbench import PlacementNotPossibleError
from ..store.jobs import (
    JobNotFoundError,
    JobQueueFullError,
    RetrainRunningError,
    SceneJobRunningError,
)
from ..store.model_registry import ModelNotFoundError
from ..store.scenes import RevisionConflictError, SceneNotFoundError


def install_error_handlers(app: FastAPI) -> None:
    @app.exception_handler(InputError)
    async def _input(_: Request, exc: InputError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=exc.status)

    @app.exception_handler(InvalidEditError)
    async def _edit(_: Request, exc: InvalidEditError) -> JSONResponse:
        return JSONResponse({"detail": f"invalid edit: {exc}"}, status_code=422)

    @app.exception_handler(SceneNotFoundError)
    @app.exception_handler(JobNotFoundError)
    @app.exception_handler(ModelNotFoundError)
    async def _missing(_: Request, exc: LookupError) -> JSONResponse:
        return JSONResponse(
            {"detail": str(exc.args[0]) if exc.args else "not found"}, status_code=404
        )

    @app.exception_handler(RevisionConflictError)
    async def _conflict(_: Request, exc: RevisionConflictError) -> JSONResponse:
        detail = {
            "message": "this scene changed since you loaded it (someone else saved first); "
            "reload to see their changes, then apply yours again",
            "current_revision": exc.current_revision,
        }
        return JSONResponse({"detail": detail}, status_code=409)

    @app.exception_handler(RetrainRunningError)
    @app.exception_handler(SceneJobRunningError)
    async def _job_running(_: Request, exc: Exception) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=409)

    @app.exception_handler(JobQueueFullError)
    async def _queue_full(_: Request, exc: JobQueueFullError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=503, headers={"Retry-After": "60"})

    @app.exception_handler(RefineInputError)
    async def _refine(_: Request, exc: RefineInputError) -> JSONResponse:
        return JSONResponse({"detail": f"cannot refine the mask: {exc}"}, status_code=422)

    @app.exception_handler(NotEnoughLabelsError)
    async def _few_labels(_: Request, exc: NotEnoughLabelsError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=422)

    @app.exception_handler(PlacementNotPossibleError)
    async def _no_placement(_: Request, exc: PlacementNotPossibleError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=422)

    @app.exception_handler(PipelineBuildError)
    async def _pipeline(_: Request, exc: PipelineBuildError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=422)

    @app.exception_handler(RequestValidationError)
    async def _validation(_: Request, exc: RequestValidationError) -> JSONResponse:
        parts = []
        for err in exc.errors():
            where = ".".join(str(p) for p in err.get("loc", ()) if p != "body")
            parts.append(f"{where}: {err.get('msg')}" if where else str(err.get("msg")))
        return JSONResponse({"detail": "; ".join(parts)}, status_code=422)
