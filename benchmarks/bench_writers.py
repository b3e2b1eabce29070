"""Save latency with many annotators at once, on SQLite and on PostgreSQL: `make bench-writers`.

    python benchmarks/bench_writers.py [--writers 20] [--scenes 10] [--saves 10] [--pause-ms 500]

Each database on a fresh data folder: one writer alone, then `--writers` writers saving at once
through the HTTP API (holiscene.testing.concurrent_writers: real threads, one app; writers
share scenes, so some saves conflict and are retried with the revision the 409 names), first
back to back, then with a pause of `--pause-ms` on average between a writer's saves (a person
looks at the result before the next edit; 20 writers then still save 40 times a second).
Figures: p50 and p95 of the requests that saved. SQLite is a file in a temporary folder;
PostgreSQL a scratch server with its default, durable settings (fsync and synchronous commit
on). Every save is checked in the history too.

Target (issue 20): p95 <= 100 ms at 20 writers on PostgreSQL, checked on the paced run (exit
status 1 when missed or when a history is wrong). Back to back, 20 writers keep the 2 cores
busy: each save costs CPU in the one process that runs the app and the writers, so latency
there is about writers x CPU per save / cores, whatever the database.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
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
            began = time.process_time()
            first = run_writers(client, alone, 1, args.saves)
            cpu_ms = (time.process_time() - began) * 1000 / len(first.save_ms)
            print(f"  alone: {cpu_ms:.1f} ms CPU per save (app and writer, one process)")
            runs = [
                first,
                run_writers(client, crowd, args.writers, args.saves),
                run_writers(client, paced, args.writers, args.saves, args.pause_ms / 1000),
            ]
            for run in runs:
                print(f"  {run.describe()}")
                problems = history_problems(client, run)
                if problems:
                    sys.exit("wrong history: " + "; ".join(problems[:5]))
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
