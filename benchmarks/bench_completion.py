"""Completed shapes against the library fit and the raw depth points: `make bench-completion`.

    python benchmarks/bench_completion.py [--seed 900000] [--count 12] [--out DIR]

Held-out synthetic rooms (`holiscene synth`, seeds no training uses; given boxes, intrinsics
and depth) go through `holiscene infer` twice: the default pipeline (with `shape_completion`)
and the same stages without it (every object keeps its library fit). Both are scored by
`evaluation.shape_eval` (Chamfer, EMD approximation, normal consistency against the true
meshes, in the true box's frame with its longest side 1), over all objects and over the
objects that got a completed mesh, where the three candidates are compared on the same objects.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from holiscene.evaluation.shape_eval import ShapeEvaluation
from holiscene.pipeline.runner import DEFAULT_STAGES

HOLISCENE = [sys.executable, "-m", "holiscene.cli"]
WITHOUT_COMPLETION = ",".join(s for s in DEFAULT_STAGES if s != "shape_completion")


def infer_all(rooms: list[Path], out: Path, stages: str | None) -> tuple[ShapeEvaluation, float]:
    evaluation = ShapeEvaluation()
    seconds = 0.0
    for room in rooms:
        command = [*HOLISCENE, "infer", str(room), "-o", str(out / room.name)]
        if stages is not None:
            command += ["--stages", stages]
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, text=True)
        seconds += time.perf_counter() - start
        evaluation.add_folder(out / room.name, room)
    return evaluation, seconds / len(rooms)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seed", type=int, default=900_000)
    parser.add_argument("--count", type=int, default=12)
    parser.add_argument("--out", type=Path, help="keep the rooms and predictions here")
    args = parser.parse_args()
    work = args.out or Path(tempfile.mkdtemp(prefix="bench-completion-"))
    synth = [*HOLISCENE, "synth", "--seed", str(args.seed), "--count", str(args.count)]
    subprocess.run([*synth, "-o", str(work / "gt"), "--workers", "1"], check=True)
    rooms = sorted((work / "gt").glob("synth-*"))
    completed, completed_s = infer_all(rooms, work / "with_completion", None)
    library, library_s = infer_all(rooms, work / "library_only", WITHOUT_COMPLETION)
    keys = {k for k, row in completed.records.items() if "completion" in row}
    paired = {
        "completion": completed.summary(keys).get("completion"),
        "library fit": library.summary(keys).get("builtin"),
        "partial points": library.summary(keys).get("partial_points"),
    }
    result = {
        "rooms": len(rooms),
        "objects": len(completed.records),
        "completed_objects": len(keys),
        "infer_seconds_per_photo": {"with_completion": completed_s, "library_only": library_s},
        "on_completed_objects": paired,
        "all_objects_library_only": library.summary(),
    }
    print(json.dumps(result, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
