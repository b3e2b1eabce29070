"""`holiscene train-meshes`: the mesh network (needs PyTorch: `pip install -e '.[train]'`),
trained on library objects seen from room viewpoints."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from .common import needs_pytorch


def add_mesh_net_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    train = sub.add_parser(
        "train-meshes",
        help="train the mesh network (template deformation, single photos) on library objects",
    )
    train.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    train.add_argument("--seed", type=int, default=0)
    train.add_argument("--views", type=int, default=16000, help="training views")
    train.add_argument("--validation-views", type=int, default=400)
    train.add_argument(
        "--time-budget", type=float, default=1500.0, help="seconds of training (annealed)"
    )
    train.set_defaults(handler=_train_meshes)


def _train_meshes(args: argparse.Namespace) -> int:
    with needs_pytorch():
        from ..learning.mesh_net.train import MeshNetTraining, train_mesh_net

    metrics = train_mesh_net(
        MeshNetTraining(
            out=args.out,
            train_views=args.views,
            validation_views=args.validation_views,
            seed=args.seed,
            time_budget=args.time_budget,
        )
    )
    print(json.dumps(metrics, indent=1))
    return 0
