"""Who may talk to the server: the Host a request names, and the page a change comes from.

- Host: only names the server is meant to be reached by (the loopback names, the host it
  listens on, `allowed_hosts`); otherwise 400. A web page on a name its owner points at
  127.0.0.1 ("DNS rebinding") would else be same-origin with the server.
- Origin: a request that changes something (POST, PUT, PATCH, DELETE) sent by a browser names
  the page that sent it in `Origin` (or `Referer`); unless that is the server's own origin or
  in `allowed_origins`, 403. The session cookie's SameSite=Strict alone is not enough: a
  browser counts every port of 127.0.0.1 as the same site, the viewers this server starts
  there included. Scripts (no Origin, no Referer) are not browsers and pass.
"""

from __future__ import annotations

from collections.abc import Iterable
from urllib.parse import urlsplit

from starlette.types import ASGIApp, Receive, Scope, Send

from .asgi_answer import send_json_error

LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")
STATE_CHANGING = frozenset({"POST", "PUT", "PATCH", "DELETE"})
_ANY_ADDRESS = ("0.0.0.0", "::", "")


def allowed_host_names(listen_host: str, extra: Iterable[str]) -> frozenset[str]:
    names = {*LOOPBACK_NAMES, *extra}
    if listen_host not in _ANY_ADDRESS:
        names.add(listen_host)
    return frozenset(_bare_host(n) for n in names)


def _bare_host(host: str) -> str:
    """`Host` header -> name without port, lower case; "[::1]:8000" -> "::1"."""
    host = host.strip().lower()
    if host.startswith("["):
        return host[1 : host.find("]")] if "]" in host else host
    return host.rsplit(":", 1)[0] if host.count(":") == 1 else host


def _origin_of(url: str) -> str | None:
    parts = urlsplit(url)
    if not parts.scheme or not parts.netloc:
        return None
    return f"{parts.scheme}://{parts.netloc}".lower()


class RequestOriginCheck:
    def __init__(
        self,
        app: ASGIApp,
        listen_host: str,
        allowed_hosts: Iterable[str],
        allowed_origins: Iterable[str],
    ) -> None:
        self.app = app
        self.hosts = allowed_host_names(listen_host, allowed_hosts)
        self.any_host = "*" in self.hosts
        self.origins = frozenset(o.rstrip("/").lower() for o in allowed_origins)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {name: value.decode("latin-1") for name, value in scope["headers"]}
        host = headers.get(b"host", "")
        if not self.any_host and _bare_host(host) not in self.hosts:
            shown = host[:100] or "(none)"
            await send_json_error(
                send, 400, f"this server does not answer to the host name {shown}"
            )
            return
        if scope["method"] in STATE_CHANGING:
            sender = headers.get(b"origin") or headers.get(b"referer")
            own = f"{scope.get('scheme', 'http')}://{host}".lower()
            if sender is not None and _origin_of(sender) not in {own, *self.origins}:
                shown = sender[:100]
                message = f"cross-site request from {shown} refused: changes must come from {own}"
                await send_json_error(send, 403, message)
                return
        await self.app(scope, receive, send)
