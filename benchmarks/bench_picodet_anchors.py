"""Whether PicoDet's boxes are where the objects are, whatever its classes say.

For each given box, the best IoU of any of PicoDet's 3598 anchors' boxes (before its scores
and NMS choose among them): the share of given boxes some anchor meets at IoU 0.5 and 0.7,
on the real photos (../shared/data/real) and on held-out synthetic rooms. A high share means
a head that only names the anchors' boxes (`holiscene train-detector --on-picodet`) could find
those objects; docs/detector.md.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np
from bench_detector import add_photo_arguments, real_folders
from holiscene.learning.detector.data import BoxedPhoto, boxed_photo, synthetic_photos
from holiscene.learning.detector.picodet_taps import PicoDetTaps
from holiscene.learning.detector.runtime import (
    MODEL_FILE,
    PICODET_DETECTOR_DIR,
    box_iou,
    preprocess,
)
from holiscene_schema.detector_model import INPUT_SIZE

IOUS = (0.5, 0.7)


def best_ious(taps: PicoDetTaps, photos: list[BoxedPhoto]) -> np.ndarray:
    """Every given box's best IoU with an anchor's box, in photo pixels."""
    best: list[float] = []
    for photo in photos:
        height, width = photo.rgb.shape[:2]
        anchors = taps(preprocess(photo.rgb)).boxes * np.array([width, height] * 2) / INPUT_SIZE
        best.extend(float(box_iou(box, anchors).max()) for box in photo.boxes)
    return np.array(best)


def line(name: str, ious: np.ndarray) -> str:
    shares = " | ".join(f"{100 * float((ious >= t).mean()):.1f}" for t in IOUS)
    return f"| {name} | {len(ious)} | {shares} | {float(np.median(ious)):.2f} |"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_photo_arguments(parser)
    args = parser.parse_args(argv)
    taps = PicoDetTaps(PICODET_DETECTOR_DIR / MODEL_FILE)
    folders = real_folders(args.real)
    real = best_ious(taps, [boxed_photo(f) for f in folders])
    with tempfile.TemporaryDirectory(prefix="bench-anchors-") as scratch:
        seeds = range(args.synth_seed, args.synth_seed + args.synth_count)
        synthetic = best_ious(taps, synthetic_photos(seeds, Path(scratch)))
    print("| photos | given boxes | met at IoU 0.5 % | met at IoU 0.7 % | median best IoU |")
    print("| --- | --- | --- | --- | --- |")
    print(line(f"real ({len(folders)} photos)", real))
    print(line(f"synthetic ({args.synth_count} rooms from seed {args.synth_seed})", synthetic))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
