"""The FastAPI application: API routers, error handlers and the built frontend."""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from fastapi import FastAPI
from fastapi.responses import JSONResponse
from fastapi.staticfiles import StaticFiles

from ..core.settings import Settings
from ..workbench import Workbench
from .errors import install_error_handlers
from .routes import jobs, models, scenes, viewer


def create_app(settings: Settings | None = None) -> FastAPI:
    settings = settings or Settings()

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        workbench = Workbench(settings)
        workbench.recover_after_restart()
        app.state.workbench = workbench
        try:
            yield
        finally:
            workbench.close()

    app = FastAPI(title="HoliScene", version="0.1.0", lifespan=lifespan)
    install_error_handlers(app)
    app.include_router(scenes.router)
    app.include_router(jobs.router)
    app.include_router(models.router)
    app.include_router(viewer.router)

    @app.get("/api/health", tags=["health"])
    def health() -> dict[str, str]:
        return {"status": "ok"}

    if (settings.web_dir / "index.html").is_file():
        app.mount("/", StaticFiles(directory=settings.web_dir, html=True), name="web")
    else:

        @app.get("/", include_in_schema=False)
        def frontend_missing() -> JSONResponse:
            return JSONResponse(
                {"detail": f"the frontend is not built ({settings.web_dir}): run `make build`"},
                status_code=503,
            )

    return app
