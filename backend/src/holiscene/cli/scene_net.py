"""`holiscene train-scene-net`: the layout and object networks (LEN + ODN; needs PyTorch:
`pip install -e '.[train]'`), trained together on synthetic rooms."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from .common import needs_pytorch


def add_scene_net_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    train = sub.add_parser(
        "train-scene-net",
        help="train the layout and object networks (LEN + ODN, single photos) on synthetic rooms",
    )
    train.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    train.add_argument(
        "--cache",
        type=Path,
        required=True,
        help="folder for the rendered rooms and their features (reused by a second run)",
    )
    train.add_argument("--rooms", type=int, default=2400, help="training rooms")
    train.add_argument("--validation-rooms", type=int, default=200)
    train.add_argument("--views", type=int, default=2, help="randomised views of each room")
    train.add_argument("--seed", type=int, default=0)
    train.add_argument(
        "--time-budget", type=float, default=1200.0, help="seconds of training (annealed)"
    )
    train.set_defaults(handler=_train_scene_net)


def _train_scene_net(args: argparse.Namespace) -> int:
    with needs_pytorch():
        from ..learning.scene_net.train import SceneNetTrainConfig, train_scene_net

    config = SceneNetTrainConfig(
        rooms=args.rooms,
        validation_rooms=args.validation_rooms,
        budget_s=args.time_budget,
        views=args.views,
        seed=args.seed,
    )
    metrics = train_scene_net(args.out, args.cache, config)
    print(json.dumps(metrics["validation"], indent=1))
    return 0
