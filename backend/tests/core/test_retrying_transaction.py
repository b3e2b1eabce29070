"""retrying_transaction on a real PostgreSQL deadlock: two transactions lock two rows in
opposite orders; the server aborts one (40P01), and running it again lets both finish."""

from __future__ import annotations

import threading
from collections.abc import Iterator

import pytest
from holiscene.core.db import make_engine, retrying_transaction
from holiscene.testing.scratch_postgres import ScratchPostgres
from sqlalchemy import text
from sqlalchemy.exc import DBAPIError


def _crossing_writers(url: str, retry: bool) -> list[str]:
    """Two threads each update row a then b / b then a, meeting at a barrier in between."""
    engine = make_engine(url)
    with engine.begin() as connection:
        connection.execute(text("CREATE TABLE pair (name TEXT PRIMARY KEY, n INTEGER)"))
        connection.execute(text("INSERT INTO pair VALUES ('a', 0), ('b', 0)"))
    met = threading.Barrier(2, timeout=10)
    outcomes: list[str] = []

    def write(first: str, second: str) -> None:
        attempts = 0

        def work() -> None:
            nonlocal attempts
            attempts += 1
            with engine.begin() as connection:
                connection.execute(text(f"UPDATE pair SET n = n + 1 WHERE name = '{first}'"))
                if attempts == 1:  # only the first try meets the other in the middle
                    met.wait()
                connection.execute(text(f"UPDATE pair SET n = n + 1 WHERE name = '{second}'"))

        try:
            retrying_transaction(work) if retry else work()
            outcomes.append("done")
        except DBAPIError as error:
            outcomes.append(getattr(error.orig, "sqlstate", "?") or "?")

    threads = [threading.Thread(target=write, args=pair) for pair in (("a", "b"), ("b", "a"))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    with engine.connect() as connection:
        totals = connection.execute(text("SELECT n FROM pair ORDER BY name")).scalars().all()
    engine.dispose()
    return [*sorted(outcomes), f"total {sum(totals)}"]


@pytest.fixture()
def postgres_url(postgres_server: ScratchPostgres) -> Iterator[str]:
    """A new database on the session's scratch PostgreSQL (SQLite has one writer at a time:
    no deadlocks to retry)."""
    name = postgres_server.create_database()
    try:
        yield postgres_server.url(name)
    finally:
        postgres_server.drop_database(name)


def test_without_retrying_one_writer_loses_its_work(postgres_url: str) -> None:
    assert _crossing_writers(postgres_url, retry=False) == ["40P01", "done", "total 2"]


def test_a_deadlocked_transaction_runs_again(postgres_url: str) -> None:
    assert _crossing_writers(postgres_url, retry=True) == ["done", "done", "total 4"]
