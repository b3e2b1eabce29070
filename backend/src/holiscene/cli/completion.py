"""`holiscene train-completion`: the shape completion network (needs PyTorch:
`pip install -e '.[train]'`), trained on partial scans of the furniture library."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from .common import needs_pytorch


def add_completion_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    train = sub.add_parser(
        "train-completion",
        help="train the shape completion network on partial scans of the furniture library",
    )
    train.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    train.add_argument("--seed", type=int, default=0)
    train.add_argument("--scans", type=int, default=4000, help="training scans")
    train.add_argument("--validation-scans", type=int, default=100)
    train.add_argument(
        "--time-budget", type=float, default=1080.0, help="seconds of training (annealed)"
    )
    train.set_defaults(handler=_train_completion)


def _train_completion(args: argparse.Namespace) -> int:
    with needs_pytorch():
        from ..learning.completion.train import CompletionTraining, train_completion

    metrics = train_completion(
        CompletionTraining(
            out=args.out,
            train_scans=args.scans,
            validation_scans=args.validation_scans,
            seed=args.seed,
            time_budget=args.time_budget,
        )
    )
    print(json.dumps(metrics, indent=1))
    return 0
