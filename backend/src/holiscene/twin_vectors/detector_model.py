"""Test vectors for the object detector's preprocessing, model and decoding: `python -m
holiscene.twin_vectors.detector_model` writes shared_schema/vectors/detector_model.json.

The backend (holiscene.learning.detector.runtime + onnxruntime) and the browser
(frontend/src/inference/detectorTensor.ts + onnxruntime-web) stretch a photo to the contract's
input tensor, run the same ONNX file and decode its rows into NYU-40 boxes (the contract is
holiscene_schema/detector_model.py); both are tested against these vectors. Like
relation_model.py this is a development tool that imports the backend.

Deterministic (one seeded generator). Photos: a few small synthetic pictures (gradients,
rectangles, discs, a fine checkerboard, noise) of sizes below, around and above the
model's 512 x 512, stored as zlib-compressed RGB bytes. Expected per photo:

- the input tensor, too big to store (786432 values): the sha256 of its float32 bytes (both
  sides compute it in float64 and round once, so they agree bit for bit), each channel's mean,
  and a few hundred sampled values;
- the model's raw `detections` [1, 100, 6], in full, each float32 exactly (rows of near-equal
  scores may come in another order on another runtime: the tests allow for that);
- the decoded boxes at the contract's score threshold, and at a low one (synthetic photos
  score low, so the low threshold is what exercises mapping and NMS on real model output).

A single pixel, a column and a row are preprocessed only (their tensors, no model output).
Decoding cases on hand-made rows then cover what photos rarely meet: the threshold's edge,
equal scores (the earlier row first), IoU exactly at the NMS limit, classes mapped to None,
out of range or not quite integers, clipping, boxes under MIN_BOX_PX (dropped after NMS: they
still suppress), and a model whose classes are NYU-40 already.

Made from the detector the app serves (holiscene.learning.detector.active: the default
detector, else the COCO model). The model file's sha256 is stored, so a test fails when the
vectors are stale relative to that model: run `make detector-vectors` again after changing the
default detector, its preprocessing or its decoding (`make detector-vectors` also writes the
suggester's, SUGGESTER_VECTORS).
"""

from __future__ import annotations

import argparse
import base64
import hashlib
import math
import zlib
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema.detector_model import (
    COCO_CLASSES,
    COCO_TO_NYU40,
    INPUT_NAME,
    INPUT_SIZE,
    MAX_DETECTIONS,
    MIN_BOX_PX,
    NMS_IOU,
    OUTPUT_NAME,
    SCORE_THRESHOLD,
)

from ..core.settings import REPO_ROOT
from ..learning.detector.runtime import (
    DEFAULT_DETECTOR_DIR,
    MODEL_FILE,
    DetectedBox,
    Detector,
    decode,
    preprocess,
)
from .relation_model import exact_float32, sha256, to_json

DETECTOR_VECTORS = REPO_ROOT / "shared_schema" / "vectors" / "detector_model.json"
# The same cases on the scene page's suggester (`--model-dir` its folder): its guesses run in
# the browser too.
SUGGESTER_VECTORS = DETECTOR_VECTORS.with_name("suggester_model.json")
SEED = 20260518
LOW_THRESHOLD = 0.02
SAMPLES = 240  # sampled input-tensor values per photo (besides the corners)

Json = dict[str, Any]

# Photos: (name, width, height). Smaller than the input (upsampling, clamping at the edges),
# odd sizes (no pixel lines up), and the usual 4:3 photo downsampled.
PHOTOS = (
    ("tiny-40x30", 40, 30),
    ("odd-97x61", 97, 61),
    ("room-640x480", 640, 480),
)
# Photos for the preprocessing only: one pixel, one column, one row (every sample clamped one
# way). The model is not run on them: on a picture this flat its peaks are ties that each
# runtime breaks its own way (another peak, another order), which says nothing about either.
PREPROCESS_ONLY = (
    ("single-pixel-1x1", 1, 1),
    ("column-1x50", 1, 50),
    ("row-70x1", 70, 1),
)


def draw_photo(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    """A synthetic picture: a two-tone gradient 'room', a few filled rectangles and discs, a
    fine checkerboard patch (every pixel differs from its neighbours) and some noise."""
    ys, xs = np.mgrid[0:height, 0:width].astype(np.float64)
    top, bottom = rng.integers(40, 220, 3), rng.integers(40, 220, 3)
    share = (ys / max(height - 1, 1))[..., None]
    image = top * (1 - share) + bottom * share
    for _ in range(int(rng.integers(3, 7))):
        colour = rng.integers(0, 256, 3)
        x0, x1 = sorted(rng.uniform(-0.1, 1.1, 2) * width)
        y0, y1 = sorted(rng.uniform(-0.1, 1.1, 2) * height)
        if rng.random() < 0.5:
            inside = (xs >= x0) & (xs < x1) & (ys >= y0) & (ys < y1)
        else:
            cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
            rx, ry = max((x1 - x0) / 2, 0.5), max((y1 - y0) / 2, 0.5)
            inside = ((xs - cx) / rx) ** 2 + ((ys - cy) / ry) ** 2 < 1
        image[inside] = colour
    if width >= 8 and height >= 8:
        cw, ch = max(width // 6, 2), max(height // 6, 2)
        cx, cy = int(rng.integers(0, width - cw)), int(rng.integers(0, height - ch))
        checker = ((xs[cy : cy + ch, cx : cx + cw] + ys[cy : cy + ch, cx : cx + cw]) % 2)[..., None]
        image[cy : cy + ch, cx : cx + cw] = checker * 255
    # Noise everywhere on a small photo; on a large one in a patch (noise does not compress).
    if width * height <= 10_000:
        image += rng.normal(0.0, 3.0, image.shape)
    else:
        nw, nh = width // 10, height // 10
        nx, ny = int(rng.integers(0, width - nw)), int(rng.integers(0, height - nh))
        image[ny : ny + nh, nx : nx + nw] += rng.normal(0.0, 12.0, (nh, nw, 3))
    photo: np.ndarray = np.clip(np.floor(image), 0, 255).astype(np.uint8)
    return photo


def encoded_photo(image: np.ndarray) -> Json:
    height, width = image.shape[:2]
    packed = zlib.compress(np.ascontiguousarray(image).tobytes(), 9)
    return {
        "width": width,
        "height": height,
        "encoding": "zlib",  # of the RGB bytes, row by row
        "rgb_base64": base64.b64encode(packed).decode("ascii"),
    }


def decoded_photo(entry: Json) -> np.ndarray:
    """A photo from the file (the inverse of encoded_photo)."""
    raw = zlib.decompress(base64.b64decode(entry["rgb_base64"]))
    return np.frombuffer(raw, dtype=np.uint8).reshape(entry["height"], entry["width"], 3)


def tensor_summary(tensor: np.ndarray, rng: np.random.Generator) -> Json:
    """What the file keeps of an input tensor: its sha256, channel means, sampled values."""
    flat = tensor.reshape(-1)
    last = flat.size - 1
    picks = {0, 1, 2, last - 2, last - 1, last}
    picks.update(int(i) for i in rng.choice(flat.size, SAMPLES, replace=False))
    index = sorted(picks)
    channels = tensor.reshape(-1, 3).astype(np.float64)
    return {
        "shape": list(tensor.shape),
        "float32_sha256": hashlib.sha256(flat.astype("<f4").tobytes()).hexdigest(),
        "channel_means": [math.fsum(channels[:, c]) / len(channels) for c in range(3)],
        "samples": {"index": index, "data": exact_float32(flat[index])},
    }


def box_json(box: DetectedBox) -> Json:
    return {
        "bbox": list(box.bbox),
        "score": box.score,
        "class": box.cls,
        "source_class": box.source_class,
    }


def preprocess_cases(rng: np.random.Generator) -> list[Json]:
    cases: list[Json] = []
    for name, width, height in PREPROCESS_ONLY:
        image = draw_photo(rng, width, height)
        summary = tensor_summary(preprocess(image), rng)
        cases.append(
            {"name": name, "image": encoded_photo(image), "expected": {INPUT_NAME: summary}}
        )
    return cases


def photo_cases(detector: Detector, rng: np.random.Generator) -> list[Json]:
    cases: list[Json] = []
    for name, width, height in PHOTOS:
        image = draw_photo(rng, width, height)
        tensor = preprocess(image)
        raw = detector.raw(tensor)
        decoded = {
            threshold: [
                box_json(b)
                for b in decode(raw, width, height, detector.classes, detector.to_nyu40, threshold)
            ]
            for threshold in (SCORE_THRESHOLD, LOW_THRESHOLD)
        }
        cases.append(
            {
                "name": name,
                "image": encoded_photo(image),
                "expected": {
                    INPUT_NAME: tensor_summary(tensor, rng),
                    OUTPUT_NAME: {"shape": list(raw.shape), "data": exact_float32(raw)},
                    "boxes": decoded[SCORE_THRESHOLD],
                    "boxes_low_threshold": decoded[LOW_THRESHOLD],
                },
            }
        )
    return cases


def _rows(rows: list[list[float]]) -> np.ndarray:
    return np.asarray(rows, dtype=np.float32)[None]


def _coco(name: str) -> int:
    return COCO_CLASSES.index(name)


def decode_specs(rng: np.random.Generator) -> list[Json]:
    """Hand-made rows (input pixels, score, class index) and what decoding makes of them."""
    s = float(INPUT_SIZE)
    chair, couch, cup, bottle, dog = (_coco(n) for n in ("chair", "couch", "cup", "bottle", "dog"))
    # Two boxes whose IoU is exactly NMS_IOU (kept: suppression needs more) and one just over.
    at_limit = [[0, 0, 100, 100, 0.9, chair], [0, 0, 100, 50, 0.8, chair]]
    over_limit = [[200, 200, 300, 300, 0.9, chair], [200, 200, 300, 251, 0.8, chair]]
    specs: list[Json] = [
        {
            "name": "threshold-edge-and-class-indices",
            "width": 640,
            "height": 480,
            "rows": [
                [10, 10, 60, 60, SCORE_THRESHOLD, chair],  # == threshold (as float32): kept
                [70, 10, 120, 60, np.nextafter(np.float32(SCORE_THRESHOLD), 0), chair],  # under
                [130, 10, 180, 60, 0.5, dog],  # a class mapped to None: dropped
                [190, 10, 240, 60, 0.5, 80],  # out of range: dropped
                [250, 10, 300, 60, 0.5, -1],  # out of range: dropped
                [310, 10, 360, 60, 0.5, cup + 0.4],  # rounds to cup
                [370, 10, 420, 60, 0.5, bottle - 0.4],  # rounds to bottle
            ],
        },
        {
            "name": "nms-ties-and-limits",
            "width": 512,
            "height": 512,
            "rows": [
                *at_limit,
                *over_limit,
                # Equal scores, overlapping: the earlier row wins.
                [300, 0, 400, 80, 0.7, couch],
                [302, 2, 402, 82, 0.7, couch],
                # cup and bottle both map to otherprop: they suppress each other.
                [0, 300, 60, 360, 0.6, cup],
                [2, 300, 62, 360, 0.65, bottle],
                # A different NYU-40 class on the same box is left alone.
                [0, 300, 60, 360, 0.55, chair],
            ],
        },
        {
            "name": "clip-and-small-boxes",
            "width": 97,
            "height": 61,
            "rows": [
                [-40, -30, 100, 90, 0.9, chair],  # clipped at the top left
                [400, 450, s + 50, s + 20, 0.8, chair],  # clipped at the bottom right
                # Under MIN_BOX_PX once scaled (97/512 of 20 px is 3.8 px): dropped, but only
                # after NMS, so it still suppresses the weaker box under it.
                [200, 200, 220, 300, 0.7, couch],
                [199, 200, 221, 300, 0.6, couch],
                [300, 100, 300, 200, 0.65, cup],  # no width at all
            ],
        },
    ]
    # A model of NYU-40 classes: its class list is its mapping.
    nyu_classes = ["chair", "table", "lamp", "otherprop"]
    specs.append(
        {
            "name": "nyu40-model",
            "width": 300,
            "height": 200,
            "classes": nyu_classes,
            "rows": [
                [10, 10, 200, 200, 0.95, 1],
                [12, 10, 200, 198, 0.9, 1],
                [12, 10, 200, 198, 0.9, 0],
                [400, 300, 500, 500, 0.4, 3],
                [400, 300, 500, 500, 0.4, 4],  # out of range
            ],
        }
    )
    # A full-size table of random rows: many classes, scores on both sides of the threshold.
    random_rows = []
    for _ in range(MAX_DETECTIONS):
        x0, y0 = rng.uniform(-20, s, 2)
        w, h = rng.uniform(0, s / 3, 2)
        random_rows.append(
            [x0, y0, x0 + w, y0 + h, rng.uniform(0, 0.9), int(rng.integers(0, len(COCO_CLASSES)))]
        )
    random_rows.sort(key=lambda r: -r[4])  # best first, as the model gives them
    specs.append({"name": "random-100-rows", "width": 730, "height": 530, "rows": random_rows})
    return specs


def decode_cases(rng: np.random.Generator) -> list[Json]:
    cases = []
    for spec in decode_specs(rng):
        raw = _rows(spec["rows"])
        classes = spec.get("classes")
        model_classes = list(classes) if classes else list(COCO_CLASSES)
        to_nyu: list[str | None] = list(classes) if classes else list(COCO_TO_NYU40)
        boxes = decode(raw, spec["width"], spec["height"], model_classes, to_nyu)
        cases.append(
            {
                "name": spec["name"],
                "width": spec["width"],
                "height": spec["height"],
                "label_space": "nyu40" if classes else "coco80",
                "classes": model_classes if classes else None,
                "score_threshold": SCORE_THRESHOLD,
                OUTPUT_NAME: {"shape": list(raw.shape), "data": exact_float32(raw)},
                "expected": [box_json(b) for b in boxes],
            }
        )
    return cases


def relative(path: Path) -> str:
    resolved = path.resolve()
    return (
        resolved.relative_to(REPO_ROOT).as_posix()
        if resolved.is_relative_to(REPO_ROOT)
        else str(path)
    )


def generate(model_dir: Path) -> Json:
    rng = np.random.default_rng(SEED)
    detector = Detector(model_dir)
    model_file = model_dir / MODEL_FILE
    return {
        "about": "Test vectors of the object detector: see "
        "holiscene/twin_vectors/detector_model.py",
        "seed": SEED,
        "model": {
            "path": relative(model_file),
            "sha256": sha256(model_file),
            "label_space": detector.metadata["label_space"],
            "classes": detector.classes,
        },
        "contract": {
            "input_size": INPUT_SIZE,
            "score_threshold": SCORE_THRESHOLD,
            "nms_iou": NMS_IOU,
            "min_box_px": MIN_BOX_PX,
        },
        "low_threshold": LOW_THRESHOLD,
        "tolerance": {"inputs": 1e-6, "detections": 1e-4, "boxes": 1e-4},
        "cases": photo_cases(detector, rng),
        "preprocess_cases": preprocess_cases(rng),
        "decode_cases": decode_cases(rng),
    }


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    parser.add_argument(
        "--model-dir",
        type=Path,
        default=DEFAULT_DETECTOR_DIR,
        help="model.onnx + metadata.json (default: the detector the app serves)",
    )
    parser.add_argument("-o", "--output", type=Path, default=DETECTOR_VECTORS)
    args = parser.parse_args(argv)
    args.output.parent.mkdir(exist_ok=True)
    args.output.write_text(to_json(generate(args.model_dir)))
    size = args.output.stat().st_size // 1024
    print(f"wrote {args.output} ({size} KiB) from {args.model_dir / MODEL_FILE}")


if __name__ == "__main__":
    main()
