"""Request dependencies as Annotated aliases: the workbench, and who is asking.

Every API router is included with `Depends(current_user)` (see app.py), so a route added
later is closed to anonymous requests by default; routes for reviewers or admins also
declare `ReviewerDep` or `AdminDep`. Roles are nested (admin > reviewer > annotator), and
annotator is the lowest, so "any logged-in user" may read and annotate.

Local single-user mode: while the server listens on loopback only and no account exists,
every request is the local admin (`local`), as before accounts existed. The first account
ends it; beyond loopback it never applies (the server refuses to start without an admin).
"""

from __future__ import annotations

import ipaddress
from collections.abc import Awaitable, Callable
from typing import Annotated

from fastapi import Depends, HTTPException, Request
from holiscene_schema import Role

from ..editing.workflow_rules import LOCAL_USER, Actor, has_role
from ..services.workbench import Workbench
from ..store.users import SessionEndedError

SESSION_COOKIE = "holiscene_session"
# Sent by the app on requests it makes by itself (polling a job, refreshing the scene list):
# they are answered as usual but are not activity, so they do not hold a session open.
BACKGROUND_HEADER = "X-Holiscene-Background"


# Dependencies that do no I/O are `async def`: FastAPI runs a plain `def` in the thread pool,
# a hand-over to another thread and back on every request (docs/benchmarks.md, concurrent
# writers).
async def get_workbench(request: Request) -> Workbench:
    workbench: Workbench = request.app.state.workbench
    return workbench


WorkbenchDep = Annotated[Workbench, Depends(get_workbench)]


def is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def local_mode(workbench: Workbench) -> bool:
    """Loopback only and no accounts yet: no login, everyone is the local admin."""
    return is_loopback(workbench.settings.host) and not workbench.users.any_users()


def session_token(request: Request) -> str | None:
    """`Authorization: Bearer <token>` (scripts), else the session cookie (the browser)."""
    scheme, _, token = request.headers.get("authorization", "").partition(" ")
    if scheme.lower() == "bearer" and token.strip():
        return token.strip()
    return request.cookies.get(SESSION_COOKIE) or None


def is_background(request: Request) -> bool:
    """Whether the page sent this request by itself, not because of something a person did."""
    return request.headers.get(BACKGROUND_HEADER, "") == "1"


def current_user(request: Request, workbench: WorkbenchDep) -> Actor:
    token = session_token(request)
    if token is not None:
        try:
            user = workbench.users.user_for_token(token, activity=not is_background(request))
        except SessionEndedError as ended:
            raise HTTPException(401, str(ended), headers={"WWW-Authenticate": "Bearer"}) from ended
        if user is not None:
            return Actor(user.name, user.role)
    if local_mode(workbench):  # cross-site writes: refused before (request_origin.py)
        return Actor(LOCAL_USER, "admin", local=True)
    raise HTTPException(401, login_needed(token), headers={"WWW-Authenticate": "Bearer"})


def login_needed(token: str | None) -> str:
    """Why a request without a working session is refused. A token that opens nothing was
    closed: by logging out, or by a new password, which ends every session of its user."""
    if token is None:
        return "log in first"
    return "log in first (your session has ended: you logged out, or your password was changed)"


def require_role(role: Role) -> Callable[[Actor], Awaitable[Actor]]:
    async def check(user: Annotated[Actor, Depends(current_user)]) -> Actor:
        if not has_role(user.role, role):
            raise HTTPException(403, f"this needs the {role} role; you are {user.role}")
        return user

    check.__name__ = f"require_{role}"
    return check


UserDep = Annotated[Actor, Depends(current_user)]
AnnotatorDep = Annotated[Actor, Depends(require_role("annotator"))]
ReviewerDep = Annotated[Actor, Depends(require_role("reviewer"))]
AdminDep = Annotated[Actor, Depends(require_role("admin"))]


def author_of(user: Actor, given: str) -> str:
    """The author to record: the account's name; in local mode the name typed in the app
    (there is nothing else to tell people apart by)."""
    return given if user.local else user.name
