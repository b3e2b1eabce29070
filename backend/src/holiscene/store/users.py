"""User accounts and login sessions.

Passwords are stored as argon2id hashes. A session is a random token given to the client
(an HttpOnly cookie, or a bearer token for scripts); the database keeps only its SHA-256, so
reading the database opens no session. Sessions end at logout, at expiry, after a while
without requests (the idle timeout; every request a person makes moves it on, the page's
background polling does not), when the user's password is reset, and while an admin has
disabled the account.
"""

from __future__ import annotations

import hashlib
import re
import secrets
import time
from dataclasses import dataclass
from datetime import datetime, timedelta

from holiscene_schema import Role, UserInfo
from sqlalchemy import ColumnElement, Engine, delete, func, select, update
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session, aliased

from ..core.db import retrying_transaction, without_transaction
from ..core.errors import DomainError, NotFoundError
from ..core.passwords import check_password, hash_password, needs_rehash, verify_password
from ..editing.workflow_rules import RESERVED_NAMES, ROLES
from .clock import as_utc, utcnow
from .tables import SessionRow, UserRow

SESSION_LIFETIME = timedelta(days=7)
# A session's last-seen time is written at most this often (not on every request).
LAST_SEEN_STEP = timedelta(seconds=30)
NAME_PATTERN = re.compile(r"^[a-z0-9][a-z0-9_.-]{0,63}$")


class UserError(DomainError, ValueError):
    """A request about users that cannot be done (HTTP 422 or 409, see `status`)."""

    def __init__(self, message: str, status: int = 422) -> None:
        super().__init__(message)
        self.status = status


class UserNotFoundError(NotFoundError):
    pass


class SessionEndedError(Exception):
    """A token of a session that no longer opens anything; the message says why (HTTP 401)."""


class AccountDisabledError(Exception):
    """The right password for an account an admin disabled (HTTP 403 at login)."""


@dataclass(frozen=True)
class User:
    id: int
    name: str
    role: Role
    disabled: bool = False


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


_ANY_USER = select(UserRow.id).limit(1)


# How long "no accounts yet" is believed before the database is asked again (any_users).
NO_USERS_RECHECK_S = 1.0


class UserStore:
    def __init__(
        self,
        engine: Engine,
        idle_timeout: timedelta,
        no_users_recheck_s: float = NO_USERS_RECHECK_S,
    ) -> None:
        """`idle_timeout`: how long a session lasts without a request (Settings);
        `no_users_recheck_s`: how long a "no accounts" answer is believed (any_users)."""
        self.engine = engine
        # For the one-statement reads of every request (no BEGIN/ROLLBACK on PostgreSQL).
        self.reads = without_transaction(engine)
        self.idle_timeout = idle_timeout
        self._last_seen_step = min(LAST_SEEN_STEP, idle_timeout / 10)
        self._users_exist = False
        self._no_users_recheck_s = no_users_recheck_s
        self._no_users_until = 0.0  # time.monotonic() until which "no accounts" holds

    # -- accounts ------------------------------------------------------------------------

    def any_users(self) -> bool:
        """Whether accounts exist (then every request must log in). Asked on every request;
        accounts are disabled, never deleted, so once there is one the answer stays yes and
        the store stops asking the database. A "no" is believed for `no_users_recheck_s`
        (a second by default): `holiscene users add` in another process may make the first
        account while the server runs, and logging in is then required a second later at
        most; an account made through this store counts at once."""
        if self._users_exist:
            return True
        if time.monotonic() < self._no_users_until:
            return False
        # A plain connection, not an ORM session: half the CPU of one, on every request of a
        # local server (docs/benchmarks.md, concurrent writers).
        with self.reads.connect() as connection:
            self._users_exist = connection.scalar(_ANY_USER) is not None
        if not self._users_exist:
            self._no_users_until = time.monotonic() + self._no_users_recheck_s
        return self._users_exist

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
            self._users_exist = True
            return _info(row)

    def set_role(self, name: str, role: str) -> UserInfo:
        """A new role. The last enabled admin cannot stop being admin (nobody could manage
        accounts): checked in the statement that writes the role (`_unless_last_admin`)."""
        checked_role = check_role(role)

        def write() -> UserInfo:
            with Session(self.engine) as session:
                row = self._row(session, name)
                if checked_role == "admin":
                    row.role = checked_role
                else:
                    _update_unless_last_admin(
                        session,
                        row.id,
                        f"{name} is the only admin; make someone else admin first",
                        role=checked_role,
                    )
                session.commit()
                return _info(row)

        # Two admins demoting each other at once can deadlock on PostgreSQL: run again.
        return retrying_transaction(write)

    def set_disabled(self, name: str, disabled: bool) -> UserInfo:
        """Disable an account (it cannot log in, and its sessions stop working at once) or
        enable it again (its sessions from before stay ended: log in anew). The last enabled
        admin cannot be disabled, not even by themselves: nobody could manage accounts."""

        def write() -> UserInfo:
            with Session(self.engine) as session:
                row = self._row(session, name)
                if disabled and row.disabled_at is None:
                    _update_unless_last_admin(
                        session,
                        row.id,
                        f"{name} is the only enabled admin and cannot be disabled: make "
                        "someone else admin first",
                        UserRow.disabled_at.is_(None),
                        disabled_at=utcnow(),
                    )
                elif not disabled and row.disabled_at is not None:
                    row.disabled_at = None
                    session.execute(delete(SessionRow).where(SessionRow.user_id == row.id))
                session.commit()
                return _info(row)

        return retrying_transaction(write)

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
            return _user(row)

    def log_in(self, name: str, password: str) -> User | None:
        """check_credentials for a login: AccountDisabledError for a disabled account (said
        only to whoever knows its password)."""
        user = self.check_credentials(name, password)
        if user is not None and user.disabled:
            raise AccountDisabledError(
                f"the account {user.name} is disabled; ask an admin to enable it"
            )
        return user

    # -- sessions ------------------------------------------------------------------------

    def open_session(self, user: User) -> NewSession:
        token = secrets.token_urlsafe(32)
        now = utcnow()
        expires = now + SESSION_LIFETIME
        with Session(self.engine) as session:
            session.execute(
                delete(SessionRow).where(
                    (SessionRow.expires_at < now)
                    | (SessionRow.last_seen_at < now - self.idle_timeout)
                )
            )
            session.add(
                SessionRow(
                    token_hash=_token_hash(token),
                    user_id=user.id,
                    created_at=now,
                    expires_at=expires,
                    last_seen_at=now,
                )
            )
            session.commit()
        return NewSession(token=token, user=user, expires_at=expires)

    def user_for_token(self, token: str, *, activity: bool = True) -> User | None:
        """The session's user, read fresh (a role change applies at the next request), and
        the session kept alive: each request moves its idle deadline on, unless `activity`
        is False (a page polling by itself: a forgotten tab must still idle out). None for a
        token that never opened a session (or whose session was closed); SessionEndedError,
        saying why, for one that expired, went unused too long, or whose account is
        disabled."""
        now = utcnow()
        # One read (and now and then one UPDATE, committed by itself): no transaction needed.
        with Session(self.reads) as session:
            found = session.execute(
                select(SessionRow, UserRow)
                .join(UserRow, UserRow.id == SessionRow.user_id)
                .where(SessionRow.token_hash == _token_hash(token))
            ).first()
            if found is None:
                return None
            row, user = found
            if user.disabled_at is not None:
                raise SessionEndedError(
                    f"the account {user.name} was disabled by an admin; your session ended"
                )
            if as_utc(row.expires_at) <= now:
                raise SessionEndedError("your session expired; log in again")
            last_seen = as_utc(row.last_seen_at)
            if last_seen + self.idle_timeout <= now:
                raise SessionEndedError(
                    f"your session ended after {_duration(self.idle_timeout)} without "
                    "activity; log in again"
                )
            if activity and now - last_seen >= self._last_seen_step:
                row.last_seen_at = now
                session.commit()
            return _user(user)

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
        """Enabled admins: a disabled one manages nothing."""
        query = (
            select(func.count())
            .select_from(UserRow)
            .where(UserRow.role == "admin", UserRow.disabled_at.is_(None))
        )
        return int(session.scalar(query) or 0)


def _update_unless_last_admin(
    session: Session,
    user_id: int,
    refusal: str,
    *conditions: ColumnElement[bool],
    **values: object,
) -> None:
    """Write `values` to user `user_id` (where `conditions` hold too), unless that leaves no
    enabled admin (`_unless_last_admin`): then UserError 409 `refusal`, nothing written."""
    moved = session.execute(
        update(UserRow)
        .where(UserRow.id == user_id, *conditions, _unless_last_admin(user_id))
        .values(**values)
        .execution_options(synchronize_session=False)
    )
    if moved.rowcount != 1:  # type: ignore[attr-defined]
        raise UserError(refusal, 409)


def _unless_last_admin(user_id: int) -> ColumnElement[bool]:
    """For an UPDATE of user `user_id` that takes admin rights away (a role change, or
    disabling): the user is not an enabled admin, or another enabled admin remains.

    It is checked inside the UPDATE that writes the row, never read before it, so two admins
    demoting or disabling each other at once cannot both win:
    - SQLite runs one writer at a time and an UPDATE takes the write lock before it reads, so
      the second UPDATE counts the admins with the first one's change committed (or fails
      "database is locked" after the 30 s busy timeout, changing nothing).
    - PostgreSQL (READ COMMITTED) would count from the statement's snapshot, and two UPDATEs of
      different rows do not wait for each other: both could see the other admin still there
      and win. So the count locks the enabled admins it counts (FOR UPDATE, in id order, so two
      such UPDATEs queue on the first row instead of deadlocking): the second one waits until
      the first commits, then reads the admin it demoted as it is now (no longer an enabled
      admin, left out of the count) and writes nothing.
    SQLite ignores FOR UPDATE (it needs none).
    """
    admin = aliased(UserRow)  # not correlated with the row updated
    enabled_admins = (
        select(admin.id)
        .where(admin.role == "admin", admin.disabled_at.is_(None))
        .order_by(admin.id)
        .with_for_update()
        .subquery()
    )
    others = (
        select(func.count())
        .select_from(enabled_admins)
        .where(enabled_admins.c.id != user_id)
        .scalar_subquery()
    )
    return (UserRow.role != "admin") | UserRow.disabled_at.is_not(None) | (others > 0)


def _user(row: UserRow) -> User:
    return User(row.id, row.name, check_role(row.role), disabled=row.disabled_at is not None)


def _info(row: UserRow) -> UserInfo:
    return UserInfo(
        name=row.name,
        role=check_role(row.role),
        created_at=as_utc(row.created_at),
        disabled=row.disabled_at is not None,
        disabled_at=as_utc(row.disabled_at) if row.disabled_at is not None else None,
    )


def _duration(span: timedelta) -> str:
    """8 hours, 90 minutes, 45 seconds."""
    seconds = span.total_seconds()
    for unit, size in (("hour", 3600), ("minute", 60)):
        if seconds >= size and seconds % size == 0:
            count = int(seconds // size)
            return f"{count} {unit}{'s' if count != 1 else ''}"
    if seconds >= 60:
        return f"{seconds / 60:g} minutes"
    return f"{seconds:g} seconds"
