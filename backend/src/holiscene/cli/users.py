"""`holiscene users ...`: accounts from the command line (the way to make the first admin),
and the check `holiscene serve` makes before listening beyond loopback."""

from __future__ import annotations

import argparse
import getpass
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

from ..core.settings import Settings
from ..editing.workflow_rules import ROLES

if TYPE_CHECKING:
    from ..store.users import UserStore

PASSWORD_ENV = "HOLISCENE_PASSWORD"

SettingsFactory = Callable[[argparse.Namespace], Settings]


class UsersCliError(Exception):
    """A message for the user (exit status 2)."""


def add_user_commands(
    sub: argparse._SubParsersAction,  # type: ignore[type-arg]
    settings: SettingsFactory,
) -> None:
    users = sub.add_parser(
        "users", help="user accounts: add, list, set-role, reset-password, disable, enable"
    )
    commands = users.add_subparsers(required=True, metavar="ACTION")

    def store_options(parser: argparse.ArgumentParser) -> None:
        parser.add_argument("--data-dir", type=Path, help="data directory (default var/data)")
        parser.add_argument("--database-url", help="SQLAlchemy URL (default: SQLite there)")

    add = commands.add_parser(
        "add", help=f"add an account (password from ${PASSWORD_ENV}, else asked for)"
    )
    add.add_argument("name")
    add.add_argument("--role", required=True, choices=ROLES)
    store_options(add)
    add.set_defaults(handler=lambda args: _add(args, settings(args)))

    listing = commands.add_parser("list", help="list the accounts")
    store_options(listing)
    listing.set_defaults(handler=lambda args: _list(settings(args)))

    role = commands.add_parser("set-role", help="change an account's role")
    role.add_argument("name")
    role.add_argument("role", choices=ROLES)
    store_options(role)
    role.set_defaults(handler=lambda args: _set_role(args, settings(args)))

    reset = commands.add_parser(
        "reset-password", help=f"set a new password (from ${PASSWORD_ENV}, else asked for)"
    )
    reset.add_argument("name")
    store_options(reset)
    reset.set_defaults(handler=lambda args: _reset(args, settings(args)))

    for action, disabled, help_text in (
        ("disable", True, "disable an account: no login, and its sessions end at once"),
        ("enable", False, "enable a disabled account again"),
    ):
        switch = commands.add_parser(action, help=help_text)
        switch.add_argument("name")
        store_options(switch)
        switch.set_defaults(
            handler=lambda args, off=disabled: _set_disabled(args, settings(args), off)
        )


@contextmanager
def user_store(settings: Settings) -> Iterator[UserStore]:
    """The accounts of a store, without starting the workbench (no models, no jobs)."""
    from ..core.db import make_engine, migrate
    from ..store.users import UserStore

    settings.data_dir.mkdir(parents=True, exist_ok=True)
    engine = make_engine(settings.resolved_database_url)
    try:
        migrate(engine)
        yield UserStore(engine, settings.session_idle_timeout)
    finally:
        engine.dispose()


def _password(name: str) -> str:
    from_env = os.environ.get(PASSWORD_ENV)
    if from_env is not None:
        return from_env
    if not sys.stdin.isatty():
        raise UsersCliError(f"no password: set {PASSWORD_ENV} or run this in a terminal")
    first = getpass.getpass(f"password for {name}: ")
    if getpass.getpass("the same again: ") != first:
        raise UsersCliError("the two passwords differ; nothing changed")
    return first


def _run(action: Callable[[], str]) -> int:
    from ..core.passwords import WeakPasswordError
    from ..store.users import UserError, UserNotFoundError

    try:
        print(action())
    except (UserError, WeakPasswordError, UserNotFoundError) as exc:
        raise UsersCliError(str(exc.args[0]) if exc.args else str(exc)) from exc
    return 0


def _add(args: argparse.Namespace, settings: Settings) -> int:
    password = _password(args.name)
    with user_store(settings) as users:
        return _run(lambda: f"added {users.create(args.name, args.role, password).name}")


def _list(settings: Settings) -> int:
    with user_store(settings) as users:
        accounts = users.list_users()
    if not accounts:
        print("no accounts (the server runs in local single-user mode on 127.0.0.1)")
    for user in accounts:
        line = f"{user.name:24s} {user.role:10s} since {user.created_at:%Y-%m-%d %H:%M}"
        if user.disabled_at is not None:
            line += f"  disabled since {user.disabled_at:%Y-%m-%d %H:%M}"
        print(line)
    return 0


def _set_role(args: argparse.Namespace, settings: Settings) -> int:
    with user_store(settings) as users:
        return _run(lambda: f"{args.name} is now {users.set_role(args.name, args.role).role}")


def _reset(args: argparse.Namespace, settings: Settings) -> int:
    password = _password(args.name)
    with user_store(settings) as users:
        return _run(lambda: f"new password set for {users.set_password(args.name, password).name}")


def _set_disabled(args: argparse.Namespace, settings: Settings, disabled: bool) -> int:
    with user_store(settings) as users:
        state = "disabled" if disabled else "enabled"
        return _run(lambda: f"{users.set_disabled(args.name, disabled).name} is now {state}")


def check_can_serve(settings: Settings, allow_remote: bool) -> None:
    """Beyond loopback: only with --allow-remote and an admin account (no default
    credentials, ever). On loopback without accounts the server runs in local mode."""
    from ..api.deps import is_loopback

    if is_loopback(settings.host):
        return
    if not allow_remote:
        raise UsersCliError(
            f"refusing to listen on {settings.host}: pass --allow-remote to serve beyond "
            "127.0.0.1 (everyone must then log in)"
        )
    with user_store(settings) as users:
        admins = users.count_admins()
    if admins == 0:
        raise UsersCliError(
            f"refusing to listen on {settings.host}: there is no admin account and there are "
            "no default credentials; create one first:\n"
            f"  holiscene users add NAME --role admin --data-dir {settings.data_dir}"
        )
