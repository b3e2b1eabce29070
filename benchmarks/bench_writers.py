"""Save latency with many annotators at once, on SQLite and on PostgreSQL: `make bench-writers`.

    python benchmarks/bench_writers.py [--writers 20] [--scenes 10] [--saves 10]

Each database first with one writer alone, then with `--writers` writers saving at once
through the HTTP API (holiscene.testing.concurrent_writers: real threads, one app; writers
share scenes, so some saves conflict and are retried). Figures: p50 and p95 of the requests
that saved. SQLite is a file in a temporary folder; PostgreSQL a scratch server with its
default, durable settings (fsync and synchronous commit on). Every save is checked in the
history too. Target (issue 20): p95 <= 100 ms at 20 writers on PostgreSQL; the exit status is
1 when it is missed or a history is wrong.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
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


def measure(database_url: str | None, args: argparse.Namespace) -> tuple[WriterRun, WriterRun]:
    """(one writer alone, all writers at once) on a fresh data folder and database."""
    with tempfile.TemporaryDirectory(prefix="bench-writers-") as folder:
        settings = Settings(
            data_dir=Path(folder) / "data", web_dir=Path(folder) / "web", database_url=database_url
        )
        # The loopback address the server answers to by default (not TestClient's own name).
        app = create_app(settings)
        with TestClient(app, base_url=f"http://{settings.host}:{settings.port}") as client:
            *shared, own = import_scenes(client, args.scenes + 1)
            runs = (
                run_writers(client, [own], 1, args.saves),
                run_writers(client, shared, args.writers, args.saves),
            )
            for run in runs:
                problems = history_problems(client, run)
                if problems:
                    sys.exit("wrong history: " + "; ".join(problems[:5]))
    return runs


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--writers", type=int, default=20)
    parser.add_argument("--scenes", type=int, default=10)
    parser.add_argument("--saves", type=int, default=10, help="saves per writer")
    args = parser.parse_args()

    results: dict[str, tuple[WriterRun, WriterRun]] = {"SQLite": measure(None, args)}
    with ScratchPostgres(durable=True) as postgres:
        database = postgres.create_database()
        results["PostgreSQL"] = measure(postgres.url(database), args)

    print(f"{args.writers} writers on {args.scenes} scenes, {args.saves} saves each")
    print(f"{'database':<12} {'alone p50/p95 ms':>17} {'all p50/p95 ms':>15} {'conflicts':>10}")
    for name, (alone, crowd) in results.items():
        print(
            f"{name:<12} {alone.p50:>8.0f}/{alone.p95:<8.0f} {crowd.p50:>7.0f}/{crowd.p95:<7.0f}"
            f" {crowd.conflicts:>10}"
        )
    p95 = results["PostgreSQL"][1].p95
    verdict = "met" if p95 <= TARGET_P95_MS else "MISSED"
    print(f"target p95 <= {TARGET_P95_MS:.0f} ms on PostgreSQL: {verdict} ({p95:.0f} ms)")
    return 0 if p95 <= TARGET_P95_MS else 1


if __name__ == "__main__":
    sys.exit(main())
