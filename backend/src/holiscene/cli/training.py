"""`holiscene train-rn`, `train-surfaces` and `train-detector`: the learned models, trained on
synthetic rooms (and, for the Relation Network, on the store's labelled scenes). They need
PyTorch (`pip install -e '.[train]'`)."""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

from holiscene_schema.classes import NYU40_CLASSES

from .common import CliError, needs_pytorch, settings_from

if TYPE_CHECKING:
    from ..learning.detector.data import BoxedPhoto
    from ..learning.samples import SupportSample

# Synthetic rooms for the detector: seeds no benchmark or other training uses.
DETECTOR_TRAIN_SEED = 400_000
DETECTOR_VALIDATION_SEED = 460_000


def add_relation_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    train = sub.add_parser(
        "train-rn", help="train the Relation Network on synthetic and stored labelled scenes"
    )
    train.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    train.add_argument("--seed", type=int, default=0)
    train.add_argument("--synthetic-scenes", type=int, default=800)
    train.add_argument("--max-epochs", type=int, default=20)
    train.add_argument("--patience", type=int, default=4)
    train.add_argument("--time-budget", type=float, help="stop training after this many seconds")
    train.add_argument(
        "--with-store",
        action="store_true",
        help="also learn from the labelled scenes stored in the data directory",
    )
    train.add_argument(
        "--register",
        action="store_true",
        help="add the new model to the data directory's registry (an admin makes it active)",
    )
    train.add_argument("--data-dir", type=Path)
    train.add_argument("--database-url")
    train.set_defaults(handler=_train_rn)


def add_surface_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    surfaces = sub.add_parser(
        "train-surfaces",
        help="train the Surface Network (floor, ceiling and wall labels) on synthetic rooms",
    )
    surfaces.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    surfaces.add_argument("--seed", type=int, default=0)
    surfaces.add_argument("--scenes", type=int, default=600, help="synthetic training rooms")
    surfaces.add_argument("--epochs", type=int, default=16)
    surfaces.set_defaults(handler=_train_surfaces)


def add_detector_training_command(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> None:
    detector = sub.add_parser(
        "train-detector",
        help="fine-tune the NYU-40 object detector's head on synthetic rooms (COCO backbone), "
        "or train one from scratch",
    )
    detector.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    detector.add_argument("--seed", type=int, default=0)
    detector.add_argument("--scenes", type=int, default=1400, help="synthetic training rooms")
    detector.add_argument("--validation-scenes", type=int, default=100)
    detector.add_argument("--epochs", type=int, default=16)
    detector.add_argument(
        "--views",
        type=int,
        default=1,
        help="randomised views of each training room (its features are kept in memory: "
        "about 4.3 MB a view)",
    )
    detector.add_argument(
        "--tune-deep-blocks",
        action="store_true",
        help="fine-tune the head's own copy of the backbone's stride-32 blocks too "
        "(the COCO model's outputs stay as they are)",
    )
    detector.add_argument(
        "--deep-blocks-learning-rate",
        type=float,
        default=None,
        help="--tune-deep-blocks: their learning rate as a share of the head's (default 0.1)",
    )
    detector.add_argument(
        "--retexture",
        type=float,
        default=0.0,
        help="chance that each synthetic object is repainted with a random pattern "
        "(stripes, checks, prints, speckle) in its own shading; 0: as rendered",
    )
    detector.add_argument(
        "--cushion-rows",
        action="store_true",
        help="train on rooms whose beds and sofas hold rows of cushions against their back "
        "(validation rooms stay the generator's default)",
    )
    detector.add_argument(
        "--coco-weight",
        type=float,
        default=1.0,
        help="weight of the COCO model's heatmap for the classes COCO knows (0: new head only)",
    )
    detector.add_argument(
        "--cache", type=Path, help="where rendered rooms are kept (default: ~/.cache/holiscene)"
    )
    detector.add_argument(
        "--from-scratch",
        action="store_true",
        help="train a small detector with no pretrained weights instead (for comparison)",
    )
    detector.add_argument(
        "--time-budget",
        type=float,
        help="--from-scratch: end training (annealed) after this many seconds",
    )
    detector.add_argument(
        "--on-picodet",
        action="store_true",
        help="train an NYU-40 class head on the COCO PicoDet's anchors instead, keeping its "
        "boxes (the CenterNet's options do not apply)",
    )
    detector.add_argument(
        "--branch-learning-rate",
        type=float,
        default=None,
        help="--on-picodet: the learning rate of the copies of PicoDet's class branches as a "
        "share of the head's (default 0.1; 0 keeps them as they are)",
    )
    detector.add_argument(
        "--unnamed",
        action="append",
        default=[],
        metavar="CLASS",
        help="--on-picodet: a class the exported head does not name (it still learns it; "
        "COCO's evidence for it stays); repeat for more",
    )
    detector.set_defaults(handler=_train_detector)


@contextlib.contextmanager
def _training_progress(name: str) -> Iterator[Callable[[float, str], None]]:
    """A progress bar fed by a training run's (fraction, line) reports; epoch lines stay."""
    from tqdm import tqdm

    with tqdm(total=100, desc=name, unit="%", file=sys.stderr) as bar:

        def progress(fraction: float, line: str) -> None:
            bar.update(round(100 * fraction) - bar.n)
            bar.set_postfix_str(line[:60])
            if line.startswith(("epoch", "done", "training")):
                tqdm.write(line, file=sys.stderr)

        yield progress


def _train_surfaces(args: argparse.Namespace) -> int:
    with needs_pytorch():
        from ..learning.surface_net import SurfaceTrainConfig, train_surface_model
    if args.out.exists() and any(args.out.iterdir()):
        raise CliError(f"{args.out} is not empty; give a new directory")
    if args.scenes < 1 or args.epochs < 1:
        raise CliError("--scenes and --epochs must be at least 1")
    config = SurfaceTrainConfig(
        seed=args.seed, train_seeds=(500_000, args.scenes), epochs=args.epochs
    )
    with _training_progress("train-surfaces") as progress:
        metrics = train_surface_model(config, args.out, progress)
    print(f"validation pixel accuracy {metrics['validation_pixel_accuracy']:.4f} -> {args.out}")
    return 0


def _train_detector(args: argparse.Namespace) -> int:
    with needs_pytorch():
        from ..learning.detector.data import synthetic_photos
        from ..learning.detector.train import DetectorTrainConfig, train_detector
    if args.out.exists() and any(args.out.iterdir()):
        raise CliError(f"{args.out} is not empty; give a new directory")
    if min(args.scenes, args.validation_scenes, args.epochs, args.views) < 1:
        raise CliError("--scenes, --validation-scenes, --epochs and --views must be at least 1")
    if not 0.0 <= args.coco_weight <= 1.0:
        raise CliError("--coco-weight must be between 0 and 1")
    if not 0.0 <= args.retexture <= 1.0:
        raise CliError("--retexture must be between 0 and 1")
    if args.time_budget is not None and not args.time_budget > 0:
        raise CliError("--time-budget must be a positive number of seconds")
    centernet_only = {
        "--from-scratch": args.from_scratch,
        "--tune-deep-blocks": args.tune_deep_blocks,
        "--deep-blocks-learning-rate": args.deep_blocks_learning_rate is not None,
        "--retexture": args.retexture > 0,
        "--cushion-rows": args.cushion_rows,
    }
    clashing = [flag for flag, given in centernet_only.items() if given]
    if args.on_picodet and clashing:
        raise CliError(f"--on-picodet trains PicoDet's class head; drop {', '.join(clashing)}")
    if args.branch_learning_rate is not None and not (
        args.on_picodet and args.branch_learning_rate >= 0
    ):
        raise CliError("--branch-learning-rate is for --on-picodet, at 0 or more")
    if args.unnamed and not args.on_picodet:
        raise CliError("--unnamed is for --on-picodet")
    unknown = [c for c in args.unnamed if c not in NYU40_CLASSES]
    if unknown:
        raise CliError(f"--unnamed: not NYU-40 classes: {', '.join(unknown)}")
    cache = args.cache or Path.home() / ".cache" / "holiscene" / "detector-rooms"
    with _training_progress("train-detector") as progress:

        def rendered(done: int, total: int) -> None:
            progress(0.0, f"rendering rooms {done}/{total}")

        config = DetectorTrainConfig(
            seed=args.seed,
            epochs=args.epochs,
            coco_weight=args.coco_weight,
            views=args.views,
            tune_deep_blocks=args.tune_deep_blocks,
            retexture=args.retexture,
            cushion_rows=args.cushion_rows,
        )
        if args.deep_blocks_learning_rate is not None:
            config = dataclasses.replace(
                config, deep_blocks_learning_rate=args.deep_blocks_learning_rate
            )
        train = synthetic_photos(
            range(DETECTOR_TRAIN_SEED, DETECTOR_TRAIN_SEED + args.scenes),
            cache,
            rendered,
            style=config.room_style,
        )
        validation = synthetic_photos(
            range(DETECTOR_VALIDATION_SEED, DETECTOR_VALIDATION_SEED + args.validation_scenes),
            cache,
            rendered,
        )
        if args.from_scratch:
            metrics = _train_scratch(args, train, validation, progress)
        elif args.on_picodet:
            metrics = _train_on_picodet(args, train, validation, progress)
        else:
            metrics = train_detector(train, validation, config, args.out, progress)
    print(f"validation mAP@0.5 {metrics['validation_map_at_0_5']:.3f} -> {args.out}")
    return 0


def _train_scratch(
    args: argparse.Namespace,
    train: list[BoxedPhoto],
    validation: list[BoxedPhoto],
    progress: Callable[[float, str], None],
) -> dict[str, Any]:
    from ..learning.detector.scratch_train import ScratchTrainConfig, train_scratch_detector

    config = ScratchTrainConfig(seed=args.seed, epochs=args.epochs, time_budget_s=args.time_budget)
    return train_scratch_detector(train, validation, config, args.out, progress)


def _train_on_picodet(
    args: argparse.Namespace,
    train: list[BoxedPhoto],
    validation: list[BoxedPhoto],
    progress: Callable[[float, str], None],
) -> dict[str, Any]:
    from ..learning.detector.picodet_train import PicoDetHeadConfig, train_picodet_head

    config = PicoDetHeadConfig(
        seed=args.seed,
        epochs=args.epochs,
        views=args.views,
        coco_weight=args.coco_weight,
        unnamed=tuple(args.unnamed),
    )
    if args.branch_learning_rate is not None:
        config = dataclasses.replace(config, branch_learning_rate=args.branch_learning_rate)
    return train_picodet_head(train, validation, config, args.out, progress)


def _train_rn(args: argparse.Namespace) -> int:
    from ..learning.training_api import TrainConfig

    with needs_pytorch():
        from ..learning.train import train_relation_model
    if args.out.exists() and any(args.out.iterdir()):
        raise CliError(f"{args.out} is not empty; give a new directory")
    if args.synthetic_scenes < 0 or args.max_epochs < 1 or args.patience < 1:
        raise CliError("--synthetic-scenes must be >= 0, --max-epochs and --patience >= 1")
    labelled = _stored_samples(args) if args.with_store else []
    config = TrainConfig(
        seed=args.seed,
        synthetic_scenes=args.synthetic_scenes,
        max_epochs=args.max_epochs,
        patience=args.patience,
        time_budget_s=args.time_budget,
    )
    with _training_progress("train-rn") as progress:
        try:
            result = train_relation_model(config, labelled, args.out, progress)
        except ValueError as error:
            raise CliError(str(error)) from error
    print(f"validation accuracy {result.validation_accuracy:.4f} -> {result.model_dir}")
    if args.register:
        _register_model(args, result.model_dir, result.validation_accuracy)
    return 0


def _register_model(args: argparse.Namespace, model_dir: Path, accuracy: float) -> None:
    from ..learning.training_api import DATA_FILE
    from ..services.workbench import Workbench
    from ..store.model_registry import Registration

    workbench = Workbench(settings_from(args))
    try:
        info = workbench.models.register(
            model_dir,
            Registration(
                status="candidate",
                validation_accuracy=accuracy,
                data=json.loads((model_dir / DATA_FILE).read_text()),
                note="trained with holiscene train-rn",
            ),
            actor="train-rn",
        )
    finally:
        workbench.close()
    print(f"registered as model {info.id} (version {info.version}); make it active in #/models")


def _stored_samples(args: argparse.Namespace) -> list[SupportSample]:
    """The samples of the labelled scenes in the store (what a retrain job learns from)."""
    from ..services.relation_retraining import stored_samples
    from ..services.workbench import Workbench

    workbench = Workbench(settings_from(args))
    try:
        return stored_samples(workbench.scenes)
    finally:
        workbench.close()
