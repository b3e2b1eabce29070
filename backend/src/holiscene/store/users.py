"""User accounts and login sessions.

Passwords are stored as argon2id hashes. A session is a random token given to the client
(an HttpOnly cookie, or a bearer token for scripts); the database keeps only its SHA-256, so
reading the database opens no session. Sessions end at logout, at expiry, and when the
user's password is reset.
"""

from __future__ import annotations

import hashlib
import re
import secrets
from dataclasses import dataclass
from datetime import datetime, timedelta

from holiscene_schema import Role, UserInfo
from sqlalchemy import Engine, delete, func, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from ..core.passwords import check_password, hash_password, needs_rehash, verify_password
from ..workflow import RESERVED_NAMES, ROLES
from .clock import as_utc, utcnow
from .tables import SessionRow, UserRow

SESSION_LIFETIME = timedelta(days=7)
NAME_PATTERN = re.compile(r"^[a-z0-9][a-z0-9_.-]{0,63}$")


class UserError(ValueError):
    """A request about users that cannot be done (HTTP 422 or 409, see `status`)."""

    def __init__(self, message: str, status: int = 422) -> None:
        super().__init__(message)
        self.status = status


class UserNotFoundError(LookupError):
    pass


@dataclass(frozen=True)
class User:
    id: int
    name: str
    role: Role


@dataclass(frozen=True)
class NewSession:
    token: str  # given to the client once; only its hash is stored
    user: User
    expires_at: datetime


def _token_hash(token: str) -> str:
    return hashlib.sha256(token.encode()).hexdigest()


def check_name(name: str) -> None:
    if not NAME_PATTERN.match(name):
        raise UserError(
            "a user name has 1 to 64 lower-case letters, digits, '.', '_' or '-', "
            "starting with a letter or digit"
        )
    if name in RESERVED_NAMES:
        raise UserError(f"{name!r} is reserved; choose another name")


def check_role(role: str) -> Role:
    for known in ROLES:
        if role == known:
            return known
    raise UserError(f"unknown role {role!r}: choose one of {', '.join(ROLES)}")


class UserStore:
    def __init__(self, engine: Engine) -> None:
        self.engine = engine

    # -- accounts ------------------------------------------------------------------------

    def any_users(self) -> bool:
        """Whether accounts exist (then every request must log in)."""
        with Session(self.engine) as session:
            return session.scalar(select(UserRow.id).limit(1)) is not None

    def count_admins(self) -> int:
        with Session(self.engine) as session:
            return self._admins(session)

    def list_users(self) -> list[UserInfo]:
        with Session(self.engine) as session:
            rows = session.scalars(select(UserRow).order_by(UserRow.name)).all()
            return [_info(row) for row in rows]

    def roles(self) -> dict[str, Role]:
        with Session(self.engine) as session:
            return {row.name: check_role(row.role) for row in session.scalars(select(UserRow))}

    def create(self, name: str, role: str, password: str) -> UserInfo:
        """A new account. The first account must be an admin: once one exists, login is
        required, and someone must be able to manage the others."""
        check_name(name)
        checked_role = check_role(role)
        check_password(name, password)
        password_hash = hash_password(password)  # slow: outside the transaction
        with Session(self.engine) as session:
            if checked_role != "admin" and session.scalar(select(UserRow.id).limit(1)) is None:
                raise UserError(
                    "the first account must be an admin: once an account exists everyone "
                    "must log in, and an admin must be able to manage the others",
                    409,
                )
            row = UserRow(
                name=name, role=checked_role, password_hash=password_hash, created_at=utcnow()
            )
            session.add(row)
            try:
                session.commit()
            except IntegrityError as exc:
                raise UserError(f"there is already a user {name!r}", 409) from exc
            return _info(row)

    def set_role(self, name: str, role: str) -> UserInfo:
        checked_role = check_role(role)
        with Session(self.engine) as session:
            row = self._row(session, name)
            if row.role == "admin" and checked_role != "admin" and self._admins(session) <= 1:
                raise UserError(f"{name} is the only admin; make someone else admin first", 409)
            row.role = checked_role
            session.commit()
            return _info(row)

    def set_password(self, name: str, password: str) -> UserInfo:
        """A new password; every session of the user ends."""
        check_password(name, password)
        password_hash = hash_password(password)
        with Session(self.engine) as session:
            row = self._row(session, name)
            row.password_hash = password_hash
            session.execute(delete(SessionRow).where(SessionRow.user_id == row.id))
            session.commit()
            return _info(row)

    def check_credentials(self, name: str, password: str) -> User | None:
        """The user when the password is right, else None (same work for unknown names)."""
        with Session(self.engine) as session:
            row = session.scalar(select(UserRow).where(UserRow.name == name))
            if not verify_password(row.password_hash if row else None, password) or row is None:
                return None
            if needs_rehash(row.password_hash):
                row.password_hash = hash_password(password)
                session.commit()
            return User(row.id, row.name, check_role(row.role))

    # -- sessions ------------------------------------------------------------------------

    def open_session(self, user: User) -> NewSession:
        token = secrets.token_urlsafe(32)
        now = utcnow()
        expires = now + SESSION_LIFETIME
        with Session(self.engine) as session:
            session.execute(delete(SessionRow).where(SessionRow.expires_at < now))
            session.add(
                SessionRow(
                    token_hash=_token_hash(token),
                    user_id=user.id,
                    created_at=now,
                    expires_at=expires,
                )
            )
            session.commit()
        return NewSession(token=token, user=user, expires_at=expires)

    def user_for_token(self, token: str) -> User | None:
        """The session's user, read fresh (a role change applies at the next request)."""
        with Session(self.engine) as session:
            found = session.execute(
                select(SessionRow, UserRow)
                .join(UserRow, UserRow.id == SessionRow.user_id)
                .where(SessionRow.token_hash == _token_hash(token))
            ).first()
            if found is None:
                return None
            row, user = found
            if as_utc(row.expires_at) <= utcnow():
                return None
            return User(user.id, user.name, check_role(user.role))

    def close_session(self, token: str) -> None:
        with Session(self.engine) as session:
            session.execute(delete(SessionRow).where(SessionRow.token_hash == _token_hash(token)))
            session.commit()

    # -- helpers -------------------------------------------------------------------------

    @staticmethod
    def _row(session: Session, name: str) -> UserRow:
        row = session.scalar(select(UserRow).where(UserRow.name == name))
        if row is None:
            raise UserNotFoundError(f"no user {name!r}")
        return row

    @staticmethod
    def _admins(session: Session) -> int:
        query = select(func.count()).select_from(UserRow).where(UserRow.role == "admin")
        return int(session.scalar(query) or 0)


def _info(row: UserRow) -> UserInfo:
    return UserInfo(name=row.name, role=check_role(row.role), created_at=as_utc(row.created_at))
