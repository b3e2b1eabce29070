"""Engine creation and schema migration (Alembic, run at start-up)."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from alembic import command
from alembic.config import Config
from sqlalchemy import Engine, create_engine, event
from sqlalchemy.exc import DBAPIError, DisconnectionError

MIGRATIONS_DIR = Path(__file__).resolve().parent.parent / "store" / "migrations"

T = TypeVar("T")

# PostgreSQL's deadlock and serialization failures: the server rolled the transaction back and
# running it again is the documented answer.
_RETRYABLE_SQLSTATES = frozenset({"40P01", "40001"})


# Connections kept open. The API answers in up to 40 threads (AnyIO's default for sync
# routes): with SQLAlchemy's default of 5, concurrent saves opened and closed a connection
# each on PostgreSQL (a new server process and a password exchange every time, ~1 per save
# at 20 writers). Beyond POOL_SIZE, up to POOL_OVERFLOW more are opened for a while.
POOL_SIZE = 20
POOL_OVERFLOW = 30


# A pooled server connection idle this long is checked before use (the server may have
# restarted meanwhile). Not on every use: SQLAlchemy's pool_pre_ping costs about four round
# trips per checkout, and a save checks out four connections.
PING_AFTER_IDLE_S = 10.0


def make_engine(url: str) -> Engine:
    pool = {"pool_size": POOL_SIZE, "max_overflow": POOL_OVERFLOW}
    if url.startswith("sqlite"):
        engine = create_engine(
            url, connect_args={"check_same_thread": False, "timeout": 30}, **pool
        )
        event.listen(engine, "connect", _sqlite_pragmas)
        return engine
    engine = create_engine(url, **pool)
    _ping_after_idle(engine)
    return engine


def without_transaction(engine: Engine) -> Engine:
    """The engine for reads that need no snapshot shared by their statements (the hot reads
    of every save). On PostgreSQL each statement then commits by itself, which saves the
    BEGIN and ROLLBACK round trips of a read-only transaction: two of the four round trips of
    such a read, each a wait for another process on a busy machine. Its default isolation
    (READ COMMITTED) gives every statement a snapshot of its own anyway, so the reader sees
    nothing different. SQLite: the engine as it is."""
    if engine.dialect.name == "sqlite":
        return engine
    return engine.execution_options(isolation_level="AUTOCOMMIT")


def _ping_after_idle(engine: Engine) -> None:
    dbapi_error = engine.dialect.loaded_dbapi.Error

    @event.listens_for(engine, "checkin")
    def _checked_in(_dbapi_connection: Any, record: Any) -> None:
        record.info["checked_in"] = time.monotonic()

    @event.listens_for(engine, "checkout")
    def _checked_out(dbapi_connection: Any, record: Any, _proxy: Any) -> None:
        checked_in = record.info.get("checked_in")
        if checked_in is None or time.monotonic() - checked_in < PING_AFTER_IDLE_S:
            return
        try:
            cursor = dbapi_connection.cursor()
            cursor.execute("SELECT 1")
            cursor.close()
            dbapi_connection.rollback()
        except dbapi_error as lost:
            # The pool drops this connection and checks out another (a new one if need be).
            raise DisconnectionError(f"a pooled connection was lost: {lost}") from lost


def _sqlite_pragmas(dbapi_connection: Any, _record: Any) -> None:
    cursor = dbapi_connection.cursor()
    cursor.execute("PRAGMA foreign_keys=ON")
    cursor.execute("PRAGMA journal_mode=WAL")
    cursor.close()


def migrate(engine: Engine) -> None:
    """Bring the database schema to the newest revision."""
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS_DIR))
    with engine.begin() as connection:
        config.attributes["connection"] = connection
        command.upgrade(config, "head")


def retrying_transaction(work: Callable[[], T], attempts: int = 5) -> T:
    """`work` (one whole transaction, opening its own session) run again when PostgreSQL
    aborted it as a deadlock or serialization failure; any other error, or the last attempt's,
    goes to the caller."""
    for attempt in range(attempts):
        try:
            return work()
        except DBAPIError as error:
            state = getattr(error.orig, "sqlstate", None)
            if state not in _RETRYABLE_SQLSTATES or attempt == attempts - 1:
                raise
    raise AssertionError("unreachable")
