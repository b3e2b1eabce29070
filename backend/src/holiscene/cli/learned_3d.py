"""`holiscene train-3d`: the learned networks of thesis Ch. 5 (needs PyTorch:
`pip install -e '.[train]'`), each trained on synthetic rooms.

    holiscene train-3d scene-net -o DIR --cache CACHE   # LEN + ODN (docs/scene-net.md)
    holiscene train-3d meshes -o DIR                    # the mesh network (docs/mesh-net.md)
    holiscene train-3d box-refiner -o DIR               # the 3D box refiner (docs/box-refiner.md)
    holiscene train-3d all -o DIR                       # the three, one folder each

`all` trains them one after the other with their defaults (about 1.5 hours on 2 cores);
`--scale` shrinks every count and time budget for a quick try."""

from __future__ import annotations

import argparse
import json
import time
from collections.abc import Callable
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any, TypeVar

from ..learning.box_refiner.config import BoxRefinerTraining
from ..learning.mesh_net.config import MeshNetTraining
from ..learning.scene_net.config import SceneNetTrainConfig
from .common import CliError, needs_pytorch

NETWORK_FOLDERS = {
    "scene-net": "scene_net_model",
    "meshes": "mesh_net_model",
    "box-refiner": "box_refiner_model",
}  # the names of the committed models' folders in holiscene/learning/


# The CLI's runs take their defaults from the training configs (torch-free modules), so a
# default lives in one place; the box refiner's run is its config itself.


@dataclass(frozen=True)
class SceneNetRun:
    """SceneNetTrainConfig's options, with where the model and the rendered rooms go."""

    out: Path
    cache: Path
    rooms: int = SceneNetTrainConfig.rooms
    validation_rooms: int = SceneNetTrainConfig.validation_rooms
    views: int = SceneNetTrainConfig.views
    seed: int = 0
    time_budget: float = SceneNetTrainConfig.budget_s


@dataclass(frozen=True)
class MeshNetRun:
    """MeshNetTraining's options, named as the command's."""

    out: Path
    views: int = MeshNetTraining.train_views
    validation_views: int = MeshNetTraining.validation_views
    seed: int = 0
    time_budget: float = MeshNetTraining.time_budget


def add_learned_3d_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    train = sub.add_parser(
        "train-3d",
        help="train the learned 3D networks (LEN + ODN, mesh network, box refiner) on "
        "synthetic rooms",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    networks = train.add_subparsers(required=True, metavar="NETWORK")

    scene = networks.add_parser(
        "scene-net", help="the layout and object networks (LEN + ODN, single photos)"
    )
    _add_out(scene)
    scene.add_argument(
        "--cache",
        type=Path,
        required=True,
        help="folder for the rendered rooms and their features (reused by a second run)",
    )
    scene.add_argument("--rooms", type=int, default=SceneNetRun.rooms, help="training rooms")
    scene.add_argument("--validation-rooms", type=int, default=SceneNetRun.validation_rooms)
    scene.add_argument(
        "--views", type=int, default=SceneNetRun.views, help="randomised views of each room"
    )
    scene.add_argument("--seed", type=int, default=0)
    _add_time_budget(scene, SceneNetRun.time_budget)
    scene.set_defaults(handler=lambda args: _report(_train_scene_net(_run_from(SceneNetRun, args))))

    meshes = networks.add_parser(
        "meshes", help="the mesh network (template deformation and cutting, single photos)"
    )
    _add_out(meshes)
    meshes.add_argument("--views", type=int, default=MeshNetRun.views, help="training views")
    meshes.add_argument("--validation-views", type=int, default=MeshNetRun.validation_views)
    meshes.add_argument("--seed", type=int, default=0)
    _add_time_budget(meshes, MeshNetRun.time_budget)
    meshes.set_defaults(handler=lambda args: _report(_train_meshes(_run_from(MeshNetRun, args))))

    refiner = networks.add_parser(
        "box-refiner", help="the 3D box refiner (single photos run through the geometry)"
    )
    _add_out(refiner)
    refiner.add_argument(
        "--rooms", type=int, default=BoxRefinerTraining.rooms, help="training rooms"
    )
    refiner.add_argument(
        "--first-seed", type=int, default=BoxRefinerTraining.first_seed, help="first room's seed"
    )
    refiner.add_argument(
        "--validation-rooms", type=int, default=BoxRefinerTraining.validation_rooms
    )
    refiner.add_argument("--validation-seed", type=int, default=BoxRefinerTraining.validation_seed)
    refiner.add_argument("--epochs", type=int, default=BoxRefinerTraining.epochs)
    refiner.add_argument(
        "--members", type=int, default=BoxRefinerTraining.members, help="networks in the ensemble"
    )
    refiner.add_argument(
        "--workers",
        type=int,
        default=BoxRefinerTraining.workers,
        help="processes making the rooms and training the members",
    )
    refiner.add_argument("--seed", type=int, default=0)
    refiner.add_argument(
        "--room-cache",
        type=Path,
        help="keep the rooms made in this folder and reuse those already there",
    )
    refiner.set_defaults(
        handler=lambda args: _report(_train_box_refiner(_run_from(BoxRefinerTraining, args)))
    )

    every = networks.add_parser(
        "all",
        help="the three networks one after the other, each in its own folder of -o",
    )
    _add_out(every)
    every.add_argument(
        "--cache",
        type=Path,
        help="the scene networks' rendered rooms (default: OUT/scene_net_cache)",
    )
    every.add_argument(
        "--scale",
        type=float,
        default=1.0,
        help="fraction of every default count and time budget (0.05 for a quick try)",
    )
    every.add_argument("--seed", type=int, default=0)
    every.set_defaults(handler=_train_all)


def _add_out(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("-o", "--out", type=Path, required=True, help="new model directory")


def _add_time_budget(parser: argparse.ArgumentParser, default: float) -> None:
    parser.add_argument(
        "--time-budget", type=float, default=default, help="seconds of training (annealed)"
    )


RunT = TypeVar("RunT", SceneNetRun, MeshNetRun, BoxRefinerTraining)


def _run_from(run_type: type[RunT], args: argparse.Namespace) -> RunT:
    """A network's run from its subcommand's options, which carry the run's field names (the
    fields no option sets, such as the training curves, keep their defaults)."""
    given = {f.name: getattr(args, f.name) for f in fields(run_type) if hasattr(args, f.name)}
    return run_type(**given)


def plan_all(
    out: Path, cache: Path | None, scale: float, seed: int
) -> tuple[SceneNetRun, MeshNetRun, BoxRefinerTraining]:
    """`train-3d all`: each network's run with its defaults times `scale`, in its own folder
    named as the committed model's."""
    if not 0.0 < scale <= 1.0:
        raise CliError("--scale must be above 0 and at most 1")

    def count(default: int, least: int = 1) -> int:
        return max(least, round(default * scale))

    return (
        SceneNetRun(
            out=out / NETWORK_FOLDERS["scene-net"],
            cache=cache or out / "scene_net_cache",
            rooms=count(SceneNetRun.rooms, 2),
            validation_rooms=count(SceneNetRun.validation_rooms, 2),
            views=SceneNetRun.views,
            seed=seed,
            time_budget=SceneNetRun.time_budget * scale,
        ),
        MeshNetRun(
            out=out / NETWORK_FOLDERS["meshes"],
            views=count(MeshNetRun.views, 8),
            validation_views=count(MeshNetRun.validation_views, 4),
            seed=seed,
            time_budget=MeshNetRun.time_budget * scale,
        ),
        BoxRefinerTraining(
            out=out / NETWORK_FOLDERS["box-refiner"],
            rooms=count(BoxRefinerTraining.rooms, 2),
            validation_rooms=count(BoxRefinerTraining.validation_rooms, 2),
            epochs=count(BoxRefinerTraining.epochs),
            members=count(BoxRefinerTraining.members, 2),
            workers=BoxRefinerTraining.workers,
            seed=seed,
        ),
    )


def _train_all(args: argparse.Namespace) -> int:
    scene, meshes, refiner = plan_all(args.out, args.cache, args.scale, args.seed)
    steps: list[tuple[str, Callable[[], dict[str, Any]]]] = [
        ("scene-net", lambda: _train_scene_net(scene)),
        ("meshes", lambda: _train_meshes(meshes)),
        ("box-refiner", lambda: _train_box_refiner(refiner)),
    ]
    summary: dict[str, Any] = {}
    for number, (name, train) in enumerate(steps, start=1):
        print(f"[{number}/{len(steps)}] train-3d {name}", flush=True)
        started = time.monotonic()
        summary[name] = {"metrics": train(), "minutes": (time.monotonic() - started) / 60}
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "summary.json").write_text(json.dumps(summary, indent=1))
    return _report(summary)


def _report(metrics: dict[str, Any]) -> int:
    print(json.dumps(metrics, indent=1))
    return 0


def _check_counts(run: object, names: tuple[str, ...]) -> None:
    for name in names:
        if getattr(run, name) < 1:
            raise CliError(f"--{name.replace('_', '-')} must be at least 1")


def _train_scene_net(run: SceneNetRun) -> dict[str, Any]:
    _check_counts(run, ("rooms", "validation_rooms", "views"))
    with needs_pytorch():
        from ..learning.scene_net.train import train_scene_net

    config = SceneNetTrainConfig(
        rooms=run.rooms,
        validation_rooms=run.validation_rooms,
        budget_s=run.time_budget,
        views=run.views,
        seed=run.seed,
    )
    metrics: dict[str, Any] = train_scene_net(run.out, run.cache, config)["validation"]
    return metrics


def _train_meshes(run: MeshNetRun) -> dict[str, Any]:
    _check_counts(run, ("views", "validation_views"))
    with needs_pytorch():
        from ..learning.mesh_net.train import train_mesh_net

    metrics: dict[str, Any] = train_mesh_net(
        MeshNetTraining(
            out=run.out,
            train_views=run.views,
            validation_views=run.validation_views,
            seed=run.seed,
            time_budget=run.time_budget,
        )
    )
    return metrics


def _train_box_refiner(run: BoxRefinerTraining) -> dict[str, Any]:
    _check_counts(run, ("rooms", "validation_rooms", "epochs", "members", "workers"))
    with needs_pytorch():
        from ..learning.box_refiner.train import train_box_refiner

    metrics: dict[str, Any] = train_box_refiner(run)
    return metrics
