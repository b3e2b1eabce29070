"""Support accuracy on synthetic scenes never used in training, given their true masks.

    python benchmarks/bench_support.py [--seed 900000] [--count 200] [--model-dir DIR]

Compares, on the same scenes: the prior-only inference of Chapter 3 (counted priors checked on
the 2D boxes), the Relation Network alone, and the Relation Network combined with the priors
(Eq. 4.1). The default model trains on seeds 100000 on; the test seeds start at 900000.
Object-level accuracy: supporter (instance or floor/wall/ceiling) and type both right.
Target (issue 5): at least 90% for the default.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from holiscene.learning.evaluate import network_method, prior_method, score
from holiscene.learning.runtime import DEFAULT_MODEL_DIR, SupportModel
from holiscene.learning.synthetic import synthetic_samples
from holiscene.synth.ranges import IMAGE_SIZE
from tqdm import tqdm


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seed", type=int, default=900_000)
    parser.add_argument("--count", type=int, default=200)
    parser.add_argument("--model-dir", type=Path, default=DEFAULT_MODEL_DIR)
    parser.add_argument("--json", type=Path, help="also write the figures here")
    args = parser.parse_args()

    bar = tqdm(total=args.count, desc="test scenes", unit="scene", file=sys.stderr)

    def advance(done: int, total: int) -> None:
        bar.update(done - bar.n)

    samples = synthetic_samples(range(args.seed, args.seed + args.count), progress=advance)
    bar.close()
    model = SupportModel.load(args.model_dir)
    methods = {
        "prior only (Ch. 3)": prior_method(model.priors, IMAGE_SIZE),
        "Relation Network": network_method(model, "network"),
        "Relation Network + priors (Eq. 4.1)": network_method(model, "network+priors"),
    }
    rows = []
    print(f"{len(samples)} scenes from seed {args.seed}, model {args.model_dir}")
    header = ("method", "accuracy", "supporter", "type", "objects", "s")
    print("{:40s} {:>9s} {:>10s} {:>7s} {:>8s} {:>6s}".format(*header))
    for name, method in methods.items():
        start = time.perf_counter()
        result = score(name, method, samples)
        seconds = time.perf_counter() - start
        supporter, type_right = (
            result.supporter_right / result.total,
            result.type_right / result.total,
        )
        rows.append(
            {
                "method": name,
                "accuracy": result.accuracy,
                "supporter": supporter,
                "type": type_right,
                "objects": result.total,
                "seconds": seconds,
            }
        )
        print(
            f"{name:40s} {100 * result.accuracy:8.2f}% {100 * supporter:9.2f}% "
            f"{100 * type_right:6.2f}% {result.total:8d} {seconds:6.1f}"
        )
    if args.json:
        args.json.write_text(json.dumps({"seed": args.seed, "rows": rows}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
