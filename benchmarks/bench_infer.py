"""Time `infer_scene` on every real photo: `make bench` (or python benchmarks/bench_infer.py).

Prints one row per photo (objects, seconds, pitch/roll, 3D boxes placed) and a summary line.
The first run of each photo is timed; the pipeline holds no cache between photos.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

from holiscene.core.settings import REPO_ROOT
from holiscene.inference import infer_scene
from holiscene.inputs import read_input_folder

PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"


def main() -> int:
    folders = sorted(p for p in PHOTOS.iterdir() if (p / "detections.json").is_file())
    if not folders:
        print(f"no photos in {PHOTOS}", file=sys.stderr)
        return 1
    print(
        f"{'photo':8s} {'size':>8s} {'objects':>7s} {'seconds':>8s} {'pitch':>7s} {'roll':>7s} {'3D boxes':>8s}"
    )
    times = []
    for folder in folders:
        start = time.perf_counter()
        inputs = read_input_folder(folder)
        scene = infer_scene(inputs, name=folder.name, image_file="img.jpg").scene
        seconds = time.perf_counter() - start
        times.append(seconds)
        camera = scene.camera
        pitch = f"{camera.pitch_deg:.1f}" if camera and camera.pitch_deg is not None else "-"
        roll = f"{camera.roll_deg:.1f}" if camera and camera.roll_deg is not None else "-"
        placed = sum(o.box_3d is not None for o in scene.objects)
        size = f"{scene.image.width}x{scene.image.height}"
        print(
            f"{folder.name:8s} {size:>8s} {len(scene.objects):7d} {seconds:8.3f} {pitch:>7s} {roll:>7s} {placed:>4d}/{len(scene.objects):<3d}"
        )
    print(
        f"photos={len(times)} mean={statistics.mean(times):.3f}s "
        f"max={max(times):.3f}s (holiscene infer, {len(times)} real photos, 2-core machine)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
