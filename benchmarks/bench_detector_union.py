"""Two detectors as one: PicoDet's COCO boxes with the NYU-40 head's boxes added.

PicoDet finds the real photos' chairs, beds, tables and sofas; the NYU-40 head knows the
classes COCO lacks (night stand, dresser, lamp, pillow, door...) but is far less precise on real
photos. This scores unions of the two detectors' rows, each rule one line, on the photos of
`bench_detector.py` (same figures, same IoU and thresholds): both models run once per photo and
every rule is decoded from those outputs by the contract's decoding (per-class NMS).

    python benchmarks/bench_detector_union.py [--synth-count 40]

A rule: `nyu_min` is the least score of an NYU-40 row to be added, `nyu_weight` multiplies its
score, and `unknown_only` adds only the classes COCO has no name for.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from bench_detector import IOU, REAL, percent, truth_of
from holiscene.evaluation.detection_2d import MAP_SCORE_THRESHOLD, DetectionEvaluation, ScoredBox
from holiscene.learning.detector.data import BoxedPhoto, boxed_photo, synthetic_photos
from holiscene.learning.detector.runtime import (
    NYU_DETECTOR_DIR,
    PICODET_DETECTOR_DIR,
    Detector,
    decode,
    preprocess,
)
from holiscene_schema.detector_model import COCO_TO_NYU40, SCORE_THRESHOLD
from tqdm import tqdm

COCO_NAMED = {name for name in COCO_TO_NYU40 if name is not None}


@dataclass(frozen=True)
class Rule:
    nyu_min: float
    nyu_weight: float
    unknown_only: bool

    def __str__(self) -> str:
        classes = "classes COCO lacks" if self.unknown_only else "every class"
        return f"NYU-40 rows at >= {self.nyu_min} x {self.nyu_weight}, {classes}"


@dataclass(frozen=True)
class Outputs:
    photo: BoxedPhoto
    picodet: np.ndarray  # [100, 6], COCO class indices
    nyu: np.ndarray  # [100, 6], NYU-40 head class indices


def united(outputs: Outputs, rule: Rule | None, nyu_classes: list[str]) -> list[ScoredBox]:
    """The two models' rows in one NYU-40 class list, decoded as one model's (rule None:
    PicoDet alone)."""
    rows: list[tuple[np.ndarray, float, str]] = []
    for row in outputs.picodet:
        name = COCO_TO_NYU40[round(float(row[5]))]
        if name is not None:
            rows.append((row[:4], float(row[4]), name))
    if rule is not None:
        for row in outputs.nyu:
            name = nyu_classes[round(float(row[5]))]
            if float(row[4]) >= rule.nyu_min and not (rule.unknown_only and name in COCO_NAMED):
                rows.append((row[:4], float(row[4]) * rule.nyu_weight, name))
    classes = sorted({name for _, _, name in rows})
    table = np.array([[*box, score, classes.index(name)] for box, score, name in rows])
    height, width = outputs.photo.rgb.shape[:2]
    found = decode(table.reshape(-1, 6), width, height, classes, list(classes), MAP_SCORE_THRESHOLD)
    return [ScoredBox(d.bbox, d.cls, d.score) for d in found]


def score(
    rule: Rule | None,
    real: list[Outputs],
    complete: list[Outputs],
    synthetic: list[Outputs],
    nyu_classes: list[str],
) -> list[float | None]:
    at_threshold = {"real": DetectionEvaluation(iou=IOU), "mm3d": DetectionEvaluation(iou=IOU)}
    for name, photos in (("real", real), ("mm3d", complete)):
        for outputs in photos:
            boxes = united(outputs, rule, nyu_classes)
            kept = [b for b in boxes if b.score >= SCORE_THRESHOLD]
            at_threshold[name].add(kept, truth_of(outputs.photo))
    ranked = DetectionEvaluation(iou=IOU)
    for outputs in synthetic:
        ranked.add(united(outputs, rule, nyu_classes), truth_of(outputs.photo))
    classes = {c for o in synthetic for c in o.photo.classes}
    on_real = at_threshold["real"].summary()
    return [
        on_real["recall_any_class"],
        on_real["recall_right_class"],
        at_threshold["mm3d"].summary()["precision"],
        ranked.summary(classes)["map"],
    ]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--real", type=Path, default=REAL)
    parser.add_argument("--synth-seed", type=int, default=950000)
    parser.add_argument("--synth-count", type=int, default=40)
    args = parser.parse_args(argv)
    picodet, nyu = Detector.load(PICODET_DETECTOR_DIR), Detector.load(NYU_DETECTOR_DIR)

    def run_both(photos: list[BoxedPhoto], desc: str) -> list[Outputs]:
        outputs = []
        for photo in tqdm(photos, desc=desc, unit="photo", file=sys.stderr):
            tensor = preprocess(photo.rgb)
            outputs.append(Outputs(photo, picodet.raw(tensor)[0], nyu.raw(tensor)[0]))
        return outputs

    folders = sorted(p for p in args.real.iterdir() if (p / "detections.json").is_file())
    real = run_both([boxed_photo(f) for f in folders], "real")
    complete = [o for f, o in zip(folders, real, strict=True) if f.name.startswith("mm3d")]
    with tempfile.TemporaryDirectory(prefix="bench-union-") as scratch:
        seeds = range(args.synth_seed, args.synth_seed + args.synth_count)
        synthetic = run_both(synthetic_photos(seeds, Path(scratch)), "synthetic")
    rules: list[Rule | None] = [None]
    for unknown_only in (True, False):
        rules += [Rule(m, w, unknown_only) for m in (0.0, 0.4, 0.5) for w in (1.0, 0.7)]
    print(
        f"\nIoU {IOU}; found and real at score >= {SCORE_THRESHOLD}, mAP down to "
        f"{MAP_SCORE_THRESHOLD}; {len(real)} real photos, {len(synthetic)} synthetic rooms\n"
    )
    print("| PicoDet with | real: found % | right class % | mm3d: real % | synthetic mAP@0.5 |")
    print("| --- | --- | --- | --- | --- |")
    for rule in rules:
        figures = score(rule, real, complete, synthetic, nyu.classes)
        cells = " | ".join(percent(f) for f in figures)
        print(f"| {rule or 'nothing (PicoDet alone)'} | {cells} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
