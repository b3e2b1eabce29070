"""The built workbench (frontend/dist), served with caching that fits how it is built: files
under assets/ have a hash of their content in their names (Vite), so a browser may keep them
for good and never ask again; index.html (and any other file) names the current ones and is
checked every time. Without a Cache-Control a browser may keep index.html by its age alone,
and after an upgrade open a page whose scripts the server no longer has.

An address that names no file gets 404.html (a page pointing to the workbench) in a browser,
but an unknown /api/ address stays a JSON 404, as API clients read it."""

from __future__ import annotations

import os

from starlette.responses import JSONResponse, Response
from starlette.staticfiles import StaticFiles
from starlette.types import Scope

HASHED_ASSETS = "/assets/"
FOREVER = "public, max-age=31536000, immutable"
ALWAYS_CHECK = "no-cache"


class WebFiles(StaticFiles):
    async def get_response(self, path: str, scope: Scope) -> Response:
        if str(scope.get("path", "")).startswith("/api/"):
            return JSONResponse({"detail": "Not Found"}, status_code=404)
        return await super().get_response(path, scope)

    def file_response(
        self,
        full_path: str | os.PathLike[str],
        stat_result: os.stat_result,
        scope: Scope,
        status_code: int = 200,
    ) -> Response:
        response = super().file_response(full_path, stat_result, scope, status_code)
        hashed = str(scope.get("path", "")).startswith(HASHED_ASSETS) and status_code == 200
        response.headers["Cache-Control"] = FOREVER if hashed else ALWAYS_CHECK
        return response
