"""Learn the per-class bias and spread of single-view size measurements (`make calibrate-scale`).

Renders synthetic rooms from seeds no test or benchmark uses (300000+), measures every
floor-standing object and every wall object the way the layout stage does (camera pitch, roll
and room from the photo, the object's box), compares with the true camera height and writes
`backend/src/holiscene/knowledge/scale_calibration.json`. The room search does not depend on
the calibration of wall objects, so measuring them with it is not circular.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

from holiscene.geometry.metric_scale import (
    CALIBRATION_FILE,
    Residual,
    fit_calibration,
    measurement_residuals,
)
from holiscene.geometry.surface_map import load_surface_model
from holiscene.inputs.validation import read_input_folder
from holiscene.pipeline import SceneContext, build_pipeline
from holiscene.pipeline.base import required
from holiscene.pipeline.stages.layout import estimate_layout
from tqdm import tqdm


def scene_residuals(folder: Path) -> Iterator[Residual]:
    inputs = read_input_folder(folder, use_depth=False)  # the single-photo path
    truth = json.loads((folder / "gt.json").read_text())
    ctx = SceneContext(image=inputs.photo.rgb, given_K=inputs.K, detections=inputs.detections)
    build_pipeline(["objects_from_detections", "intrinsics"]).run(ctx)
    K, _ = required(ctx.intrinsics, "intrinsics")
    estimate = estimate_layout(ctx.image, K, required(ctx.objects, "objects"), load_surface_model())
    if estimate is None:
        return
    yield from measurement_residuals(
        estimate.camera, estimate.contacts, estimate.mounted, truth["camera"]["height_m"], ctx.width
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seed", type=int, default=300000)
    parser.add_argument("--count", type=int, default=300)
    parser.add_argument("--scenes", type=Path, help="use these rendered scenes instead")
    parser.add_argument("-o", "--output", type=Path, default=CALIBRATION_FILE)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        scenes = args.scenes
        if scenes is None:
            scenes = Path(tmp) / "scenes"
            synth = ["synth", "--seed", str(args.seed), "--count", str(args.count)]
            subprocess.run(
                [sys.executable, "-m", "holiscene.cli", *synth, "-o", str(scenes)], check=True
            )
        folders = sorted(p for p in scenes.iterdir() if (p / "gt.json").is_file())
        if not folders:
            print(f"error: no synthetic scenes (gt.json) in {scenes}", file=sys.stderr)
            return 2
        residuals = [
            r for f in tqdm(folders, desc="measure", unit="scene") for r in scene_residuals(f)
        ]
    source = f"{len(folders)} synthetic scenes, seeds {args.seed}+ ({len(residuals)} measurements)"
    calibration = fit_calibration(residuals, source)
    args.output.write_text(calibration.to_json())
    for kind, classes in calibration.kinds.items():
        for cls, c in sorted(classes.items(), key=lambda kv: -kv[1].count):
            print(f"{kind:6s} {cls:14s} n={c.count:4d} bias={c.bias:+.3f} sd={c.sd:.3f}")
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
