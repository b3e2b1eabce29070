"""The mesh network's meshes against the library fit, object by object, per class.

    python benchmarks/bench_meshes.py TRUTH LIBRARY_PRED LEARNED_PRED

TRUTH is a `holiscene synth` folder, LIBRARY_PRED and LEARNED_PRED two `holiscene infer`
outputs on it: one without the stage `shapes_by_mesh_net` (library fit), one with it. Both are
scored by `evaluation.shape_eval` in each mesh's own predicted box (the shape alone, not its
placement; longest side 1) and in the true box's frame. Prints, per class and over all
objects, the mean Chamfer distance of each, the mean paired difference with its standard
error, and the normal consistency.
"""

from __future__ import annotations

import argparse
import math
from collections import defaultdict
from pathlib import Path

import numpy as np
from holiscene.evaluation.shape_eval import ShapeEvaluation
from holiscene_schema import Scene

OWN_BOX = ", own box"


def _classes(truth: Path) -> dict[str, str]:
    """`<scene>/<object id>` -> class, as ShapeEvaluation keys its records."""
    classes: dict[str, str] = {}
    for room in sorted(truth.glob("*/gt.json")):
        scene = Scene.model_validate_json(room.read_text())
        classes.update({f"{scene.name}/{o.id}": o.cls for o in scene.objects})
    return classes


def _paired(rows: list[tuple[dict[str, float], dict[str, float]]]) -> str:
    library = np.array([a["chamfer"] for a, _ in rows])
    learned = np.array([b["chamfer"] for _, b in rows])
    difference = learned - library
    error = difference.std(ddof=1) / math.sqrt(len(rows)) if len(rows) > 1 else float("nan")
    normals = (
        np.mean([a["normal_consistency"] for a, _ in rows]),
        np.mean([b["normal_consistency"] for _, b in rows]),
    )
    return (
        f"{len(rows)} | {library.mean():.4f} | {learned.mean():.4f} | "
        f"{difference.mean():+.4f} ± {error:.4f} | {normals[0]:.3f} | {normals[1]:.3f}"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("truth", type=Path)
    parser.add_argument("library", type=Path, help="predictions without shapes_by_mesh_net")
    parser.add_argument("learned", type=Path, help="predictions with shapes_by_mesh_net")
    args = parser.parse_args()
    evaluation = ShapeEvaluation()
    for room in sorted(p.parent for p in args.truth.glob("*/gt.json")):
        for pred in (args.library, args.learned):
            if (pred / room.name).is_dir():
                evaluation.add_folder(pred / room.name, room)
    classes = _classes(args.truth)
    for frame in (OWN_BOX, ""):
        by_class: dict[str, list[tuple[dict[str, float], dict[str, float]]]] = defaultdict(list)
        for key, row in evaluation.records.items():
            pair = (row.get("builtin" + frame), row.get("learned" + frame))
            if pair[0] is not None and pair[1] is not None:
                by_class[classes[key]].append((pair[0], pair[1]))
        title = "each mesh in its own box" if frame else "in the true box's frame"
        print(f"\n{title}\n")
        print(
            "| class | objects | library fit | mesh network | difference ± s.e. | normals, library"
            " | normals, network |"
        )
        print("| --- | --- | --- | --- | --- | --- | --- |")
        for cls in sorted(by_class, key=lambda c: -len(by_class[c])):
            print(f"| {cls} | {_paired(by_class[cls])} |")
        every = [pair for rows in by_class.values() for pair in rows]
        print(f"| **all** | {_paired(every)} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
