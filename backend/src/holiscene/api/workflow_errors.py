"""Errors of accounts and of the annotation workflow -> HTTP answers with a readable `detail`."""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.responses import JSONResponse

from ..core.passwords import WeakPasswordError
from ..editing.workflow_rules import WorkflowError
from ..store.users import UserError, UserNotFoundError
from ..store.workflow import NoSceneWaitingError, WorkflowCommentError


def install_workflow_error_handlers(app: FastAPI) -> None:
    @app.exception_handler(WorkflowError)
    async def _workflow(_: Request, exc: WorkflowError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=409)

    @app.exception_handler(WorkflowCommentError)
    @app.exception_handler(WeakPasswordError)
    async def _unprocessable(_: Request, exc: ValueError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=422)

    @app.exception_handler(UserError)
    async def _user(_: Request, exc: UserError) -> JSONResponse:
        return JSONResponse({"detail": str(exc)}, status_code=exc.status)

    @app.exception_handler(UserNotFoundError)
    @app.exception_handler(NoSceneWaitingError)
    async def _missing(_: Request, exc: LookupError) -> JSONResponse:
        return JSONResponse({"detail": str(exc.args[0]) if exc.args else "not found"}, 404)
