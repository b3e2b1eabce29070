"""What the scene page's guesses ("Show N guesses") add to the detector's suggestions, by their
source.

The page offers the active detector's boxes at the contract's threshold; on request it offers
guesses as well. Their sources are compared on the real photos of `bench_detector.py`:

- the active detector's own boxes below its threshold, down to the class hints' score (0.1);
- the suggester's boxes at the threshold (PicoDet's boxes named by the head trained on
  synthetic rooms, `make suggester-detector-model`), which knows the classes COCO lacks
  (lamp, pillow, night stand, picture...), the page's guesses;
- both.

Guesses are left out as the page leaves them out (`detectionOffers.ts`): over a
suggestion proper of their class (IoU over 0.5) or at its place whatever the class (over the
contract's same-place IoU), or at the place of a better guess. Printed: the given boxes found
at IoU 0.5 by everything shown (whatever the class, and with the right class), the guesses a
person looks through per photo, and the real boxes of the classes COCO has no name for found
with the right class.

The class picker's hints (frontend classHints.ts) are compared too: for each given box, as if
a person drew it, the classes of the boxes at its place (IoU 0.5 or more, score 0.1 or more),
best first, at most three: from the active detector's run alone, and with the suggester's
boxes added.

    python benchmarks/bench_guesses.py [--suggester DIR]
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
from bench_detector import IOU, REAL, percent, real_folders, truth_of
from holiscene.evaluation.detection_2d import DetectionEvaluation, ScoredBox
from holiscene.learning.detector.data import BoxedPhoto, boxed_photo
from holiscene.learning.detector.runtime import (
    DEFAULT_DETECTOR_DIR,
    SUGGESTER_DETECTOR_DIR,
    Detector,
    box_iou,
)
from holiscene_schema.detector_model import COCO_TO_NYU40, SAME_PLACE_IOU, SCORE_THRESHOLD
from tqdm import tqdm

HINT_SCORE = 0.1  # the class hints' score (frontend classHints.ts): the faintest box kept
OVERLAP_IOU = 0.5  # an offer over a box of its class is the same thing (detectionOffers.ts)
COCO_NAMED = {name for name in COCO_TO_NYU40 if name is not None}

Boxes = list[ScoredBox]


def clear_of(boxes: Boxes, shown: Boxes) -> Boxes:
    """`boxes` (best first) without those at the place of a shown box or of a better one."""
    kept: Boxes = []
    for box in sorted(boxes, key=lambda b: -(b.score or 0.0)):
        others = shown + kept
        if others:
            ious = box_iou(np.array(box.bbox), np.array([o.bbox for o in others]))
            same = np.array([o.cls == box.cls for o in others])
            if (ious > SAME_PLACE_IOU).any() or (same & (ious > OVERLAP_IOU)).any():
                continue
        kept.append(box)
    return kept


def scored(detector: Detector, photo: BoxedPhoto, threshold: float) -> Boxes:
    return [ScoredBox(d.bbox, d.cls, d.score) for d in detector.detect(photo.rgb, threshold)]


Source = Callable[[BoxedPhoto], Boxes]


def evaluate(photos: list[BoxedPhoto], offers: Source, guesses: Source | None) -> list[str]:
    shown_eval, guess_count, lacking_right, lacking_total = DetectionEvaluation(iou=IOU), 0, 0, 0
    for photo in tqdm(photos, unit="photo", file=sys.stderr):
        proper = offers(photo)
        guessed = clear_of(guesses(photo), proper) if guesses else []
        guess_count += len(guessed)
        shown = proper + guessed
        truth = truth_of(photo)
        shown_eval.add(shown, truth)
        for t in truth:
            if t.cls in COCO_NAMED:
                continue
            lacking_total += 1
            ious = box_iou(np.array(t.bbox), np.array([s.bbox for s in shown]).reshape(-1, 4))
            lacking_right += any(
                iou >= IOU and s.cls == t.cls for iou, s in zip(ious, shown, strict=True)
            )
    summary = shown_eval.summary()
    return [
        percent(summary["recall_any_class"]),
        percent(summary["recall_right_class"]),
        f"{guess_count / len(photos):.1f}",
        f"{lacking_right} of {lacking_total}",
    ]


MAX_HINTS = 3  # classHints.ts
HINT_IOU = 0.5


def hinted(bbox: tuple[float, ...], seen: Boxes) -> list[str]:
    """The picker's hints for a box: classes of the boxes at its place, best score first."""
    best: dict[str, float] = {}
    for box in seen:
        if (box.score or 0.0) >= HINT_SCORE and box_iou(np.array(bbox), np.array([box.bbox]))[
            0
        ] >= HINT_IOU:
            best[box.cls] = max(best.get(box.cls, 0.0), box.score or 0.0)
    return sorted(best, key=lambda c: -best[c])[:MAX_HINTS]


def hint_figures(photos: list[BoxedPhoto], seen: Callable[[BoxedPhoto], Boxes]) -> list[str]:
    first = among = some = total = 0
    for photo in photos:
        boxes = seen(photo)
        for truth in truth_of(photo):
            hints = hinted(truth.bbox, boxes)
            total += 1
            first += bool(hints) and hints[0] == truth.cls
            among += truth.cls in hints
            some += bool(hints)
    return [percent(first / total), percent(among / total), percent(some / total)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--real", type=Path, default=REAL)
    parser.add_argument("--active", type=Path, default=DEFAULT_DETECTOR_DIR)
    parser.add_argument("--suggester", type=Path, default=SUGGESTER_DETECTOR_DIR)
    args = parser.parse_args(argv)
    active, suggester = Detector.load(args.active), Detector.load(args.suggester)
    folders = real_folders(args.real)
    photos = [boxed_photo(f) for f in folders]

    def offers(photo: BoxedPhoto) -> Boxes:
        return scored(active, photo, SCORE_THRESHOLD)

    def below_threshold(photo: BoxedPhoto) -> Boxes:
        return [b for b in scored(active, photo, HINT_SCORE) if (b.score or 0) < SCORE_THRESHOLD]

    def suggested(photo: BoxedPhoto) -> Boxes:
        return scored(suggester, photo, SCORE_THRESHOLD)

    rows = {
        "none (the suggestions alone)": evaluate(photos, offers, None),
        f"the active detector's own boxes, {HINT_SCORE} to {SCORE_THRESHOLD}": evaluate(
            photos, offers, below_threshold
        ),
        f"the suggester's boxes, {SCORE_THRESHOLD} or more": evaluate(photos, offers, suggested),
        "both": evaluate(photos, offers, lambda photo: suggested(photo) + below_threshold(photo)),
    }
    print(
        f"\nIoU {IOU}; {len(photos)} real photos; suggestions proper: "
        f"{active.metadata.get('name')} at {SCORE_THRESHOLD}\n"
    )
    print(
        "| guesses | found % | right class % | guesses per photo "
        "| classes COCO lacks: right class |"
    )
    print("| --- | --- | --- | --- | --- |")
    for name, cells in rows.items():
        print(f"| {name} | " + " | ".join(cells) + " |")

    def active_run(photo: BoxedPhoto) -> Boxes:
        return scored(active, photo, HINT_SCORE)

    hints = {
        "the active detector's run": hint_figures(photos, active_run),
        "with the suggester's boxes": hint_figures(
            photos, lambda photo: active_run(photo) + suggested(photo)
        ),
    }
    print("\nClass hints for the given boxes (as if drawn by hand)\n")
    print("| hints from | first hint right % | right class among the hints % | any hint % |")
    print("| --- | --- | --- | --- |")
    for name, cells in hints.items():
        print(f"| {name} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
