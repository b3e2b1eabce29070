"""The database under the tests' servers: SQLite by default, and PostgreSQL as well for the
modules and tests marked `both_databases` (the store, workflow, concurrency and migration
tests), which then run once per database, as test[sqlite] and test[postgresql].

PostgreSQL is a scratch server for the whole session (holiscene.testing.scratch_postgres), with
a new empty database per test, dropped after it. Without PostgreSQL on the machine the
[postgresql] runs are skipped, saying why, or fail when HOLISCENE_REQUIRE_POSTGRES=1 (as
`make test` sets it, so CI cannot pass without them).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

import pytest
from holiscene.testing.scratch_postgres import PostgresUnavailableError, ScratchPostgres
from sqlalchemy import Engine

DATABASES = ("sqlite", "postgresql")
MARKER = "both_databases"


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", f"{MARKER}: run the test on SQLite and on a scratch PostgreSQL database"
    )


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    # database_url is in the closure of every test whose server comes from `settings`.
    if "database_url" in metafunc.fixturenames and metafunc.definition.get_closest_marker(MARKER):
        metafunc.parametrize("database_url", DATABASES, indirect=True)


@pytest.fixture(scope="session")
def postgres_server() -> Iterator[ScratchPostgres]:
    try:
        server = ScratchPostgres().start()
    except PostgresUnavailableError as missing:
        if os.environ.get("HOLISCENE_REQUIRE_POSTGRES") == "1":
            pytest.fail(f"HOLISCENE_REQUIRE_POSTGRES=1, but {missing}", pytrace=False)
        pytest.skip(f"no PostgreSQL run: {missing}")
    try:
        yield server
    finally:
        server.stop()


@pytest.fixture()
def database_url(request: pytest.FixtureRequest) -> Iterator[str | None]:
    """None: the default SQLite file in the data folder; else a new PostgreSQL database."""
    if getattr(request, "param", "sqlite") == "sqlite":
        yield None
        return
    server: ScratchPostgres = request.getfixturevalue("postgres_server")
    name = server.create_database()
    try:
        yield server.url(name)
    finally:
        server.drop_database(name)


@contextmanager
def writes_held(engine: Engine, table: str) -> Iterator[None]:
    """Writers to `table` wait until the block ends: on SQLite by holding its one write lock,
    on PostgreSQL by a lock on the table that every UPDATE waits for."""
    with engine.connect() as blocker:
        if engine.dialect.name == "sqlite":
            blocker.exec_driver_sql("BEGIN IMMEDIATE")
            yield
            blocker.exec_driver_sql("COMMIT")
        else:
            blocker.exec_driver_sql(f"LOCK TABLE {table} IN EXCLUSIVE MODE")
            yield
            blocker.commit()
