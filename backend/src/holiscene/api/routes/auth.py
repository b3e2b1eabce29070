"""Logging in and out, who am I, and changing one's own password.

The browser gets the session as an HttpOnly, SameSite=Strict cookie (page scripts cannot
read it, other sites cannot make the browser send it); scripts ask for the token in the
answer (`{"token": true}`) and send it as `Authorization: Bearer`.
"""

from __future__ import annotations

from collections.abc import Sequence

from fastapi import APIRouter, HTTPException, Request, Response
from holiscene_schema import CurrentUser, ErrorMessage, LoginRequest, LoginResult, PasswordChange

from ...store.users import SESSION_LIFETIME, AccountDisabledError
from ..attempt_limits import (
    Attempt,
    AttemptLimiter,
    Limit,
    TooManyAttemptsError,
    login_limits,
    password_change_limits,
)
from ..deps import SESSION_COOKIE, UserDep, WorkbenchDep, local_mode, session_token

router = APIRouter(prefix="/api/auth", tags=["auth"])


def _limiter(request: Request) -> AttemptLimiter:
    limiter: AttemptLimiter = request.app.state.attempt_limiter  # one per app (create_app)
    return limiter


def _begin_attempt(request: Request, limits: Sequence[Limit], refusal: str) -> Attempt:
    """The attempt counted against `limits`, or 429 saying `refusal` when one is used up."""
    try:
        return _limiter(request).begin(limits)
    except TooManyAttemptsError as refused:
        raise HTTPException(429, f"{refusal}; wait a few minutes") from refused


def _client(request: Request) -> str:
    # The peer's address (uvicorn puts a local proxy's X-Forwarded-For here).
    return request.client.host if request.client else "unknown"


def _me(name: str, role: str, local: bool) -> CurrentUser:
    return CurrentUser.model_validate({"name": name, "role": role, "local_mode": local})


@router.post(
    "/login",
    response_model=LoginResult,
    responses={
        401: {"model": ErrorMessage},
        403: {"model": ErrorMessage, "description": "The account is disabled"},
        429: {"model": ErrorMessage, "description": "Too many failed logins from here"},
    },
)
def login(
    body: LoginRequest, request: Request, response: Response, workbench: WorkbenchDep
) -> LoginResult:
    name = body.name.strip().lower()
    limits = login_limits(_client(request), name)
    attempt = _begin_attempt(request, limits, "too many failed logins from here")
    try:
        user = workbench.users.log_in(name, body.password)
    except AccountDisabledError as disabled:
        raise HTTPException(403, str(disabled)) from disabled
    if user is None:
        raise HTTPException(401, "wrong user name or password")  # the attempt stays counted
    _limiter(request).succeeded(attempt, forget=[limits[0].key])
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
    responses={
        401: {"model": ErrorMessage},
        403: {"model": ErrorMessage},
        422: {"model": ErrorMessage},
        429: {"model": ErrorMessage},
    },
)
def change_password(
    body: PasswordChange, request: Request, user: UserDep, workbench: WorkbenchDep
) -> Response:
    """Change one's own password (every session of the account ends, this one too). Wrong
    current passwords are limited like logins: a stolen session must not be a way to guess."""
    if user.local:
        raise HTTPException(409, "the local single-user mode has no password to change")
    limits = password_change_limits(user.name)
    attempt = _begin_attempt(request, limits, "too many wrong current passwords")
    if workbench.users.check_credentials(user.name, body.current_password) is None:
        raise HTTPException(403, "the current password is wrong")
    _limiter(request).succeeded(attempt, forget=[limits[0].key])
    workbench.users.set_password(user.name, body.new_password)
    return Response(status_code=204)
