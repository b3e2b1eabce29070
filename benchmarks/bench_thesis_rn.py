"""The thesis's Relation Network as the reference row (issue 5): train it within a time budget,
then score it on synthetic test scenes whose seeds no training uses.

  python benchmarks/bench_thesis_rn.py --budget-seconds 120 --test-seeds 900000-900019

Prints seconds per batch of 8 questions, batches done, the relational-question accuracy before
Eq. 4.1 (argmax of the 104 answers) and after it, and the object-level support accuracy
(supporter instance and type both right, ground-truth masks) with Eq. 4.1 decoding, beside the
prior-only baseline on the same neighbours. One PyTorch / onnxruntime thread throughout, so
the timing compares with other single-thread figures on this 2-core machine.

Priors: counted from the training scenes, or `--priors model_dir/priors.json` to use the same
counts as another model (e.g. the default network's) for a like-for-like comparison.
Seeds are given as `a-b` (inclusive) or single numbers.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import torch
from holiscene.learning.priors import SupportPriors
from holiscene.learning.training_api import MODEL_FILE
from holiscene.research.thesis_rn import (
    evaluate_thesis_rn,
    onnx_answer_fn,
    train_thesis_rn,
)
from holiscene.research.thesis_rn_data import synthetic_rn_scenes


def seed_list(tokens: list[str]) -> list[int]:
    seeds: list[int] = []
    for token in tokens:
        first, _, last = token.partition("-")
        seeds.extend(range(int(first), int(last or first) + 1))
    return seeds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--budget-seconds", type=float, required=True)
    parser.add_argument("--test-seeds", nargs="+", required=True)
    parser.add_argument("--train-seeds", nargs="+", default=["100000-100199"])
    parser.add_argument("--val-seeds", nargs="+", default=["100200-100204"])
    parser.add_argument("--priors", type=Path, help="priors.json to use instead of counting")
    parser.add_argument("--mask-mode", choices=("labels", "object"), default="labels")
    parser.add_argument("--out", type=Path, help="model directory (default: a temporary one)")
    parser.add_argument("--workers", type=int, default=2, help="scene-generation processes")
    parser.add_argument(
        "--relational-only", action="store_true", help="skip non-relational test questions"
    )
    args = parser.parse_args()
    torch.set_num_threads(1)
    train_seeds, val_seeds = seed_list(args.train_seeds), seed_list(args.val_seeds)
    test_seeds = seed_list(args.test_seeds)
    if set(test_seeds) & (set(train_seeds) | set(val_seeds)):
        print("test seeds overlap training or validation seeds", file=sys.stderr)
        return 1
    out = args.out or Path(tempfile.mkdtemp(prefix="thesis-rn-"))
    priors = SupportPriors.load(args.priors) if args.priors else None

    last = [0.0]

    def progress(fraction: float, line: str) -> None:
        now = time.perf_counter()
        if now - last[0] > 15 or fraction >= 1.0:  # a line every 15 s is plenty
            last[0] = now
            print(f"  [{fraction:4.0%}] {line}", flush=True)

    result = train_thesis_rn(
        args.budget_seconds,
        train_seeds,
        val_seeds,
        out,
        progress,
        mode=args.mask_mode,
        priors=priors,
        workers=args.workers,
    )
    metrics = result.metrics
    if priors is None:
        priors = SupportPriors.load(out / "priors.json")

    test = synthetic_rn_scenes(test_seeds, workers=args.workers)
    start = time.perf_counter()
    evaluation = evaluate_thesis_rn(
        onnx_answer_fn(out / MODEL_FILE, threads=1),
        test,
        priors,
        args.mask_mode,
        non_relational=not args.relational_only,
    )
    eval_seconds = time.perf_counter() - start
    summary = evaluation.summary()
    report = {
        "model_dir": str(out),
        "budget_s": args.budget_seconds,
        "seconds_per_batch_of_8": metrics["seconds_per_batch"],
        "batches": metrics["batches"],
        "epoch_fraction": metrics["epoch_fraction"],
        "first_losses": metrics["losses"][:5],
        "last_losses": metrics["losses"][-5:],
        "onnx_max_abs_diff": metrics["onnx_max_abs_diff"],
        "onnx_max_rel_diff": metrics["onnx_max_rel_diff"],
        "validation": metrics["validation"],
        "test_scenes": len(test),
        "test_eval_seconds": round(eval_seconds, 1),
        "test": summary,
    }
    (out / "bench.json").write_text(json.dumps(report, indent=1) + "\n")
    print(json.dumps(report, indent=1))
    print(
        f"thesis_rn budget={args.budget_seconds:.0f}s "
        f"s/batch8={metrics['seconds_per_batch']} batches={metrics['batches']} "
        f"relational={summary['relational_accuracy']} "
        f"relational_eq41={summary['relational_accuracy_eq41']} "
        f"support_eq41={summary['support_accuracy_eq41']} "
        f"prior_only={summary['support_accuracy_prior_only']} "
        f"(objects={summary['objects']}, scenes={len(test)})"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
