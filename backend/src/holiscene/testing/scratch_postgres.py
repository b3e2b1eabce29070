"""A throw-away PostgreSQL server for the tests and benchmarks: initdb into a temporary folder,
the server on a free loopback port (its Unix socket in that folder too), one database per
caller, and everything stopped and removed at the end.

It uses the machine's PostgreSQL binaries (Debian: `apt-get install postgresql`, which puts
them in /usr/lib/postgresql/<version>/bin). PostgreSQL refuses to run as root, so under root
the server runs as the unprivileged `postgres` user that package creates; the folder is
handed to that user and removed by us afterwards.
"""

from __future__ import annotations

import contextlib
import ctypes
import itertools
import os
import pwd
import re
import secrets
import shutil
import signal
import socket
import subprocess
import tempfile
import time
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import psycopg

SERVER_USER = "postgres"  # the account Debian's package makes, for runs as root
_SUPERUSER = "holiscene"
_START_TIMEOUT_S = 30.0
_STOP_TIMEOUT_S = 30.0
# Speed over durability: a scratch cluster is deleted anyway (never for a benchmark).
_NOT_DURABLE = ("fsync=off", "synchronous_commit=off", "full_page_writes=off")
_PR_SET_PDEATHSIG = 1


class PostgresUnavailableError(RuntimeError):
    """No PostgreSQL binaries, or no unprivileged user to run them as."""


def find_bindir() -> Path | None:
    """PostgreSQL's bin folder: HOLISCENE_POSTGRES_BIN when set (only that one), else the
    newest of Debian's /usr/lib/postgresql/<version>/bin, else the folder of `postgres` on
    the PATH."""
    given = os.environ.get("HOLISCENE_POSTGRES_BIN")

    def version(path: Path) -> int:
        return int(path.parent.name) if path.parent.name.isdigit() else 0

    if given:
        candidates = [Path(given)]
    else:
        candidates = sorted(Path("/usr/lib/postgresql").glob("*/bin"), key=version, reverse=True)
        on_path = shutil.which("postgres")
        if on_path:
            candidates.append(Path(on_path).parent)
    for folder in candidates:
        if all((folder / tool).is_file() for tool in ("initdb", "postgres")):
            return folder
    return None


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


class ScratchPostgres:
    """Use as a context manager, or call start() and stop() (stop also removes the folder)."""

    def __init__(self, *, durable: bool = False) -> None:
        """`durable`: keep PostgreSQL's default fsync and commit settings (benchmarks); the
        tests turn them off."""
        try:
            import psycopg  # noqa: F401  (the driver: the postgres extra, in the dev install)
        except ImportError:
            raise PostgresUnavailableError(
                'the PostgreSQL driver is missing: pip install -e ".[postgres]"'
            ) from None
        bindir = find_bindir()
        if bindir is None:
            raise PostgresUnavailableError(
                "PostgreSQL is not installed (no initdb and postgres in "
                f"{os.environ.get('HOLISCENE_POSTGRES_BIN') or '/usr/lib/postgresql/*/bin'} "
                "or on the PATH): install it with `apt-get install postgresql` (make "
                "install-postgres), or set HOLISCENE_POSTGRES_BIN to its bin folder"
            )
        self.bindir = bindir
        self.durable = durable
        self._as: dict[str, Any] = _unprivileged_user()
        self._password = secrets.token_hex(16)
        self._names = itertools.count(1)
        self._root: Path | None = None
        self._server: subprocess.Popen[bytes] | None = None
        self.port = 0

    # -- life cycle ------------------------------------------------------------------------

    def start(self) -> ScratchPostgres:
        self._root = Path(tempfile.mkdtemp(prefix="holiscene-postgres-"))
        try:
            self._hand_over(self._root)
            self._initdb()
            for _ in range(3):  # another process may take the free port before the server
                if self._launch():
                    return self
            raise PostgresUnavailableError(f"PostgreSQL did not start: {self._log_tail()}")
        except BaseException:
            self.stop()
            raise

    def stop(self) -> None:
        """Stop the server (a fast shutdown) and remove its folder; safe to call twice."""
        server, self._server = self._server, None
        if server is not None and server.poll() is None:
            server.send_signal(signal.SIGINT)
            try:
                server.wait(_STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                server.kill()
                server.wait()
        root, self._root = self._root, None
        if root is not None:
            shutil.rmtree(root, ignore_errors=True)

    def __enter__(self) -> ScratchPostgres:
        return self.start()

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        self.stop()

    # -- databases -------------------------------------------------------------------------

    def url(self, database: str) -> str:
        """The SQLAlchemy URL of one database of this server."""
        return (
            f"postgresql+psycopg://{_SUPERUSER}:{self._password}@127.0.0.1:{self.port}/{database}"
        )

    def create_database(self) -> str:
        """A new empty database; returns its name."""
        name = f"test_{next(self._names)}"
        with self._admin() as connection:
            connection.execute(f'CREATE DATABASE "{name}"')
        return name

    def drop_database(self, name: str) -> None:
        """Drop a database, closing whatever connections a test left open on it."""
        with self._admin() as connection:
            connection.execute(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)')

    # -- helpers ---------------------------------------------------------------------------

    @property
    def _folder(self) -> Path:
        if self._root is None:
            raise RuntimeError("the scratch PostgreSQL server is not started")
        return self._root

    def _admin(self) -> psycopg.Connection[Any]:
        import psycopg

        return psycopg.connect(
            host="127.0.0.1",
            port=self.port,
            user=_SUPERUSER,
            password=self._password,
            dbname="postgres",
            autocommit=True,
        )

    def _hand_over(self, path: Path) -> None:
        if "user" in self._as:
            entry = pwd.getpwnam(self._as["user"])
            os.chown(path, entry.pw_uid, entry.pw_gid)

    def _initdb(self) -> None:
        password_file = self._folder / "password"
        password_file.write_text(self._password + "\n")
        self._hand_over(password_file)
        log = self._folder / "initdb.log"
        with log.open("wb") as output:
            done = subprocess.run(
                [
                    str(self.bindir / "initdb"),
                    f"--pgdata={self._folder / 'data'}",
                    f"--username={_SUPERUSER}",
                    f"--pwfile={password_file}",
                    "--auth=scram-sha-256",  # a password even on loopback: other users share it
                    "--encoding=UTF8",
                    "--locale=C",
                    "--no-sync",
                ],
                stdout=output,
                stderr=subprocess.STDOUT,
                cwd=self._folder,
                check=False,
                **self._as,
            )
        password_file.unlink()
        if done.returncode != 0:
            raise PostgresUnavailableError(f"initdb failed: {log.read_text()[-2000:]}")

    def _launch(self) -> bool:
        """Start the server on a free port; False if the port was taken meanwhile."""
        import psycopg

        self.port = _free_port()
        settings = [
            f"port={self.port}",
            "listen_addresses=127.0.0.1",
            f"unix_socket_directories={self._folder}",
            "max_connections=300",
            *(() if self.durable else _NOT_DURABLE),
        ]
        options = [part for setting in settings for part in ("-c", setting)]
        with (self._folder / "server.log").open("ab") as log:
            self._server = subprocess.Popen(
                [str(self.bindir / "postgres"), "-D", str(self._folder / "data"), *options],
                stdout=log,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                cwd=self._folder,
                preexec_fn=_die_with_parent,  # a killed test run leaves no server behind
                **self._as,
            )
        deadline = time.monotonic() + _START_TIMEOUT_S
        while time.monotonic() < deadline:
            if self._server.poll() is not None:
                self._server = None
                if re.search(r"could not bind|Address already in use", self._log_tail()):
                    return False
                raise PostgresUnavailableError(f"PostgreSQL exited: {self._log_tail()}")
            with contextlib.suppress(psycopg.OperationalError), self._admin():
                return True
            time.sleep(0.1)
        raise PostgresUnavailableError(
            f"PostgreSQL did not answer in {_START_TIMEOUT_S:.0f} s: {self._log_tail()}"
        )

    def _log_tail(self) -> str:
        log = self._folder / "server.log"
        return log.read_text(errors="replace")[-2000:] if log.is_file() else "(no log)"


def _unprivileged_user() -> dict[str, Any]:
    """Extra arguments for subprocess: none as a normal user; under root, the postgres user
    (its own group, no supplementary groups)."""
    if os.geteuid() != 0:
        return {}
    try:
        entry = pwd.getpwnam(SERVER_USER)
    except KeyError:
        raise PostgresUnavailableError(
            f"PostgreSQL refuses to run as root, and there is no {SERVER_USER!r} user to run "
            "it as (Debian's postgresql package creates one)"
        ) from None
    return {"user": entry.pw_name, "group": entry.pw_gid, "extra_groups": []}


_LIBC = ctypes.CDLL(None, use_errno=True)


def _die_with_parent() -> None:
    # Runs in the child after it switched user (a change of user would clear the setting):
    # the server gets SIGINT, a fast shutdown, when the process that started it dies.
    _LIBC.prctl(_PR_SET_PDEATHSIG, signal.SIGINT, 0, 0, 0)
