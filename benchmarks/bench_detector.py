"""Object detectors against given boxes: `make bench-detector`.

- Real photos (../shared/data/real): the boxes that come with them are the truth. mm3d-* hold
  the dataset's complete boxes, so the share of predicted boxes that are real is measured
  there only; t3d-* and im3d-* hold furniture only (recall only).
- Held-out synthetic rooms (seeds no training uses): exact boxes for every object the
  generator makes; mAP@0.5 over the generator's classes.
- Time per photo of the detector alone (preprocessing, onnxruntime one thread, decoding).

Each --model is a detector directory (model.onnx + metadata.json); the default is the
committed one. Figures are printed as a table, and --json writes them.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from holiscene.evaluation.detection_2d import MAP_SCORE_THRESHOLD, DetectionEvaluation, ScoredBox
from holiscene.learning.detector.data import BoxedPhoto, boxed_photo, synthetic_photos
from holiscene.learning.detector.runtime import DEFAULT_DETECTOR_DIR, Detector
from holiscene_schema.detector_model import SCORE_THRESHOLD
from tqdm import tqdm

REPO = Path(__file__).resolve().parent.parent
REAL = REPO.parent / "shared" / "data" / "real"
IOU = 0.5


def add_photo_arguments(parser: argparse.ArgumentParser) -> None:
    """The photos every detector benchmark scores: the real ones, and held-out synthetic rooms."""
    parser.add_argument("--real", type=Path, default=REAL)
    parser.add_argument("--synth-seed", type=int, default=950000)
    parser.add_argument("--synth-count", type=int, default=40)


def real_folders(real: Path) -> list[Path]:
    """The real photos' folders that come with boxes (detections.json)."""
    return sorted(p for p in real.iterdir() if (p / "detections.json").is_file())


def truth_of(photo: BoxedPhoto) -> list[ScoredBox]:
    return [
        ScoredBox((b[0], b[1], b[2], b[3]), c)
        for b, c in zip(photo.boxes.tolist(), photo.classes, strict=True)
    ]


def evaluate(
    detector: Detector, photos: list[BoxedPhoto], threshold: float, desc: str
) -> tuple[DetectionEvaluation, DetectionEvaluation, list[float]]:
    """Scores at the operating threshold (recall, precision) and down to the mAP threshold
    (mAP), and the seconds each photo took."""
    at_threshold, ranked = DetectionEvaluation(iou=IOU), DetectionEvaluation(iou=IOU)
    seconds: list[float] = []
    for photo in tqdm(photos, desc=desc, unit="photo", file=sys.stderr):
        start = time.perf_counter()
        found = detector.detect(photo.rgb, MAP_SCORE_THRESHOLD)
        seconds.append(time.perf_counter() - start)
        boxes = [ScoredBox(d.bbox, d.cls, d.score) for d in found]
        truth = truth_of(photo)
        ranked.add(boxes, truth)
        at_threshold.add([b for b in boxes if b.score >= threshold], truth)
    return at_threshold, ranked, seconds


def percent(value: float | None) -> str:
    return "-" if value is None else f"{100 * value:.1f}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--model", type=Path, action="append", help="detector directory")
    add_photo_arguments(parser)
    parser.add_argument("--threshold", type=float, default=SCORE_THRESHOLD)
    parser.add_argument("--json", type=Path, help="write the figures here too")
    parser.add_argument(
        "--per-class",
        action="store_true",
        help="also print the real boxes found per class (found / with the right class)",
    )
    args = parser.parse_args(argv)
    models = args.model or [DEFAULT_DETECTOR_DIR]
    folders = real_folders(args.real)
    real = [boxed_photo(f) for f in folders]
    complete = [p for f, p in zip(folders, real, strict=True) if f.name.startswith("mm3d")]
    results: dict[str, dict[str, Any]] = {}
    with tempfile.TemporaryDirectory(prefix="bench-detector-") as scratch:
        seeds = range(args.synth_seed, args.synth_seed + args.synth_count)
        synthetic = synthetic_photos(seeds, Path(scratch))
        synth_classes = {c for p in synthetic for c in p.classes}
        for model_dir in models:
            detector = Detector.load(model_dir)
            name = str(detector.metadata.get("name", model_dir.name))
            if name in results:  # two runs of one recipe: tell them apart by folder
                name = f"{name} ({model_dir})"
            on_real, _, seconds = evaluate(detector, real, args.threshold, f"real {name}")
            on_complete, _, _ = evaluate(detector, complete, args.threshold, f"mm3d {name}")
            on_synth, synth_ranked, _ = evaluate(
                detector, synthetic, args.threshold, f"synthetic {name}"
            )
            results[name] = {
                "model_dir": str(model_dir),
                "real": on_real.summary(),
                "mm3d": on_complete.summary(),
                "synthetic": on_synth.summary(synth_classes),
                "synthetic_map": synth_ranked.summary(synth_classes)["map"],
                "seconds_median": statistics.median(seconds),
            }
    print(
        f"\nIoU {IOU}; boxes found and predictions real at score >= {args.threshold}, mAP over "
        f"every box down to {MAP_SCORE_THRESHOLD}; real: {len(real)} photos; synthetic: "
        f"{args.synth_count} rooms from seed {args.synth_seed}, {len(synth_classes)} classes\n"
    )
    print(
        "| model | real: boxes found % | with right class % | mm3d: predictions real % "
        "| synthetic mAP@0.5 | synthetic found % | s per photo | real: boxes per photo |"
    )
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, r in results.items():
        real_s, mm3d_s, synth_s = r["real"], r["mm3d"], r["synthetic"]
        print(
            f"| {name} | {percent(real_s['recall_any_class'])} "
            f"| {percent(real_s['recall_right_class'])} | {percent(mm3d_s['precision'])} "
            f"| {percent(r['synthetic_map'])} | {percent(synth_s['recall_right_class'])} "
            f"| {r['seconds_median']:.3f} | {real_s['predicted_boxes'] / real_s['photos']:.1f} |"
        )
    if args.per_class:
        print_per_class(results)
    if args.json:
        args.json.write_text(json.dumps(results, indent=1) + "\n")
    return 0


def print_per_class(results: dict[str, dict[str, Any]]) -> None:
    """Real boxes found per truth class, one column per model: where each model fails."""
    names = list(results)
    per_model = [results[name]["real"]["found_per_class"] for name in names]
    classes = sorted(per_model[0], key=lambda c: (-per_model[0][c]["truth"], c))
    print("\nReal boxes found / with the right class, per class (models in the order above)\n")
    print("| class | boxes | " + " | ".join(f"model {i + 1}" for i in range(len(names))) + " |")
    print("| --- | --- |" + " --- |" * len(names))
    for cls in classes:
        cells = [f"{m[cls]['found']} / {m[cls]['right_class']}" for m in per_model]
        print(f"| {cls} | {per_model[0][cls]['truth']} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    raise SystemExit(main())
