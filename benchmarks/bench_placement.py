"""Metrology -> placement -> model fitting on 20 synthetic scenes (seeds 7000-7019).

    python benchmarks/bench_placement.py [--seeds N] [--first-seed S]

An oracle stands in for the stages before these: the true 2D boxes and classes, the true
masks (then, in a second pass, the filled 2D boxes as masks), the true supports, and the true
camera and room layout (vanishing points from them). Prints the 3D detection mAP at 3D IoU
0.15, the mean 3D IoU with the true boxes, the heights' error, and seconds per scene of
heights_by_metrology + placement + shapes_fit (the GLB is not written).
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
from holiscene.evaluation.box_iou import iou_3d
from holiscene.evaluation.metrics import Evaluation
from holiscene.geometry.boxes import box_corners
from holiscene.pipeline.stages.metrology import HeightsByMetrology
from holiscene.pipeline.stages.placement import PlacementStage
from holiscene.pipeline.stages.shapes_fit import ShapesFit
from holiscene.placement.oracle import MaskKind, context_from_truth
from holiscene.synth.generate import SyntheticScene, synthesize

FIRST_SEED = 7000  # never used by the tests (they use 3000-3010)


def run(scenes: list[SyntheticScene], masks: MaskKind) -> None:
    stages = [HeightsByMetrology(), PlacementStage(), ShapesFit()]
    evaluation = Evaluation()
    ious: list[float] = []
    height_errors: list[float] = []
    seconds: list[float] = []
    for synthetic in scenes:
        ctx = context_from_truth(synthetic, masks)
        start = time.perf_counter()
        for stage in stages:
            stage.run(ctx)
        seconds.append(time.perf_counter() - start)
        assert ctx.boxes_3d is not None and ctx.heights is not None
        objects = []
        for obj in synthetic.truth.objects:
            assert obj.corners_3d is not None and obj.box_3d is not None
            box = ctx.boxes_3d.get(obj.id)
            corners = (
                None
                if box is None
                else box_corners(np.array(box.center), np.array(box.size), box.yaw_deg)
            )
            ious.append(0.0 if corners is None else iou_3d(corners, np.array(obj.corners_3d)))
            height_errors.append(abs(ctx.heights[obj.id] / obj.box_3d.size[1] - 1.0))
            objects.append(
                obj.model_copy(
                    update={
                        "box_3d": box,
                        "corners_3d": None if corners is None else corners.tolist(),
                    }
                )
            )
        evaluation.add(synthetic.truth.model_copy(update={"objects": objects}), synthetic.truth)
    summary = evaluation.summary()
    detection = summary["detection_3d"]
    errors = np.array(height_errors)
    print(
        f"masks={masks:5s} scenes={len(scenes)} objects={len(ious)} "
        f"mAP@0.15={100 * detection['map']:.1f} mean3DIoU={np.mean(ious):.3f} "
        f"IoU>=0.15={100 * np.mean(np.array(ious) >= 0.15):.0f}% "
        f"height error median={100 * np.median(errors):.1f}% "
        f"within10%={100 * np.mean(errors <= 0.1):.0f}% "
        f"s/scene mean={statistics.mean(seconds):.2f} max={max(seconds):.2f}"
    )
    per_class = ", ".join(f"{c} {100 * ap:.0f}" for c, ap in detection["ap_per_class"].items())
    print(f"  AP per class: {per_class}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--first-seed", type=int, default=FIRST_SEED)
    args = parser.parse_args()
    print(
        "oracle inputs: true 2D boxes + classes, masks, supports, camera and layout "
        "(vanishing points from them); stages timed: heights_by_metrology, placement, shapes_fit"
    )
    scenes = [synthesize(seed) for seed in range(args.first_seed, args.first_seed + args.seeds)]
    run(scenes, "truth")
    run(scenes, "box")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
