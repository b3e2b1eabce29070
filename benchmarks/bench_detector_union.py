"""Detectors as one: PicoDet's COCO boxes with the NYU-40 head's boxes, or PicoDet's own boxes
on more views of the photo, added.

PicoDet finds the real photos' chairs, beds, tables and sofas; the NYU-40 head knows the
classes COCO lacks (night stand, dresser, lamp, pillow, door...) but is far less precise on real
photos. This scores unions of the two detectors' rows, each rule one line, on the photos of
`bench_detector.py` (same figures, same IoU and thresholds): both models run once per photo and
every rule is decoded from those outputs by the contract's decoding (per-class NMS).

    python benchmarks/bench_detector_union.py [--synth-count 40]

A rule: `nyu_min` is the least score of an NYU-40 row to be added (None: none added),
`nyu_weight` multiplies its score, and `unknown_only` adds only the classes COCO has no name
for; `flipped` adds PicoDet's rows on the photo mirrored, `crops` those on four overlapping
crops of 60% of each side (small objects seen larger), both mapped back onto the photo.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from bench_detector import IOU, add_photo_arguments, percent, real_folders, truth_of
from holiscene.evaluation.detection_2d import MAP_SCORE_THRESHOLD, DetectionEvaluation, ScoredBox
from holiscene.learning.detector.data import BoxedPhoto, boxed_photo, synthetic_photos
from holiscene.learning.detector.runtime import (
    NYU_DETECTOR_DIR,
    PICODET_DETECTOR_DIR,
    Detector,
    decode,
    preprocess,
)
from holiscene_schema.detector_model import COCO_TO_NYU40, INPUT_SIZE, SCORE_THRESHOLD
from tqdm import tqdm

COCO_NAMED = {name for name in COCO_TO_NYU40 if name is not None}


CROP_SHARE = 0.6
CROP_STARTS = (0.0, 1.0 - CROP_SHARE)  # left and right (top and bottom), overlapping


@dataclass(frozen=True)
class Rule:
    nyu_min: float | None = None
    nyu_weight: float = 1.0
    unknown_only: bool = True
    flipped: bool = False
    crops: bool = False

    def __str__(self) -> str:
        parts = []
        if self.nyu_min is not None:
            classes = "classes COCO lacks" if self.unknown_only else "every class"
            parts.append(f"NYU-40 rows at >= {self.nyu_min} x {self.nyu_weight}, {classes}")
        if self.flipped:
            parts.append("its rows on the mirrored photo")
        if self.crops:
            parts.append("its rows on four 60% crops")
        return "; ".join(parts) or "nothing (PicoDet alone)"


@dataclass(frozen=True)
class Outputs:
    photo: BoxedPhoto
    picodet: np.ndarray  # [100, 6], COCO class indices
    nyu: np.ndarray  # [100, 6], NYU-40 head class indices
    flipped: np.ndarray  # [100, 6], PicoDet on the mirrored photo, boxes mapped back
    crops: np.ndarray  # [400, 6], PicoDet on the crops, boxes mapped back


def mirrored_rows(picodet: Detector, tensor: np.ndarray) -> np.ndarray:
    rows: np.ndarray = picodet.raw(tensor[:, :, ::-1].copy())[0].copy()
    rows[:, [0, 2]] = INPUT_SIZE - rows[:, [2, 0]]
    return rows


def crop_rows(picodet: Detector, rgb: np.ndarray) -> np.ndarray:
    """PicoDet's rows on each crop, in the input pixels of the whole photo."""
    height, width = rgb.shape[:2]
    h, w = int(CROP_SHARE * height), int(CROP_SHARE * width)
    found = []
    for fy in CROP_STARTS:
        for fx in CROP_STARTS:
            y0, x0 = int(fy * height), int(fx * width)
            rows = picodet.raw(preprocess(rgb[y0 : y0 + h, x0 : x0 + w]))[0].copy()
            rows[:, [0, 2]] = rows[:, [0, 2]] * (w / width) + x0 / width * INPUT_SIZE
            rows[:, [1, 3]] = rows[:, [1, 3]] * (h / height) + y0 / height * INPUT_SIZE
            found.append(rows)
    return np.concatenate(found)


def united(outputs: Outputs, rule: Rule, nyu_classes: list[str]) -> list[ScoredBox]:
    """The rule's rows in one NYU-40 class list, decoded as one model's."""
    rows: list[tuple[np.ndarray, float, str]] = []
    picodet = [outputs.picodet]
    picodet += [outputs.flipped] if rule.flipped else []
    picodet += [outputs.crops] if rule.crops else []
    for row in np.concatenate(picodet):
        name = COCO_TO_NYU40[round(float(row[5]))]
        if name is not None and row[4] > 0:
            rows.append((row[:4], float(row[4]), name))
    if rule.nyu_min is not None:
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
    rule: Rule,
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
    add_photo_arguments(parser)
    args = parser.parse_args(argv)
    picodet, nyu = Detector.load(PICODET_DETECTOR_DIR), Detector.load(NYU_DETECTOR_DIR)

    def run_both(photos: list[BoxedPhoto], desc: str) -> list[Outputs]:
        outputs = []
        for photo in tqdm(photos, desc=desc, unit="photo", file=sys.stderr):
            tensor = preprocess(photo.rgb)
            outputs.append(
                Outputs(
                    photo,
                    picodet.raw(tensor)[0],
                    nyu.raw(tensor)[0],
                    mirrored_rows(picodet, tensor),
                    crop_rows(picodet, photo.rgb),
                )
            )
        return outputs

    folders = real_folders(args.real)
    real = run_both([boxed_photo(f) for f in folders], "real")
    complete = [o for f, o in zip(folders, real, strict=True) if f.name.startswith("mm3d")]
    with tempfile.TemporaryDirectory(prefix="bench-union-") as scratch:
        seeds = range(args.synth_seed, args.synth_seed + args.synth_count)
        synthetic = run_both(synthetic_photos(seeds, Path(scratch)), "synthetic")
    rules = [Rule()]
    for unknown_only in (True, False):
        rules += [Rule(m, w, unknown_only) for m in (0.0, 0.4, 0.5) for w in (1.0, 0.7)]
    rules += [Rule(flipped=True), Rule(crops=True), Rule(flipped=True, crops=True)]
    print(
        f"\nIoU {IOU}; found and real at score >= {SCORE_THRESHOLD}, mAP down to "
        f"{MAP_SCORE_THRESHOLD}; {len(real)} real photos, {len(synthetic)} synthetic rooms\n"
    )
    print("| PicoDet with | real: found % | right class % | mm3d: real % | synthetic mAP@0.5 |")
    print("| --- | --- | --- | --- | --- |")
    for rule in rules:
        figures = score(rule, real, complete, synthetic, nyu.classes)
        cells = " | ".join(percent(f) for f in figures)
        print(f"| {rule} | {cells} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
