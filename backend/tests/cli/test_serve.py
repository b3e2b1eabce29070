"""One server per data directory and per PostgreSQL database, with real `holiscene serve`
processes: a second server on a data directory (or a database) in use refuses to start, with
a clear message and a non-zero exit, before its start-up recovery could fail the running
server's jobs."""

from __future__ import annotations

import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from holiscene.core.db import make_engine
from holiscene.core.settings import Settings
from holiscene.store.jobs import JobStore
from holiscene.testing.scratch_postgres import ScratchPostgres


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port: int = probe.getsockname()[1]
        return port


def _serve(data_dir: Path, port: int, log: Path, *options: str) -> subprocess.Popen[bytes]:
    command = [sys.executable, "-m", "holiscene.cli", "serve", "--port", str(port), *options]
    # stdout and stderr to a file: an undrained pipe could fill up and stall the server.
    with log.open("wb") as out:
        return subprocess.Popen(
            [*command, "--data-dir", str(data_dir)], stdout=out, stderr=subprocess.STDOUT
        )


def _healthy(port: int) -> bool:
    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/api/health", timeout=2) as answer:
            return bool(answer.status == 200)
    except OSError:
        return False


@contextmanager
def _running(data_dir: Path, log: Path, *options: str) -> Iterator[tuple[int, int]]:
    """A server, up and answering: (its process id, its port)."""
    port = _free_port()
    server = _serve(data_dir, port, log, *options)
    try:
        deadline = time.monotonic() + 120
        while not _healthy(port):
            assert server.poll() is None, log.read_text()
            assert time.monotonic() < deadline, "the first server did not start"
            time.sleep(0.2)
        yield server.pid, port
    finally:
        server.terminate()
        server.wait(timeout=60)


def _refused(data_dir: Path, log: Path, *options: str) -> str:
    """Start a second server (on another port: nothing else stops it); it must exit non-zero.
    Returns what it said."""
    second = _serve(data_dir, _free_port(), log, *options)
    try:
        code = second.wait(timeout=120)
    finally:
        if second.poll() is None:
            second.kill()
            second.wait()
    message = log.read_text()
    assert code != 0, message
    return message


def _files(data_dir: Path) -> dict[str, tuple[int, int]]:
    """Every file but the database's own (the running server may touch those) by size and
    modification time."""
    return {
        str(p.relative_to(data_dir)): (p.stat().st_size, p.stat().st_mtime_ns)
        for p in sorted(data_dir.rglob("*"))
        if p.is_file() and not p.name.startswith("holiscene.db")
    }


def test_a_second_server_on_the_same_data_directory_refuses_and_touches_nothing(
    tmp_path: Path,
) -> None:
    data_dir = tmp_path / "data"
    with _running(data_dir, tmp_path / "first.log") as (first_pid, port):
        # A job the first server is running (as far as the database says): a second server's
        # start-up recovery would mark it failed.
        engine = make_engine(Settings(data_dir=data_dir).resolved_database_url)
        jobs = JobStore(engine)
        job = jobs.create_retrain()
        before = _files(data_dir)

        message = _refused(data_dir, tmp_path / "second.log")
        assert f"{data_dir} is in use by another holiscene server" in message, message
        assert f"process {first_pid}" in message, message

        assert jobs.get(job.id) == job  # still queued, no error
        assert _files(data_dir) == before
        assert _healthy(port)
        engine.dispose()


def test_a_second_server_on_the_same_postgresql_database_refuses(
    tmp_path: Path, postgres_server: ScratchPostgres
) -> None:
    """Another data directory, the same database: the data directory's lock cannot see it."""
    name = postgres_server.create_database()
    url = postgres_server.url(name)
    try:
        with _running(tmp_path / "first", tmp_path / "first.log", "--database-url", url) as (
            _,
            port,
        ):
            engine = make_engine(url)
            jobs = JobStore(engine)
            job = jobs.create_retrain()
            second = tmp_path / "second"
            message = _refused(second, tmp_path / "second.log", "--database-url", url)
            assert "is in use by another holiscene server" in message, message
            assert postgres_server.url(name) not in message  # no password shown
            assert jobs.get(job.id) == job
            assert _healthy(port)
            engine.dispose()
    finally:
        postgres_server.drop_database(name)
