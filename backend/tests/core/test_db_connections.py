"""The server's connections to PostgreSQL: concurrent requests reuse pooled connections
instead of opening one per request, and a pooled connection the server dropped while it was
idle (a restart) is replaced before a request uses it."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator

import pytest
from holiscene.core import db
from holiscene.testing.scratch_postgres import ScratchPostgres
from sqlalchemy import Engine, create_engine, event, text
from sqlalchemy.pool import NullPool

WRITERS = 20


@pytest.fixture()
def engine(postgres_server: ScratchPostgres) -> Iterator[Engine]:
    name = postgres_server.create_database()
    made = db.make_engine(postgres_server.url(name))
    yield made
    made.dispose()
    postgres_server.drop_database(name)


def test_concurrent_requests_reuse_pooled_connections(engine: Engine) -> None:
    opened = []
    event.listen(engine, "connect", lambda *_: opened.append(1))
    start = threading.Barrier(WRITERS)

    def requests() -> None:
        start.wait()
        for _ in range(10):  # like a save: short uses of the database, work in between
            with engine.connect() as connection:
                connection.execute(text("SELECT pg_sleep(0.005)"))
            time.sleep(0.01)

    threads = [threading.Thread(target=requests) for _ in range(WRITERS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    # One connection per concurrent user at most, not one per request (each would be a new
    # server process and a password exchange).
    assert 0 < len(opened) <= WRITERS


def test_a_connection_dropped_while_idle_is_replaced(
    engine: Engine, monkeypatch: pytest.MonkeyPatch
) -> None:
    with engine.connect() as connection:
        pid = connection.execute(text("SELECT pg_backend_pid()")).scalar_one()
    # The server ends that session, as a restart would, while the connection waits in the
    # pool (asked on a connection of its own, outside the pool).
    with create_engine(engine.url, poolclass=NullPool).connect() as admin:
        killed = admin.execute(text("SELECT pg_terminate_backend(:pid)"), {"pid": pid})
        assert killed.scalar_one() is True
    monkeypatch.setattr(db, "PING_AFTER_IDLE_S", 0.0)  # as if it had been idle a while
    for _ in range(2):  # both pooled connections: the dropped one is replaced, not used
        with engine.connect() as connection:
            assert connection.execute(text("SELECT 1")).scalar_one() == 1
