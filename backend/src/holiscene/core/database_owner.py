"""One server per PostgreSQL database: `holiscene serve` holds a PostgreSQL advisory lock for
its whole life, on a connection of its own, taken before start-up recovery.

The data directory's lock (data_dir_owner) cannot see a second server that shares the
database from another data directory or another machine; its start-up recovery would fail
the first server's jobs all the same. An advisory lock belongs to its connection, so it goes
when the server ends, however it ends. SQLite needs nothing more: its database lives in the
data directory (the default), whose lock covers it.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from sqlalchemy import create_engine, make_url, text
from sqlalchemy.pool import NullPool

# The advisory lock's key: any fixed number, the same for every holiscene server ("HoSc").
SERVER_LOCK_KEY = 0x486F5363


class DatabaseInUseError(RuntimeError):
    """Another server holds the database's lock."""


@contextmanager
def own_database(url: str) -> Iterator[None]:
    """Hold the database for the block (DatabaseInUseError when another server does)."""
    if make_url(url).get_backend_name() != "postgresql":
        yield
        return
    engine = create_engine(url, poolclass=NullPool)
    try:
        with engine.connect() as connection:
            held = connection.scalar(
                text("SELECT pg_try_advisory_lock(:key)"), {"key": SERVER_LOCK_KEY}
            )
            connection.commit()  # the lock is the session's: it outlives this transaction
            if not held:
                shown = make_url(url).render_as_string(hide_password=True)
                raise DatabaseInUseError(
                    f"the database {shown} is in use by another holiscene server; stop it "
                    "first (one server per database, whatever its data directory)"
                )
            yield
    finally:
        engine.dispose()
