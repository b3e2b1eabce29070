"""Support scores for a 20-object scene in the backend: preprocessing + onnxruntime.

    python benchmarks/bench_relation.py [--model-dir DIR] [--runs 20]

The scene is the one the browser benchmark times (e2e_tests/tests/relation-benchmark.spec.ts):
a 640 x 480 photo of random pixels and 20 elliptical masks in the contract's RLE, drawn by the
same seeded generator (mulberry32, seed 20260505). Each run does what the pipeline's
`supports_from_network` stage does with the masks it holds: the model's inputs
(holiscene.learning.preprocess.relation_inputs) and the probabilities from the model
(holiscene.learning.runtime.SupportModel: onnxruntime, CPU, one thread), on a model loaded
beforehand. Decoding the masks from RLE (which the pipeline has done before) is timed apart.
Prints the model's load time and the median and maximum of the runs after two warm-up runs,
and the median CPU time of a run (what the run costs when the machine is shared).
Target (issue 5): at most 100 ms.
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
from holiscene.learning.runtime import DEFAULT_MODEL_DIR, SupportModel
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Mask

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
    parser.add_argument("--model-dir", type=Path, default=DEFAULT_MODEL_DIR)
    parser.add_argument("--runs", type=int, default=20)
    args = parser.parse_args()

    image, masks, boxes, classes = benchmark_scene()
    start = time.perf_counter()
    model = SupportModel(args.model_dir)
    load_ms = (time.perf_counter() - start) * 1000

    def decode() -> tuple[list[np.ndarray], float]:
        begin = time.perf_counter()
        full = [decode_mask(m, WIDTH, HEIGHT) for m in masks]
        return full, (time.perf_counter() - begin) * 1000

    full, _ = decode()

    cpu: list[float] = []

    def score() -> tuple[float, float]:
        begin, begin_cpu = time.perf_counter(), time.process_time()
        inputs = relation_inputs(image, full, boxes, classes)
        ran = time.perf_counter()
        probabilities = model.probabilities(inputs)
        assert probabilities.shape == (OBJECTS, OBJECTS + 3, 2)
        cpu.append((time.process_time() - begin_cpu) * 1000)
        return (ran - begin) * 1000, (time.perf_counter() - ran) * 1000

    first = score()
    for _ in range(2):
        score()
    cpu.clear()
    runs = [score() for _ in range(args.runs)]
    decode_ms = statistics.median(decode()[1] for _ in range(5))
    preprocess = [p for p, _ in runs]
    network = [m for _, m in runs]
    total = [p + m for p, m in runs]
    median = statistics.median(total)
    print(
        f"relation network in the backend (onnxruntime {ort.__version__}, CPU, one thread),"
        f" {OBJECTS} objects, {WIDTH}x{HEIGHT}, model {args.model_dir}:"
    )
    print(f"  model loaded in {load_ms:.0f} ms; first score {sum(first):.1f} ms")
    print(
        f"  median of {args.runs}: preprocess {statistics.median(preprocess):.1f} ms"
        f" + model {statistics.median(network):.1f} ms = {median:.1f} ms"
        f" (max {max(total):.1f} ms; target {TARGET_MS:.0f} ms)"
    )
    # On a busy machine the wall clock includes waiting for a core; the CPU time does not.
    print(f"  CPU time of a run, median: {statistics.median(cpu):.1f} ms")
    print(f"  decoding the 20 masks from RLE beforehand: {decode_ms:.1f} ms (median of 5)")
    print("  within target" if median <= TARGET_MS else "  OVER TARGET")


if __name__ == "__main__":
    main()
