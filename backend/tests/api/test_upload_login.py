"""An upload is not read before its sender is known: once accounts exist, an anonymous photo
import is refused before a byte of its body comes in (FastAPI would otherwise read and spool
the whole multipart body before the route's login check)."""

from __future__ import annotations

import asyncio
from typing import Any

from holiscene.api.upload_login import UploadLogin

from .conftest import Accounts

UPLOAD = ("POST", "/api/scenes")


def _through_gate(accounts: Accounts, headers: list[tuple[bytes, bytes]]) -> tuple[int, bool]:
    """(status sent by the gate or 0, whether the body was read or the route reached)."""
    touched: list[str] = []
    sent: list[dict[str, Any]] = []

    async def receive() -> dict[str, Any]:
        touched.append("body read")
        return {"type": "http.request", "body": b"x", "more_body": False}

    async def send(message: dict[str, Any]) -> None:
        sent.append(message)

    async def route(scope: Any, receive: Any, send: Any) -> None:
        touched.append("route reached")

    scope = {
        "type": "http",
        "method": UPLOAD[0],
        "path": UPLOAD[1],
        "headers": headers,
        "query_string": b"",
        "app": accounts.client.app,
    }
    asyncio.run(UploadLogin(route, {UPLOAD})(scope, receive, send))
    status = sent[0]["status"] if sent else 0
    return status, bool(touched)


def test_an_anonymous_upload_is_refused_unread(accounts: Accounts) -> None:
    assert _through_gate(accounts, []) == (401, False)
    stale = [(b"authorization", b"Bearer not-a-session")]
    assert _through_gate(accounts, stale) == (401, False)


def test_a_logged_in_upload_reaches_the_route(accounts: Accounts) -> None:
    token = accounts.tokens["ann"].encode()
    assert _through_gate(accounts, [(b"authorization", b"Bearer " + token)]) == (0, True)


def test_the_server_answers_an_anonymous_upload_with_log_in_first(accounts: Accounts) -> None:
    answer = accounts.client.post(
        "/api/scenes", files={"image": ("room.jpg", b"\xff" * 1000, "image/jpeg")}
    )
    assert answer.status_code == 401
    assert answer.json()["detail"] == "log in first"
    assert accounts.client.get("/api/scenes", headers=accounts.headers("ada")).json() == []
