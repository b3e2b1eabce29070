"""A cap on request bodies, enforced before a body is read.

Without it anyone, logged in or not, could make the server read and parse a body of any size
(a 200 MB JSON body took 4 s and 377 MB before its 401). The cap is checked twice: against
Content-Length before the first byte is read, and while the body streams in (a chunked body
has no length), so no route ever holds more than its limit.
"""

from __future__ import annotations

from collections.abc import Mapping

from starlette.exceptions import HTTPException
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from .asgi_answer import send_json_error

MB = 1024 * 1024


class BodyTooLargeError(HTTPException):
    """An HTTPException, so FastAPI's body parsing passes it on as it is (413)."""

    def __init__(self, limit: int) -> None:
        super().__init__(413, f"the request body is larger than the {_size(limit)} accepted here")


def _size(limit: int) -> str:
    return f"{limit / MB:g} MB" if limit >= MB else f"{limit} bytes"


class BodySizeLimit:
    """`default` bytes for every request; `per_route` maps (method, path) to a larger limit
    for the routes that take uploads."""

    def __init__(
        self, app: ASGIApp, default: int, per_route: Mapping[tuple[str, str], int]
    ) -> None:
        self.app = app
        self.default = default
        self.per_route = dict(per_route)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        limit = self.per_route.get((scope["method"], scope["path"]), self.default)
        declared = _content_length(scope)
        if declared is not None and declared > limit:
            await _refuse(send, BodyTooLargeError(limit))  # the body is never read
            return
        received = 0

        async def capped_receive() -> Message:
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > limit:
                    raise BodyTooLargeError(limit)
            return message

        started = False

        async def watched_send(message: Message) -> None:
            nonlocal started
            started = started or message["type"] == "http.response.start"
            await send(message)

        try:
            await self.app(scope, capped_receive, watched_send)
        except BodyTooLargeError as too_large:  # read outside FastAPI's own error handling
            if started:
                raise
            await _refuse(send, too_large)


def _content_length(scope: Scope) -> int | None:
    for name, value in scope["headers"]:
        if name == b"content-length":
            try:
                return int(value)
            except ValueError:
                return None
    return None


async def _refuse(send: Send, error: BodyTooLargeError) -> None:
    # The unread body is still on the connection: it must not carry another request.
    await send_json_error(send, 413, error.detail, ((b"connection", b"close"),))
