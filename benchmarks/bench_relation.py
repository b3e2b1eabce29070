"""Support scores for a 20-object scene in the backend: preprocessing + onnxruntime.

    python benchmarks/bench_relation.py [--model PATH] [--runs 20]

The scene is the one the browser benchmark times (e2e_tests/tests/relation-benchmark.spec.ts):
a 640 x 480 photo of random pixels and 20 elliptical masks in the contract's RLE, drawn by the
same seeded generator (mulberry32, seed 20260505). Each run decodes the masks, computes the
model's inputs (holiscene.learning.preprocess) and runs the model (onnxruntime, CPU) on one
session created beforehand; prints the session's creation time and the median and maximum of
the runs. Target (issue 5): at most 100 ms.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import onnxruntime as ort
from holiscene.learning.preprocess import relation_inputs
from holiscene.rle import decode_mask
from holiscene_schema import Mask
from holiscene_schema.relation_model import INPUT_NAMES, OUTPUT_NAME

DEFAULT_MODEL = (
    Path(__file__).resolve().parents[1]
    / "backend"
    / "src"
    / "holiscene"
    / "learning"
    / "default_model"
    / "model.onnx"
)
WIDTH, HEIGHT, OBJECTS, SEED = 640, 480, 20, 20260505
CLASSES = ("bed", "chair", "table", "lamp", "pillow", "books", "box", "picture")
TARGET_MS = 100.0
MASK32 = 0xFFFFFFFF


def mulberry32(seed: int) -> Callable[[], float]:
    """The browser benchmark's generator: the same numbers for the same seed."""
    state = seed & MASK32

    def imul(a: int, b: int) -> int:
        return (a * b) & MASK32

    def next_value() -> float:
        nonlocal state
        state = (state + 0x6D2B79F5) & MASK32
        t = imul(state ^ (state >> 15), state | 1)
        t ^= (t + imul(t ^ (t >> 7), t | 61)) & MASK32
        return ((t ^ (t >> 14)) & MASK32) / 4294967296

    return next_value


def blob(next_value: Callable[[], float]) -> tuple[Mask, list[float]]:
    rx = 15 + next_value() * 120
    ry = 15 + next_value() * 100
    cx = rx + next_value() * (WIDTH - 2 * rx)
    cy = ry + next_value() * (HEIGHT - 2 * ry)
    x0, y0 = max(0, int(np.floor(cx - rx))), max(0, int(np.floor(cy - ry)))
    x1, y1 = min(WIDTH, int(np.ceil(cx + rx))), min(HEIGHT, int(np.ceil(cy + ry)))
    ys, xs = np.mgrid[y0:y1, x0:x1]
    inside = (((xs + 0.5 - cx) / rx) ** 2 + ((ys + 0.5 - cy) / ry) ** 2 < 1).reshape(-1)
    change = np.flatnonzero(np.diff(inside.astype(np.int8))) + 1
    runs = np.diff(np.concatenate([[0], change, [inside.size]])).tolist()
    if inside[0]:
        runs = [0, *runs]
    mask = Mask(origin=[x0, y0], size=[x1 - x0, y1 - y0], rle=runs, source="given")
    return mask, [float(x0), float(y0), float(x1), float(y1)]


def benchmark_scene() -> tuple[np.ndarray, list[Mask], list[list[float]], list[str]]:
    next_value = mulberry32(SEED)
    pixels = [int(next_value() * 256) for _ in range(WIDTH * HEIGHT * 3)]
    image = np.array(pixels, dtype=np.uint8).reshape(HEIGHT, WIDTH, 3)
    masks, boxes = [], []
    for _ in range(OBJECTS):
        mask, box = blob(next_value)
        masks.append(mask)
        boxes.append(box)
    classes = [CLASSES[i % len(CLASSES)] for i in range(OBJECTS)]
    return image, masks, boxes, classes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    parser.add_argument("--model", type=Path, default=DEFAULT_MODEL)
    parser.add_argument("--runs", type=int, default=20)
    args = parser.parse_args()

    image, masks, boxes, classes = benchmark_scene()
    start = time.perf_counter()
    options = ort.SessionOptions()
    session = ort.InferenceSession(
        str(args.model), sess_options=options, providers=["CPUExecutionProvider"]
    )
    session_ms = (time.perf_counter() - start) * 1000

    def score() -> tuple[float, float]:
        begin = time.perf_counter()
        full = [decode_mask(m, WIDTH, HEIGHT) for m in masks]
        inputs = relation_inputs(image, full, boxes, classes)
        ran = time.perf_counter()
        (logits,) = session.run([OUTPUT_NAME], {k: inputs[k] for k in INPUT_NAMES})
        assert logits.shape == (OBJECTS, OBJECTS + 3, 2)
        return (ran - begin) * 1000, (time.perf_counter() - ran) * 1000

    first = score()
    for _ in range(2):
        score()
    runs = [score() for _ in range(args.runs)]
    preprocess = [p for p, _ in runs]
    model = [m for _, m in runs]
    total = [p + m for p, m in runs]
    median = statistics.median(total)
    print(
        f"relation network in the backend (onnxruntime {ort.__version__}, CPU), {OBJECTS} objects,"
        f" {WIDTH}x{HEIGHT}, model {args.model}:"
    )
    print(f"  session {session_ms:.0f} ms; first score {sum(first):.1f} ms")
    print(
        f"  median of {args.runs}: preprocess {statistics.median(preprocess):.1f} ms"
        f" + model {statistics.median(model):.1f} ms = {median:.1f} ms"
        f" (max {max(total):.1f} ms; target {TARGET_MS:.0f} ms)"
    )
    print("  within target" if median <= TARGET_MS else "  OVER TARGET")


if __name__ == "__main__":
    main()
