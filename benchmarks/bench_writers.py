"""Save latency with many annotators at once, on SQLite and on PostgreSQL: `make bench-writers`.

    python benchmarks/bench_writers.py [--writers 20] [--scenes 10] [--saves 10] [--pause-ms 500]
                                       [--in-process]

Each database on a fresh data folder, served by `holiscene serve` on a loopback port (as
deployed: the writers, like browsers, are in another process): one writer alone, then
`--writers` writers saving at once through the HTTP API (holiscene.testing.concurrent_writers:
real threads; writers share scenes, so some saves conflict and are retried with the revision
the 409 names), first back to back, then pausing `--pause-ms` on average before each save (a
person looks at the result before the next edit; 20 writers then still save 40 times a
second). Figures: p50 and p95 of the requests that saved, and the server's CPU per request.
`--in-process` runs the app in this process instead (a TestClient) and splits the CPU per
request between the app's worker threads, its event loop and the rest (the writers). SQLite is
a file in a temporary folder; PostgreSQL a scratch server with its default, durable settings
(fsync and synchronous commit on). Every save is checked in the history too.

Target (issue 20): p95 <= 100 ms at 20 writers on PostgreSQL, back to back and paced (exit
status 1 when one is missed or when a history is wrong).
"""

from __future__ import annotations

import argparse
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from holiscene.testing.concurrent_writers import (
    WriterRun,
    history_problems,
    import_scenes,
    run_writers,
)
from holiscene.testing.scratch_postgres import ScratchPostgres
from httpx2 import Client, HTTPError, Limits

TARGET_P95_MS = 100.0


def cpu_of_threads() -> dict[str, float]:
    """Seconds of CPU so far of the whole process and of the app's threads: its worker threads
    (the routes' own work) and its event loop (the test client's portal thread, where FastAPI
    routes each request). Threads that ended (the writers) count in the process only."""
    parts = {"process": time.process_time(), "app's worker threads": 0.0, "event loop": 0.0}
    for thread in threading.enumerate():
        if "portal" in thread.name:
            part = "event loop"
        elif "worker" in thread.name.lower() and "writer" not in thread.name:
            part = "app's worker threads"
        else:
            continue
        if thread.ident is not None and thread.is_alive():
            parts[part] += time.clock_gettime(time.pthread_getcpuclockid(thread.ident))
    return parts


def server_cpu(pid: int) -> float:
    """Seconds of CPU the server process has used (user and system, from /proc)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


@contextmanager
def served(settings: Settings) -> Iterator[tuple[Client, Callable[[], dict[str, float]]]]:
    """`holiscene serve` on the settings' data folder and database, on a free loopback port:
    an HTTP client for it, and the server's CPU so far."""
    port = free_port()
    command = [str(Path(sys.executable).parent / "holiscene"), "serve", "--port", str(port)]
    command += ["--data-dir", str(settings.data_dir)]
    if settings.database_url:
        command += ["--database-url", settings.database_url]
    # Its log (a line per request) goes to a file: a pipe nobody reads would fill and stop it.
    log_path = settings.data_dir.parent / "serve.log"
    with log_path.open("wb") as log:
        server = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
    limits = Limits(max_connections=64, max_keepalive_connections=64)
    try:
        with Client(base_url=f"http://127.0.0.1:{port}", limits=limits, timeout=60) as client:
            for _ in range(300):
                if server.poll() is not None:
                    error = log_path.read_text(errors="replace")
                    sys.exit(f"holiscene serve stopped: {error[-2000:]}")
                try:
                    client.get("/api/health")
                    break
                except HTTPError:
                    time.sleep(0.1)
            yield client, lambda: {"process": server_cpu(server.pid)}
    finally:
        server.terminate()
        server.wait(30)


@contextmanager
def in_process(settings: Settings) -> Iterator[tuple[Client, Callable[[], dict[str, float]]]]:
    """The app in this process (a TestClient), and the CPU of its threads so far."""
    # The loopback address the server answers to by default (not TestClient's own name).
    base_url = f"http://{settings.host}:{settings.port}"
    with TestClient(create_app(settings), base_url=base_url) as client:
        yield client, cpu_of_threads


def cpu_per_request(before: dict[str, float], after: dict[str, float], run: WriterRun) -> str:
    """Milliseconds of CPU per request of the run (saves and the conflicts sent again): the
    server's, or in process by part (the app's worker threads, its event loop, and the rest:
    the writers, the test client's work in them)."""
    ms = {part: (after[part] - before[part]) * 1000 / run.requests for part in before}
    if len(ms) == 1:
        return f"server {ms['process']:.1f} ms CPU per request"
    rest = ms.pop("process") - sum(ms.values())
    split = ", ".join(f"{part} {value:.1f}" for part, value in ms.items())
    return f"{split}, writers and the rest {rest:.1f} ms CPU per request"


def measure(database_url: str | None, args: argparse.Namespace) -> list[WriterRun]:
    """[one writer alone, all writers back to back, all writers with pauses], each on scenes
    of its own."""
    with tempfile.TemporaryDirectory(prefix="bench-writers-") as folder:
        settings = Settings(
            data_dir=Path(folder) / "data", web_dir=Path(folder) / "web", database_url=database_url
        )
        server = in_process if args.in_process else served
        with server(settings) as (client, cpu):
            alone, crowd, paced = (
                import_scenes(client, count) for count in (1, args.scenes, args.scenes)
            )
            runs = []
            for scenes, writers, pause_s in (
                (alone, 1, 0.0),
                (crowd, args.writers, 0.0),
                (paced, args.writers, args.pause_ms / 1000),
            ):
                before = cpu()
                run = run_writers(client, scenes, writers, args.saves, pause_s)
                print(f"  {run.describe()}\n    {cpu_per_request(before, cpu(), run)}")
                problems = history_problems(client, run)
                if problems:
                    sys.exit("wrong history: " + "; ".join(problems[:5]))
                runs.append(run)
    return runs


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--writers", type=int, default=20)
    parser.add_argument("--scenes", type=int, default=10)
    parser.add_argument("--saves", type=int, default=10, help="saves per writer")
    parser.add_argument("--pause-ms", type=float, default=500.0)
    parser.add_argument(
        "--in-process", action="store_true", help="the app in this process, CPU by thread"
    )
    args = parser.parse_args()

    print("SQLite")
    results = {"SQLite": measure(None, args)}
    with ScratchPostgres(durable=True) as postgres:
        print("PostgreSQL")
        results["PostgreSQL"] = measure(postgres.url(postgres.create_database()), args)

    print(f"\n{args.writers} writers on {args.scenes} scenes, {args.saves} saves each")
    print("database     alone p50/p95  back to back p50/p95  paced p50/p95 (ms)")
    for name, (alone, crowd, paced) in results.items():
        print(
            f"{name:<12} {alone.p50:>5.0f}/{alone.p95:<7.0f} {crowd.p50:>12.0f}/{crowd.p95:<8.0f}"
            f" {paced.p50:>6.0f}/{paced.p95:.0f}"
        )
    _, crowd, paced = results["PostgreSQL"]
    missed = [
        name for name, run in (("back to back", crowd), ("paced", paced)) if run.p95 > TARGET_P95_MS
    ]
    verdict = "met" if not missed else "MISSED " + " and ".join(missed)
    print(f"target p95 <= {TARGET_P95_MS:.0f} ms on PostgreSQL, back to back and paced: {verdict}")
    return 0 if not missed else 1


if __name__ == "__main__":
    sys.exit(main())
