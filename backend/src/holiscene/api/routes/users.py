"""Accounts (admins only): list, create, change a role, reset a password, disable and
enable."""

from __future__ import annotations

from fastapi import APIRouter, Depends, Response
from holiscene_schema import ErrorMessage, NewUser, PasswordReset, RoleChange, UserInfo

from ..deps import WorkbenchDep, require_role

router = APIRouter(
    prefix="/api/users", tags=["users"], dependencies=[Depends(require_role("admin"))]
)

_ERRORS: dict[int | str, dict[str, object]] = {
    404: {"model": ErrorMessage},
    409: {"model": ErrorMessage},
    422: {"model": ErrorMessage},
}


@router.get("", response_model=list[UserInfo])
def list_users(workbench: WorkbenchDep) -> list[UserInfo]:
    return workbench.users.list_users()


@router.post("", status_code=201, response_model=UserInfo, responses=_ERRORS)
def create_user(body: NewUser, workbench: WorkbenchDep) -> UserInfo:
    """A new account (409 for a taken name; the first account must be an admin)."""
    return workbench.users.create(body.name, body.role, body.password)


@router.patch("/{name}", response_model=UserInfo, responses=_ERRORS)
def change_role(name: str, body: RoleChange, workbench: WorkbenchDep) -> UserInfo:
    """409 when it would leave no admin."""
    return workbench.users.set_role(name, body.role)


@router.post("/{name}/disable", response_model=UserInfo, responses=_ERRORS)
def disable_user(name: str, workbench: WorkbenchDep) -> UserInfo:
    """The account can no longer log in, and its sessions stop working at once (401). 409
    for the only enabled admin (also when they disable themselves)."""
    return workbench.users.set_disabled(name, True)


@router.post("/{name}/enable", response_model=UserInfo, responses=_ERRORS)
def enable_user(name: str, workbench: WorkbenchDep) -> UserInfo:
    """The account may log in again (its sessions from before stay ended)."""
    return workbench.users.set_disabled(name, False)


@router.post("/{name}/password", status_code=204, responses=_ERRORS)
def reset_password(name: str, body: PasswordReset, workbench: WorkbenchDep) -> Response:
    """Set a new password; the user's sessions end."""
    workbench.users.set_password(name, body.password)
    return Response(status_code=204)
