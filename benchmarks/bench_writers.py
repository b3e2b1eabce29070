"""Save latency with many annotators at once, on SQLite and on PostgreSQL: `make bench-writers`.

    python benchmarks/bench_writers.py [--writers 20] [--scenes 10] [--saves 10] [--pause-ms 500]

Each database on a fresh data folder: one writer alone, then `--writers` writers saving at once
through the HTTP API (holiscene.testing.concurrent_writers: real threads, one app; writers
share scenes, so some saves conflict and are retried with the revision the 409 names), first
back to back, then with a pause of `--pause-ms` on average between a writer's saves (a person
looks at the result before the next edit; 20 writers then still save 40 times a second).
Figures: p50 and p95 of the requests that saved, and the CPU per request in the app's worker
threads, in its event loop and in the rest of the process (the writers). SQLite is a file in
a temporary folder; PostgreSQL a scratch server with its default, durable settings (fsync and
synchronous commit on). Every save is checked in the history too.

Target (issue 20): p95 <= 100 ms at 20 writers on PostgreSQL, checked on the paced run (exit
status 1 when missed or when a history is wrong). Back to back, 20 writers keep the 2 cores
busy: each save costs CPU in the one process that runs the app and the writers, so latency
there is about writers x CPU per save / cores, whatever the database.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import threading
import time
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


def cpu_per_request(before: dict[str, float], run: WriterRun) -> str:
    """Milliseconds of CPU per request of the run (saves and the conflicts sent again), by
    part: the app's worker threads, its event loop, and the rest (the writers, the test
    client's work in them)."""
    after = cpu_of_threads()
    ms = {part: (after[part] - before[part]) * 1000 / run.requests for part in before}
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
        # The loopback address the server answers to by default (not TestClient's own name).
        app = create_app(settings)
        with TestClient(app, base_url=f"http://{settings.host}:{settings.port}") as client:
            alone, crowd, paced = (
                import_scenes(client, count) for count in (1, args.scenes, args.scenes)
            )
            runs = []
            for scenes, writers, pause_s in (
                (alone, 1, 0.0),
                (crowd, args.writers, 0.0),
                (paced, args.writers, args.pause_ms / 1000),
            ):
                before = cpu_of_threads()
                run = run_writers(client, scenes, writers, args.saves, pause_s)
                print(f"  {run.describe()}\n    {cpu_per_request(before, run)}")
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
    p95 = results["PostgreSQL"][2].p95
    met = p95 <= TARGET_P95_MS
    print(
        f"target p95 <= {TARGET_P95_MS:.0f} ms on PostgreSQL, paced: {'met' if met else 'MISSED'}"
    )
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
