"""The FastAPI application: API routers, error handlers and the built frontend."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterable
from contextlib import asynccontextmanager
from dataclasses import dataclass
from typing import Any

from fastapi import Depends, FastAPI
from fastapi.openapi.docs import get_swagger_ui_html
from fastapi.responses import HTMLResponse, JSONResponse

from ..core.settings import Settings
from ..services.workbench import Workbench
from .attempt_limits import AttemptLimiter
from .body_limit import MB, BodySizeLimit
from .deps import current_user, is_loopback
from .errors import install_error_handlers
from .request_origin import RequestOriginCheck
from .routes import (
    auth,
    detector,
    downloads,
    imports,
    jobs,
    mask_refine,
    models,
    scenes,
    users,
    viewer,
    workflow,
)
from .security_headers import SecurityHeaders
from .upload_login import UploadLogin
from .web_files import WebFiles

# Besides its files, a photo import carries cam_K.txt, detections.json and form fields.
IMPORT_OVERHEAD_MB = 10
# The Swagger page loads its scripts and styles from a CDN and starts with an inline script.
DOCS_CSP = (
    "default-src 'self'; script-src 'self' 'unsafe-inline' https://cdn.jsdelivr.net; "
    "style-src 'self' 'unsafe-inline' https://cdn.jsdelivr.net; "
    "img-src 'self' data: https://fastapi.tiangolo.com; frame-ancestors 'none'"
)

# The only API routes an anonymous request may use (the built frontend is public too: the
# login page is part of it).
PUBLIC_ROUTES = frozenset({"/api/health", "/api/auth/login", "/api/auth/logout"})


class NoAdminError(RuntimeError):
    """Beyond loopback the server needs accounts, and an admin to manage them."""


def create_app(settings: Settings | None = None) -> FastAPI:
    settings = settings or Settings()

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        workbench = Workbench(settings)
        if not is_loopback(settings.host) and workbench.users.count_admins() == 0:
            workbench.close()
            raise NoAdminError(
                f"refusing to serve on {settings.host}: there is no admin account, and "
                "beyond 127.0.0.1 there are no default credentials; create one with "
                "`holiscene users add NAME --role admin`"
            )
        workbench.recover_after_restart()
        app.state.workbench = workbench
        try:
            yield
        finally:
            workbench.close()

    # The API's description is served below, to logged-in users only.
    app = FastAPI(
        title="HoliScene",
        version="0.1.0",
        lifespan=lifespan,
        docs_url=None,
        redoc_url=None,
        openapi_url=None,
    )
    install_http_guards(app, settings)
    app.state.attempt_limiter = AttemptLimiter()
    install_error_handlers(app)
    # Every API router but auth's needs a logged-in user (the local admin in local mode);
    # routes for reviewers or admins declare their role on top.
    logged_in = [Depends(current_user)]
    app.include_router(auth.router)
    app.include_router(workflow.router, dependencies=logged_in)
    app.include_router(scenes.router, dependencies=logged_in)
    app.include_router(imports.router, dependencies=logged_in)
    app.include_router(mask_refine.router, dependencies=logged_in)
    app.include_router(downloads.router, dependencies=logged_in)
    app.include_router(jobs.router, dependencies=logged_in)
    app.include_router(models.router, dependencies=logged_in)
    app.include_router(detector.router, dependencies=logged_in)
    app.include_router(viewer.router, dependencies=logged_in)
    app.include_router(users.router, dependencies=logged_in)

    install_api_docs(app)

    @app.get("/api/health", tags=["health"])
    def health() -> dict[str, str]:
        return {"status": "ok"}

    if (settings.web_dir / "index.html").is_file():
        app.mount("/", WebFiles(directory=settings.web_dir, html=True), name="web")
    else:

        @app.get("/", include_in_schema=False)
        def frontend_missing() -> JSONResponse:
            return JSONResponse(
                {"detail": f"the frontend is not built ({settings.web_dir}): run `make build`"},
                status_code=503,
            )

    check_routes_guarded(app)
    return app


def install_http_guards(app: FastAPI, settings: Settings) -> None:
    """Checks before any route runs (the last added runs first): headers on every answer,
    then the Host and Origin checks, then the body size cap, then a login before an upload
    is read."""
    upload_limit = (settings.max_upload_mb + IMPORT_OVERHEAD_MB) * MB
    upload_routes = {
        ("POST", "/api/scenes"): upload_limit,
        ("POST", "/api/imports"): (settings.max_import_mb + 1) * MB,  # + the form's fields
    }
    app.add_middleware(UploadLogin, routes=upload_routes.keys())
    app.add_middleware(
        BodySizeLimit, default=int(settings.max_request_mb * MB), per_route=upload_routes
    )
    app.add_middleware(
        RequestOriginCheck,
        listen_host=settings.host,
        allowed_hosts=settings.allowed_hosts,
        allowed_origins=settings.allowed_origins,
    )
    app.add_middleware(SecurityHeaders)


def install_api_docs(app: FastAPI) -> None:
    """/docs and /openapi.json, behind the login like the API they describe (open in local
    mode, where everyone is the local admin)."""
    logged_in = [Depends(current_user)]

    @app.get("/openapi.json", include_in_schema=False, dependencies=logged_in)
    def openapi() -> JSONResponse:
        return JSONResponse(app.openapi())

    @app.get("/docs", include_in_schema=False, dependencies=logged_in)
    def docs() -> HTMLResponse:
        page = get_swagger_ui_html(openapi_url="/openapi.json", title="HoliScene API")
        page.headers["Content-Security-Policy"] = DOCS_CSP
        return page


@dataclass(frozen=True)
class ApiRoute:
    path: str
    methods: frozenset[str]
    dependant: Any  # fastapi.dependencies.models.Dependant, with the router's dependencies


def api_routes(app: FastAPI) -> list[ApiRoute]:
    """Every route of the app, as requests meet it (included routers' dependencies merged)."""
    try:
        # Newer FastAPI keeps included routers nested in app.routes and merges on the fly.
        from fastapi.routing import iter_route_contexts
    except ImportError:  # older FastAPI copies every route into app.routes
        contexts: Iterable[Any] = app.routes
    else:
        contexts = iter_route_contexts(app.routes)
    return [
        ApiRoute(route.path, frozenset(route.methods or ()), getattr(route, "dependant", None))
        for route in contexts
        if isinstance(getattr(route, "path", None), str)
    ]


def _needs_user(dependant: Any) -> bool:
    return any(
        d.call is current_user or _needs_user(d) for d in getattr(dependant, "dependencies", [])
    )


def check_routes_guarded(app: FastAPI) -> None:
    """Refuse to build an app with an API route anonymous requests could use by mistake."""
    routes = [r for r in api_routes(app) if r.path.startswith("/api")]  # the rest: frontend
    if not any(r.path == "/api/scenes" for r in routes):
        raise RuntimeError("cannot see the app's routes to check them (FastAPI changed?)")
    open_routes = [
        r.path for r in routes if r.path not in PUBLIC_ROUTES and not _needs_user(r.dependant)
    ]
    if open_routes:
        raise RuntimeError(f"API routes without a login check: {', '.join(open_routes)}")
