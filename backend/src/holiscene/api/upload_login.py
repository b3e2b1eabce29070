"""The login asked for before an upload is read.

FastAPI reads and spools a multipart body before a route's dependencies run, so without this
an anonymous client could make the server take in an upload of the largest accepted size
before its 401. For the upload routes the session is checked from the headers alone (a
cookie or a bearer token, or local single-user mode), and a request without one is refused
before its first byte is read. The route's own dependencies still decide the role.
"""

from __future__ import annotations

from collections.abc import Collection

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.types import ASGIApp, Receive, Scope, Send

from ..store.users import SessionEndedError
from .asgi_answer import send_json_error
from .deps import local_mode, login_needed, session_token


class UploadLogin:
    """Refuse anonymous requests to `routes` ((method, path) pairs) before reading them."""

    def __init__(self, app: ASGIApp, routes: Collection[tuple[str, str]]) -> None:
        self.app = app
        self.routes = frozenset(routes)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and (scope["method"], scope["path"]) in self.routes:
            refusal = await run_in_threadpool(_why_not_logged_in, Request(scope))
            if refusal is not None:
                await send_json_error(send, 401, refusal, ((b"www-authenticate", b"Bearer"),))
                return
        await self.app(scope, receive, send)


def _why_not_logged_in(request: Request) -> str | None:
    """None when the request comes from a live session (or local mode), else why not."""
    workbench = request.app.state.workbench
    token = session_token(request)
    if token is not None:
        try:
            if workbench.users.user_for_token(token, activity=False) is not None:
                return None
        except SessionEndedError as ended:
            return str(ended)
    if local_mode(workbench):
        return None
    return login_needed(token)
