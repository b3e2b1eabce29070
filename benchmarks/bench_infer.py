"""Time `reconstruct_scene` on every real photo: `make bench` (or python benchmarks/bench_infer.py).
`--without-boxes` leaves each photo's detections.json out, so the detector makes the objects.

Prints one row per photo (objects, seconds, pitch/roll, 3D boxes placed) and a summary line.
The first run of each photo is timed; the pipeline holds no cache between photos.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import sys
import time

from holiscene.core.settings import REPO_ROOT
from holiscene.inputs import read_input_folder
from holiscene.services.reconstruction import reconstruct_scene

PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--without-boxes", action="store_true", help="the detector finds them")
    args = parser.parse_args(argv)
    folders = sorted(p for p in PHOTOS.iterdir() if (p / "detections.json").is_file())
    if not folders:
        print(f"no photos in {PHOTOS}", file=sys.stderr)
        return 1
    columns = ("photo", "size", "objects", "seconds", "pitch", "roll", "3D boxes")
    print("{:8s} {:>8s} {:>7s} {:>8s} {:>7s} {:>7s} {:>8s}".format(*columns))
    times = []
    for folder in folders:
        start = time.perf_counter()
        inputs = read_input_folder(folder)
        if args.without_boxes:
            inputs = dataclasses.replace(inputs, detections=None)
        scene = reconstruct_scene(inputs, name=folder.name, image_file="img.jpg").scene
        seconds = time.perf_counter() - start
        times.append(seconds)
        camera = scene.camera
        pitch = f"{camera.pitch_deg:.1f}" if camera and camera.pitch_deg is not None else "-"
        roll = f"{camera.roll_deg:.1f}" if camera and camera.roll_deg is not None else "-"
        placed = sum(o.box_3d is not None for o in scene.objects)
        size = f"{scene.image.width}x{scene.image.height}"
        boxes = f"{placed}/{len(scene.objects)}"
        row = (folder.name, size, len(scene.objects), seconds, pitch, roll, boxes)
        print("{:8s} {:>8s} {:7d} {:8.3f} {:>7s} {:>7s} {:>8s}".format(*row))
    print(
        f"photos={len(times)} mean={statistics.mean(times):.3f}s "
        f"max={max(times):.3f}s (holiscene infer, {len(times)} real photos, "
        f"{'objects from the detector' if args.without_boxes else 'boxes given'}, 2-core machine)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
