"""Photos per minute of batch pre-annotation on Ray against the in-process import:
`make bench-batch`.

    python benchmarks/bench_batch.py [--rooms 12] [--seed 600] [--workers 1 2]

Synthetic rooms (`holiscene synth`, given boxes and intrinsics) are imported into a fresh
data directory per run, each command timed whole as a person runs it (Python and Ray start-up
included):

- `holiscene import ROOMS`: each photo stored and run through the pipeline in this process,
  one after another (the pipeline's numpy and OpenCV use both cores);
- `holiscene import ROOMS --no-pipeline`, then `holiscene batch --workers N`: the photos
  stored, then the pipeline on a local Ray of N workers (one thread each);
- `holiscene import ROOMS --run-pipeline --workers N`: both in one command.

Also timed: a local Ray started and stopped with nothing to run, the fixed cost in every
batch. Every run must end with each scene holding a pipeline result.
"""

from __future__ import annotations

import argparse
import sqlite3
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HOLISCENE = [sys.executable, "-m", "holiscene.cli"]
RAY_ALONE = (
    "from holiscene.services.batch import ray_runtime\nwith ray_runtime(None, 2):\n    pass\n"
)


def timed(*command: str) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, text=True)
    return time.perf_counter() - start


def pipeline_results(data: Path) -> int:
    """Scenes with a pipeline revision in the store (each run must have them all)."""
    with sqlite3.connect(data / "holiscene.db") as db:
        query = "SELECT COUNT(DISTINCT scene_id) FROM revisions WHERE kind = 'pipeline'"
        return int(db.execute(query).fetchone()[0])


def run(work: Path, label: str, steps: list[list[str]], rooms: int) -> tuple[str, list[float]]:
    """Each step's seconds on a fresh data directory; checks every room got its result."""
    data = work / f"data-{len(list(work.glob('data-*')))}"
    seconds = [timed(*HOLISCENE, *step, "--data-dir", str(data)) for step in steps]
    if pipeline_results(data) != rooms:
        raise SystemExit(f"{label}: {pipeline_results(data)} of {rooms} scenes have a result")
    return label, seconds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rooms", type=int, default=12)
    parser.add_argument("--seed", type=int, default=600)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-batch-") as tmp:
        work = Path(tmp)
        synth = ["synth", "--seed", str(args.seed), "--count", str(args.rooms)]
        subprocess.run([*HOLISCENE, *synth, "-o", str(work / "rooms")], check=True)
        rooms = [str(p) for p in sorted((work / "rooms").iterdir())]
        ray_alone = timed(sys.executable, "-c", RAY_ALONE)
        rows = [run(work, "holiscene import (in process)", [["import", *rooms]], len(rooms))]
        for n in args.workers:
            steps = [["import", *rooms, "--no-pipeline"], ["batch", "--workers", str(n)]]
            rows.append(run(work, f"import --no-pipeline + batch --workers {n}", steps, len(rooms)))
        for n in args.workers:
            step = ["import", *rooms, "--run-pipeline", "--workers", str(n)]
            rows.append(run(work, f"import --run-pipeline --workers {n}", [step], len(rooms)))
    print(
        f"\n{len(rooms)} synthetic rooms from seed {args.seed}; local Ray up and down: "
        f"{ray_alone:.1f} s\n"
    )
    print(f"| {'command':<42} | {'seconds':>12} | photos/min | of the last step |")
    print(f"| {'-' * 42} | {'-' * 12} | ---------- | ---------------- |")
    for label, seconds in rows:
        parts = " + ".join(f"{s:.1f}" for s in seconds)
        whole, last = len(rooms) / sum(seconds) * 60, len(rooms) / seconds[-1] * 60
        print(f"| {label:<42} | {parts:>12} | {whole:10.1f} | {last:16.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
