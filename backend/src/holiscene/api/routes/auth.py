"""Logging in and out, who am I, and changing one's own password.

The browser gets the session as an HttpOnly, SameSite=Strict cookie (page scripts cannot
read it, other sites cannot make the browser send it); scripts ask for the token in the
answer (`{"token": true}`) and send it as `Authorization: Bearer`.
"""

from __future__ import annotations

import threading
import time
from collections import defaultdict, deque

from fastapi import APIRouter, HTTPException, Request, Response
from holiscene_schema import CurrentUser, ErrorMessage, LoginRequest, LoginResult, PasswordChange

from ...store.users import SESSION_LIFETIME, AccountDisabledError
from ..deps import SESSION_COOKIE, UserDep, WorkbenchDep, local_mode, session_token

router = APIRouter(prefix="/api/auth", tags=["auth"])

# Guessing passwords: at most this many failures per name in the window, then 429.
MAX_FAILURES = 5
FAILURE_WINDOW_S = 300.0


class LoginThrottle:
    """Failed logins per name, in memory (one server process)."""

    def __init__(self) -> None:
        self._failures: dict[str, deque[float]] = defaultdict(deque)
        self._lock = threading.Lock()

    def _recent(self, name: str, now: float) -> deque[float]:
        failures = self._failures[name]
        while failures and failures[0] < now - FAILURE_WINDOW_S:
            failures.popleft()
        return failures

    def blocked(self, name: str) -> bool:
        with self._lock:
            return len(self._recent(name, time.monotonic())) >= MAX_FAILURES

    def failed(self, name: str) -> None:
        with self._lock:
            now = time.monotonic()
            self._recent(name, now).append(now)

    def succeeded(self, name: str) -> None:
        with self._lock:
            self._failures.pop(name, None)


def _throttle(request: Request) -> LoginThrottle:
    throttle: LoginThrottle = request.app.state.login_throttle  # one per app (create_app)
    return throttle


def _me(name: str, role: str, local: bool) -> CurrentUser:
    return CurrentUser.model_validate({"name": name, "role": role, "local_mode": local})


@router.post(
    "/login",
    response_model=LoginResult,
    responses={
        401: {"model": ErrorMessage},
        403: {"model": ErrorMessage, "description": "The account is disabled"},
        429: {"model": ErrorMessage},
    },
)
def login(
    body: LoginRequest, request: Request, response: Response, workbench: WorkbenchDep
) -> LoginResult:
    name = body.name.strip().lower()
    throttle = _throttle(request)
    if throttle.blocked(name):
        raise HTTPException(429, "too many failed logins for this name; wait a few minutes")
    try:
        user = workbench.users.log_in(name, body.password)
    except AccountDisabledError as disabled:
        raise HTTPException(403, str(disabled)) from disabled
    if user is None:
        throttle.failed(name)
        raise HTTPException(401, "wrong user name or password")
    throttle.succeeded(name)
    opened = workbench.users.open_session(user)
    if not body.token:
        response.set_cookie(
            SESSION_COOKIE,
            opened.token,
            max_age=int(SESSION_LIFETIME.total_seconds()),
            httponly=True,
            samesite="strict",
            secure=request.url.scheme == "https",
            path="/",
        )
    return LoginResult(
        user=_me(user.name, user.role, False),
        token=opened.token if body.token else None,
        expires_at=opened.expires_at,
    )


@router.post("/logout", status_code=204)
def logout(request: Request, response: Response, workbench: WorkbenchDep) -> Response:
    """End this session (no error when there is none)."""
    token = session_token(request)
    if token is not None:
        workbench.users.close_session(token)
    response.status_code = 204
    response.delete_cookie(SESSION_COOKIE, path="/", httponly=True, samesite="strict")
    return response


@router.get("/me", response_model=CurrentUser, responses={401: {"model": ErrorMessage}})
def me(user: UserDep, workbench: WorkbenchDep) -> CurrentUser:
    return _me(user.name, user.role, user.local and local_mode(workbench))


@router.post(
    "/password",
    status_code=204,
    responses={401: {"model": ErrorMessage}, 422: {"model": ErrorMessage}},
)
def change_password(body: PasswordChange, user: UserDep, workbench: WorkbenchDep) -> Response:
    """Change one's own password (every session of the account ends, this one too)."""
    if user.local:
        raise HTTPException(409, "the local single-user mode has no password to change")
    if workbench.users.check_credentials(user.name, body.current_password) is None:
        raise HTTPException(403, "the current password is wrong")
    workbench.users.set_password(user.name, body.new_password)
    return Response(status_code=204)
