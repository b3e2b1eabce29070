"""Where the layout's IoU goes: `make bench-layout` (20 synthetic scenes from seed 7000).

For each scene, runs the layout stage's parts (Manhattan frame, Surface Network, room search,
metric scale) and compares each part with the truth: the scale's error, each wall's distance
error (in camera heights), and the layout IoU when that one part is replaced by the truth.
The part whose replacement gains most is where work pays. Two more rows bound what reading
the photo better can give: the parts the photo shows (the faces of the true room in view) made
true, and those with the true scale too (the parts out of view keep their size in metres).
A last set of columns asks whether reading the objects better could help the scale: the
scale fused from measurements whose only error is each object's true size against its class's
typical size (the limit of class-size priors), the IoU with it, and the IoU with it and the
parts in view true: the best class sizes allow for the scale, however well the photo is read,
while the parts out of view stay as estimated (in metres).
Prints a row per scene and means; `--plot FILE` draws the means as a bar chart
(docs/img/layout_parts.png, shown in docs/benchmarks.md).

`--depth` asks the same of the RGB-D path (`layout_from_depth`, the scale exact): each face
made true, the faces of the true room in view that no plane was fitted to made true (what a
better reading of the depth could gain), the side walls whose true plane lies within 0.2 m of
the farthest point the depth shows made true (walls hidden right behind furniture), and the
share of rooms whose ceiling, left and right walls were fitted, or were in view at all.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from holiscene.evaluation.box_iou import iou_3d, iou_3d_in_view
from holiscene.geometry.camera import FloatArray, PinholeCamera
from holiscene.geometry.depth_points import point_grid
from holiscene.geometry.depth_room import points_reach
from holiscene.geometry.manhattan import room_directions
from holiscene.geometry.metric_scale import (
    Measurement,
    default_calibration,
    fuse,
    object_measurements,
    room_priors,
)
from holiscene.geometry.room_layout import RoomHypothesis
from holiscene.geometry.surface_labels import map_pixels
from holiscene.geometry.surface_map import load_surface_model
from holiscene.inputs import read_input_folder
from holiscene.knowledge.object_sizes import middle_size, mounting_height
from holiscene.pipeline import SceneContext, build_pipeline
from holiscene.pipeline.base import required
from holiscene.pipeline.stages.depth_layout import GRID_STEP_PX
from holiscene.pipeline.stages.layout import LayoutEstimate, estimate_layout
from holiscene.placement.room import room_of
from holiscene_schema import SceneObject

PARTS = ("front", "left", "right", "back", "ceiling")


def size_off_typical(
    kind: Measurement, obj: SceneObject, truth_obj: dict[str, Any], true_height: float
) -> float:
    """log(typical / true) of the size a measurement of `kind` reads: what even an exact
    measurement of the object would get wrong about the scale."""
    depth, height, width = truth_obj["box_3d"]["size"]
    typical_depth, typical_height, typical_width = middle_size(obj.cls)
    if kind == "height":
        return math.log(typical_height / height)
    if kind == "width":
        return math.log(max(typical_depth, typical_width) / max(depth, width))
    typical_bottom = mounting_height(obj.cls)
    assert typical_bottom is not None, f"{obj.cls} is measured on a wall but has no mounting"
    bottom = truth_obj["box_3d"]["center"][1] - height / 2 + true_height  # above the floor
    return math.log(typical_bottom / bottom)


def scale_at_class_size_limit(
    estimate: LayoutEstimate, truth: dict[str, Any], image_width: int, rays_room: FloatArray
) -> float:
    """The camera height fused from the same priors and measurements as the estimate, each
    measurement exact but for its object's size (and the priors off by the truth's own camera
    and room heights and front wall distance), with the same weights: the best the class-size
    priors can do for this photo. `rays_room` are the photo's rays (which walls it shows)."""
    true_height = truth["camera"]["height_m"]
    corners = np.array(truth["layout"]["corners_3d"])
    ceiling = front = None
    if estimate.room.ceiling_seen:  # seen exactly: the room's own height above the camera
        ceiling = float(corners[:, 1].max() - corners[:, 1].min()) / true_height - 1.0
    if "front" in estimate.room.faces_in_view(rays_room):
        front = RoomHypothesis.enclosing(corners @ estimate.to_room / true_height).front
    logs = room_priors(ceiling, front)
    truth_by_box = {tuple(o["bbox"]): o for o in truth["objects"]}
    calibration = default_calibration()
    measured = object_measurements(
        estimate.camera, estimate.contacts, estimate.mounted, image_width
    )
    for obj, kind, _ in measured:
        error = calibration.measurement_error(kind, obj.cls)
        truth_obj = truth_by_box.get(tuple(obj.bbox))
        if error is None or truth_obj is None:
            continue
        off = size_off_typical(kind, obj, truth_obj, true_height)
        logs.append((math.log(true_height) + off, error[1]))
    return fuse(logs)[0]


def scene_parts(folder: Path) -> dict[str, float]:
    inputs = read_input_folder(folder, use_depth=False)  # the single-photo path
    truth = json.loads((folder / "gt.json").read_text())
    ctx = SceneContext(image=inputs.photo.rgb, given_K=inputs.K, detections=inputs.detections)
    build_pipeline(["objects_from_detections", "intrinsics"]).run(ctx)
    K, _ = required(ctx.intrinsics, "intrinsics")
    estimate = estimate_layout(ctx.image, K, required(ctx.objects, "objects"), load_surface_model())
    if estimate is None:
        return {}
    room, to_room, metres = estimate.room, estimate.to_room, estimate.metres

    true_corners = np.array(truth["layout"]["corners_3d"])
    true_height = truth["camera"]["height_m"]
    truth_room = RoomHypothesis.enclosing(true_corners @ to_room / true_height)
    true_room = {part: getattr(truth_room, part) for part in PARTS}

    def iou(hypothesis: RoomHypothesis, scale: float) -> float:
        return iou_3d(hypothesis.corners_room() @ to_room.T * scale, true_corners)

    row = {
        "iou": iou(room, metres),
        "scale_error": abs(metres / true_height - 1),
        "iou_true_scale": iou(room, true_height),
    }
    for part in PARTS:
        row[f"{part}_error"] = abs(getattr(room, part) / true_room[part] - 1)
        row[f"iou_true_{part}"] = iou(replace(room, **{part: true_room[part]}), metres)
    row["iou_all_walls_true"] = iou(replace(room, **true_room), metres)

    # The parts whose faces the photo shows (on the true room).
    rays = estimate.camera.ray(map_pixels(ctx.width, ctx.height)) @ to_room
    faces_seen = replace(room, **true_room).faces_in_view(rays)
    in_view = [part for part in ("front", "left", "right", "ceiling") if part in faces_seen]
    seen_true = replace(room, **{part: true_room[part] for part in in_view})
    row["iou_parts_in_view_true"] = iou(seen_true, metres)

    def rescaled(scale: float) -> RoomHypothesis:
        """`seen_true` for a camera `scale` metres high, the parts out of view keeping their
        size in metres (they come from priors in metres)."""
        ratio = metres / scale
        out_of_view = {
            p: getattr(room, p) * ratio for p in PARTS if p not in in_view and p != "ceiling"
        }
        if "ceiling" not in in_view:
            out_of_view["ceiling"] = (room.ceiling + 1.0) * ratio - 1.0
        return replace(seen_true, **out_of_view)

    # ... and the true scale.
    row["iou_in_view_and_scale_true"] = iou(rescaled(true_height), true_height)

    camera = truth["camera"]
    view = PinholeCamera(np.array(camera["K"]), camera["pitch_deg"], camera["roll_deg"])
    size = (ctx.width, ctx.height)
    row["iou_in_view"] = iou_3d_in_view(estimate.corners_world(), true_corners, view, size)
    limit = scale_at_class_size_limit(estimate, truth, ctx.width, rays)
    row["limit_scale_error"] = abs(limit / true_height - 1)
    row["iou_limit_scale"] = iou(room, limit)
    # What class sizes allow at best: the photo read exactly, the scale at the limit.
    row["iou_in_view_true_limit_scale"] = iou(rescaled(limit), limit)
    return row


DEPTH_STAGES = ["objects_from_detections", "intrinsics", "layout_from_lines", "layout_from_depth"]
NEAR_REACH_M = 0.2


def depth_scene_parts(folder: Path) -> dict[str, float]:
    """The RGB-D path's layout against the truth, part by part (metres: the scale is exact)."""
    inputs = read_input_folder(folder)
    truth = json.loads((folder / "gt.json").read_text())
    depth = required(inputs.depth, "depth").metres
    ctx = SceneContext(
        image=inputs.photo.rgb, given_K=inputs.K, detections=inputs.detections, depth=depth
    )
    build_pipeline(DEPTH_STAGES).run(ctx)
    layout, camera = required(ctx.layout, "layout"), required(ctx.camera, "camera")
    report = ctx.reports.get("layout_from_depth", "")
    fitted = set(report.split("planes fitted: ")[-1].split(";")[0].split(", "))
    room_yaw = required(room_of(layout), "room").yaw_deg
    dirs = room_directions(room_yaw)
    to_room = np.column_stack([dirs[1], dirs[0], dirs[2]])
    estimate = RoomHypothesis.enclosing(np.array(layout.corners_3d) @ to_room)
    true_corners = np.array(truth["layout"]["corners_3d"])
    true_room = RoomHypothesis.enclosing(true_corners @ to_room)
    true_faces = {part: getattr(true_room, part) for part in PARTS}

    def iou(hypothesis: RoomHypothesis, floor: float) -> float:
        corners = hypothesis.corners_room()
        corners[:4, 1] = -floor  # enclosing() puts the floor at -1: metres here
        return iou_3d(corners @ to_room.T, true_corners)

    floor = -float((np.array(layout.corners_3d) @ to_room)[:, 1].min())
    row = {"iou": iou(estimate, floor)}
    for part in PARTS:
        row[f"iou_true_{part}"] = iou(replace(estimate, **{part: true_faces[part]}), floor)
    row["iou_all_walls_true"] = iou(replace(estimate, **true_faces), floor)
    K, _ = required(ctx.intrinsics, "intrinsics")
    view = PinholeCamera(
        np.asarray(K, dtype=float), camera.pitch_deg or 0.0, camera.roll_deg or 0.0
    )
    rays = view.ray(map_pixels(ctx.width, ctx.height)) @ to_room
    in_heights = RoomHypothesis.enclosing(true_corners @ to_room / truth["camera"]["height_m"])
    in_view = in_heights.faces_in_view(rays)
    unfitted_in_view = {
        p: true_faces[p] for p in ("left", "right", "ceiling") if p in in_view - fitted
    }
    row["iou_unfitted_in_view_true"] = iou(replace(estimate, **unfitted_in_view), floor)
    reach = points_reach(
        point_grid(depth, np.asarray(K, dtype=float), GRID_STEP_PX), view, room_yaw
    )
    hidden = {
        p: true_faces[p]
        for p in ("left", "right")
        if p not in fitted and abs(true_faces[p] - reach[p]) < NEAR_REACH_M
    }
    row["iou_hidden_behind_furniture_true"] = iou(replace(estimate, **hidden), floor)
    for part in ("left", "right", "ceiling"):
        row[f"{part}_fitted"] = float(part in fitted)
        row[f"{part}_in_view"] = float(part in in_view)
    return row


# The bars of the picture: (key of the row's means, label).
PLOT_BARS = (
    ("iou", "estimate"),
    ("iou_limit_scale", "scale at class-size limit"),
    ("iou_true_front", "front wall true"),
    ("iou_true_ceiling", "ceiling true"),
    ("iou_true_scale", "scale true"),
    ("iou_true_back", "back wall true"),
    ("iou_true_right", "right wall true"),
    ("iou_true_left", "left wall true"),
    ("iou_parts_in_view_true", "parts in view true"),
    ("iou_in_view_true_limit_scale", "in view true + scale at limit"),
    ("iou_all_walls_true", "all walls true"),
    ("iou_in_view_and_scale_true", "in view + scale true"),
)


def plot_means(means: dict[str, float], count: int, seed: int, path: Path) -> None:
    """A horizontal bar per row of PLOT_BARS, the estimate's IoU marked across them."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = [label for _, label in PLOT_BARS]
    values = [means[key] for key, _ in PLOT_BARS]
    fig, axis = plt.subplots(figsize=(7, 3.8), dpi=100)
    colours = ["tab:grey"] + ["tab:blue"] * (len(values) - 1)
    axis.barh(labels[::-1], values[::-1], color=colours[::-1])
    axis.axvline(means["iou"], color="black", linewidth=0.8)
    axis.axvline(0.75, color="tab:red", linestyle="--", linewidth=0.8, label="issue 4 target")
    for y, value in enumerate(values[::-1]):
        axis.text(value + 0.003, y, f"{value:.3f}", va="center", fontsize=8)
    axis.set_xlim(0.6, 0.9)
    axis.set_xlabel(f"mean layout 3D IoU, {count} synthetic scenes from seed {seed}")
    axis.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seed", type=int, default=7000)
    parser.add_argument("--count", type=int, default=20)
    parser.add_argument("--plot", type=Path, help="draw the means as a bar chart (PNG)")
    parser.add_argument("--depth", action="store_true", help="the RGB-D path's layout")
    args = parser.parse_args()
    parts = depth_scene_parts if args.depth else scene_parts
    with tempfile.TemporaryDirectory() as tmp:
        synth = ["synth", "--seed", str(args.seed), "--count", str(args.count), "-o", tmp]
        subprocess.run([sys.executable, "-m", "holiscene.cli", *synth], check=True)
        rows = {}
        for folder in sorted(p for p in Path(tmp).iterdir() if (p / "gt.json").is_file()):
            rows[folder.name] = parts(folder)
    keys = list(next(iter(rows.values())))
    print("scene        " + " ".join(f"{k:>18s}" for k in keys))
    for name, row in rows.items():
        print(f"{name:12s} " + " ".join(f"{row.get(k, float('nan')):18.3f}" for k in keys))
    means = {k: float(np.nanmean([r.get(k, np.nan) for r in rows.values()])) for k in keys}
    print("mean         " + " ".join(f"{means[k]:18.3f}" for k in keys))
    print(f"means over {len(rows)} rooms:")
    for key in keys:
        print(f"  {key:34s} {means[key]:.3f}")
    if args.plot and not args.depth:
        plot_means(means, len(rows), args.seed, args.plot)
        print(f"wrote {args.plot}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
