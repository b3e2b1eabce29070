"""`holiscene train-3d`: the learned 3D box refiner (thesis Ch. 5; needs PyTorch:
`pip install -e '.[train]'`), trained on synthetic rooms run through the single-photo pipeline."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from .common import CliError, needs_pytorch


def add_box_refiner_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    train = sub.add_parser(
        "train-3d",
        help="train the learned 3D box refiner on synthetic rooms (single photos, no depth)",
    )
    train.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    train.add_argument("--rooms", type=int, default=1500, help="training rooms")
    train.add_argument("--first-seed", type=int, default=610000, help="first training room's seed")
    train.add_argument("--validation-rooms", type=int, default=200)
    train.add_argument("--validation-seed", type=int, default=960000)
    train.add_argument("--epochs", type=int, default=30)
    train.add_argument("--members", type=int, default=5, help="networks in the ensemble")
    train.add_argument("--workers", type=int, default=2, help="processes making the rooms")
    train.add_argument("--seed", type=int, default=0)
    train.set_defaults(handler=_train_box_refiner)


def _train_box_refiner(args: argparse.Namespace) -> int:
    for name in ("rooms", "validation_rooms", "epochs", "members", "workers"):
        if getattr(args, name) < 1:
            raise CliError(f"--{name.replace('_', '-')} must be at least 1")
    with needs_pytorch():
        from ..learning.box_refiner.train import BoxRefinerTraining, train_box_refiner
    metrics = train_box_refiner(
        BoxRefinerTraining(
            out=args.out,
            rooms=args.rooms,
            first_seed=args.first_seed,
            validation_rooms=args.validation_rooms,
            validation_seed=args.validation_seed,
            epochs=args.epochs,
            members=args.members,
            workers=args.workers,
            seed=args.seed,
        )
    )
    print(json.dumps(metrics, indent=1))
    return 0
