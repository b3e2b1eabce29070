"""`holiscene`: run the pipeline on a folder, serve the workbench, load demo scenes."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import sys
import tempfile
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from .cli_users import UsersCliError, add_user_commands
from .core.settings import REPO_ROOT, Settings

if TYPE_CHECKING:
    from .learning.samples import SupportSample

DEMO_PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"
DEMO_FOLDERS = ("t3d-5", "im3d-6", "mm3d-4", "im3d-3")
DEMO_SYNTH_SEEDS = (12, 15, 14, 11)  # varied rooms that read well at a glance


class CliError(Exception):
    """A message for the user; the command exits with status 2."""


def main(argv: Sequence[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        result: int = args.handler(args)
        return result
    except (CliError, UsersCliError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="holiscene", description=__doc__)
    sub = parser.add_subparsers(required=True, metavar="COMMAND")

    infer = sub.add_parser("infer", help="run the pipeline on an input folder")
    infer.add_argument(
        "input_dir", type=Path, help="folder with img.jpg|img.png [cam_K.txt] [detections.json]"
    )
    infer.add_argument(
        "-o", "--out", type=Path, required=True, help="folder for scene.json and scene.glb"
    )
    infer.add_argument("--stages", help="comma-separated stage names (default: the full pipeline)")
    infer.add_argument(
        "--models", type=Path, help="folder of your own models: <class>/*.obj|glb|ply"
    )
    infer.set_defaults(handler=_infer)

    synth = sub.add_parser("synth", help="generate synthetic scenes with exact ground truth")
    synth.add_argument("--seed", type=int, default=0, help="first seed; scene i uses seed + i")
    synth.add_argument("--count", type=int, default=1)
    synth.add_argument("-o", "--out", type=Path, required=True)
    synth.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    synth.set_defaults(handler=_synth)

    evaluate = sub.add_parser("eval", help="score predictions against ground truth")
    evaluate.add_argument("pred_dir", type=Path, help="folders with scene.json (from infer)")
    evaluate.add_argument("gt_dir", type=Path, help="folders with gt.json (from synth)")
    evaluate.add_argument("--out", type=Path, help="where to write eval.json and eval.md")
    evaluate.set_defaults(handler=_eval)

    serve = sub.add_parser("serve", help="start the workbench server")
    serve.add_argument("--host", help="address to bind (default 127.0.0.1)")
    serve.add_argument("--port", type=int, help="port (default 8000)")
    serve.add_argument("--data-dir", type=Path, help="data directory (default var/data)")
    serve.add_argument("--database-url", help="SQLAlchemy URL (default: SQLite in the data dir)")
    serve.add_argument(
        "--allow-remote",
        action="store_true",
        help="bind beyond loopback (needs an admin account: holiscene users add)",
    )
    serve.set_defaults(handler=_serve)

    add_user_commands(sub, _settings)

    demo = sub.add_parser("demo", help="load demo scenes into an empty database")
    demo.add_argument("--data-dir", type=Path)
    demo.add_argument("--database-url")
    demo.set_defaults(handler=_demo)

    imp = sub.add_parser("import", help="import input folders as scenes and run the pipeline")
    imp.add_argument("folders", type=Path, nargs="+")
    imp.add_argument("--data-dir", type=Path)
    imp.add_argument("--database-url")
    imp.set_defaults(handler=_import)

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

    surfaces = sub.add_parser(
        "train-surfaces",
        help="train the Surface Network (floor, ceiling and wall labels) on synthetic rooms",
    )
    surfaces.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    surfaces.add_argument("--seed", type=int, default=0)
    surfaces.add_argument("--scenes", type=int, default=600, help="synthetic training rooms")
    surfaces.add_argument("--epochs", type=int, default=16)
    surfaces.set_defaults(handler=_train_surfaces)

    detector = sub.add_parser(
        "train-detector",
        help="fine-tune the NYU-40 object detector's head on synthetic rooms (COCO backbone)",
    )
    detector.add_argument("-o", "--out", type=Path, required=True, help="new model directory")
    detector.add_argument("--seed", type=int, default=0)
    detector.add_argument("--scenes", type=int, default=1400, help="synthetic training rooms")
    detector.add_argument("--validation-scenes", type=int, default=100)
    detector.add_argument("--epochs", type=int, default=16)
    detector.add_argument(
        "--coco-weight",
        type=float,
        default=1.0,
        help="weight of the COCO model's heatmap for the classes COCO knows (0: new head only)",
    )
    detector.add_argument(
        "--cache", type=Path, help="where rendered rooms are kept (default: ~/.cache/holiscene)"
    )
    detector.set_defaults(handler=_train_detector)

    view = sub.add_parser("view", help="review a scene in a viser viewer on 127.0.0.1")
    view.add_argument("scene", help="a scene id of the store, or a scene.json path (or folder)")
    view.add_argument("--port", type=int, default=8080, help="port (default 8080; 0: any free)")
    view.add_argument("--photo", type=Path, help="the photo, when it is not beside scene.json")
    view.add_argument("--data-dir", type=Path, help="the store's data directory (scene ids)")
    view.add_argument("--database-url")
    view.set_defaults(handler=_view)
    return parser


def _settings(args: argparse.Namespace) -> Settings:
    overrides = {
        key: value
        for key, value in {
            "data_dir": getattr(args, "data_dir", None),
            "database_url": getattr(args, "database_url", None),
            "host": getattr(args, "host", None),
            "port": getattr(args, "port", None),
        }.items()
        if value is not None
    }
    return Settings(**overrides)


def _is_input_folder(folder: Path) -> bool:
    return any((folder / n).is_file() for n in ("img.jpg", "img.jpeg", "img.png"))


def _infer(args: argparse.Namespace) -> int:
    """One input folder, or a folder of input folders (then OUT/<name>/ for each)."""
    from tqdm import tqdm

    from .pipeline import DEFAULT_STAGES

    stages = [s.strip() for s in args.stages.split(",")] if args.stages else list(DEFAULT_STAGES)
    if _is_input_folder(args.input_dir) or not args.input_dir.is_dir():
        _infer_one(args.input_dir, args.out, stages, args.models, verbose=True)
        print(args.out / "scene.json")
        return 0
    folders = sorted(f for f in args.input_dir.iterdir() if f.is_dir() and _is_input_folder(f))
    if not folders:
        raise CliError(f"{args.input_dir} holds neither img.jpg/img.png nor input folders")
    for folder in tqdm(folders, desc="infer", unit="scene", file=sys.stderr):
        _infer_one(folder, args.out / folder.name, stages, args.models, verbose=False)
    print(f"{len(folders)} scenes written to {args.out}")
    return 0


def _infer_one(
    folder: Path, out: Path, stages: list[str], models: Path | None, verbose: bool
) -> None:
    from tqdm import tqdm

    from .inference import infer_scene
    from .inputs import InputError, read_input_folder
    from .pipeline import PipelineBuildError

    try:
        inputs = read_input_folder(folder)
        with tqdm(
            total=len(stages), desc="pipeline", unit="stage", file=sys.stderr, disable=not verbose
        ) as bar:

            def progress(stage: str, _fraction: float) -> None:
                bar.set_postfix_str(stage)
                if stage != stages[0]:
                    bar.update(1)

            result = infer_scene(
                inputs,
                name=folder.resolve().name,
                image_file=f"img{inputs.photo.suffix}",
                stages=stages,
                models_dir=models,
                progress=progress,
            )
    except (InputError, PipelineBuildError, ValueError) as exc:
        raise CliError(f"{folder}: {exc}" if not verbose else str(exc)) from exc
    out.mkdir(parents=True, exist_ok=True)
    scene_json = json.dumps(result.scene.model_dump(mode="json"), indent=1) + "\n"
    _write_atomic(out / "scene.json", scene_json.encode())
    if result.glb is not None:
        _write_atomic(out / "scene.glb", result.glb)
    if verbose:
        for run in result.scene.stages:
            note = f"  ({run.note})" if run.note else ""
            print(f"{run.name:28s} {run.seconds:7.3f} s{note}", file=sys.stderr)


def _synth(args: argparse.Namespace) -> int:
    import time
    from concurrent.futures import ProcessPoolExecutor

    from tqdm import tqdm

    from .synth.generate import synthesize_to

    if args.count < 1 or args.workers < 1:
        raise CliError("--count and --workers must be at least 1")
    seeds = range(args.seed, args.seed + args.count)
    start = time.perf_counter()
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        jobs = pool.map(synthesize_to, seeds, [args.out] * len(seeds))
        for _ in tqdm(jobs, total=len(seeds), desc="synth", unit="scene", file=sys.stderr):
            pass
    seconds = time.perf_counter() - start
    rate = args.count / seconds
    print(f"{args.count} scenes in {seconds:.1f} s ({rate:.2f} scenes/s) -> {args.out}")
    return 0


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
    try:
        from .learning.surface_net import SurfaceTrainConfig, train_surface_model
    except ImportError as error:
        raise CliError(f"training needs PyTorch: pip install -e '.[train]' ({error})") from error
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


# Synthetic rooms for the detector: seeds no benchmark or other training uses.
DETECTOR_TRAIN_SEED = 400_000
DETECTOR_VALIDATION_SEED = 460_000


def _train_detector(args: argparse.Namespace) -> int:
    try:
        from .learning.detector.data import synthetic_photos
        from .learning.detector.train import DetectorTrainConfig, train_detector
    except ImportError as error:
        raise CliError(f"training needs PyTorch: pip install -e '.[train]' ({error})") from error
    if args.out.exists() and any(args.out.iterdir()):
        raise CliError(f"{args.out} is not empty; give a new directory")
    if min(args.scenes, args.validation_scenes, args.epochs) < 1:
        raise CliError("--scenes, --validation-scenes and --epochs must be at least 1")
    if not 0.0 <= args.coco_weight <= 1.0:
        raise CliError("--coco-weight must be between 0 and 1")
    cache = args.cache or Path.home() / ".cache" / "holiscene" / "detector-rooms"
    with _training_progress("train-detector") as progress:

        def rendered(done: int, total: int) -> None:
            progress(0.0, f"rendering rooms {done}/{total}")

        train = synthetic_photos(
            range(DETECTOR_TRAIN_SEED, DETECTOR_TRAIN_SEED + args.scenes), cache, rendered
        )
        validation = synthetic_photos(
            range(DETECTOR_VALIDATION_SEED, DETECTOR_VALIDATION_SEED + args.validation_scenes),
            cache,
            rendered,
        )
        config = DetectorTrainConfig(
            seed=args.seed, epochs=args.epochs, coco_weight=args.coco_weight
        )
        metrics = train_detector(train, validation, config, args.out, progress)
    print(f"validation mAP@0.5 {metrics['validation_map_at_0_5']:.3f} -> {args.out}")
    return 0


def _train_rn(args: argparse.Namespace) -> int:
    from .learning.training_api import TrainConfig

    try:
        from .learning.train import train_relation_model
    except ImportError as error:
        raise CliError(f"training needs PyTorch: pip install -e '.[train]' ({error})") from error
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
    from .learning.training_api import DATA_FILE
    from .store.models import Registration
    from .workbench import Workbench

    workbench = Workbench(_settings(args))
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
    from .retraining import stored_samples
    from .workbench import Workbench

    workbench = Workbench(_settings(args))
    try:
        return stored_samples(workbench.scenes)
    finally:
        workbench.close()


def _eval(args: argparse.Namespace) -> int:
    from .evaluation.report import markdown_report
    from .evaluation.run import EvaluationInputError, evaluate_folders

    try:
        run = evaluate_folders(args.pred_dir, args.gt_dir)
    except EvaluationInputError as exc:
        raise CliError(str(exc)) from exc
    summary = run.evaluation.summary()
    summary["missing_predictions"] = run.missing_predictions
    report = markdown_report(summary, f"Evaluation of {args.pred_dir} against {args.gt_dir}")
    out = args.out or args.pred_dir
    out.mkdir(parents=True, exist_ok=True)
    _write_atomic(out / "eval.json", (json.dumps(summary, indent=1) + "\n").encode())
    _write_atomic(out / "eval.md", report.encode())
    print(report)
    if run.missing_predictions:
        print(f"missing predictions (scored as empty): {', '.join(run.missing_predictions)}")
    return 0


def _write_atomic(path: Path, data: bytes) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def _serve(args: argparse.Namespace) -> int:
    import uvicorn

    from .api.app import create_app
    from .cli_users import check_can_serve
    from .core.data_dir_owner import DataDirInUseError, own_data_dir
    from .core.database_owner import DatabaseInUseError, own_database

    settings = _settings(args)
    # Owned before anything reads or writes the data: start-up recovery fails unfinished jobs,
    # which must not happen to the jobs of a server already running on it.
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(own_data_dir(settings.data_dir))
            held.enter_context(own_database(settings.resolved_database_url))
        except (DataDirInUseError, DatabaseInUseError) as exc:
            raise CliError(str(exc)) from exc
        check_can_serve(settings, args.allow_remote)
        uvicorn.run(create_app(settings), host=settings.host, port=settings.port, log_level="info")
    return 0


def _demo(args: argparse.Namespace) -> int:
    from .synth.generate import synthesize_to
    from .workbench import Workbench

    settings = _settings(args)
    workbench = Workbench(settings)
    try:
        if workbench.scenes.list_summaries():
            print("the database already holds scenes; no demo scenes loaded")
            return 0
        synthetic_dir = settings.data_dir / "demo-inputs"
        folders = [synthesize_to(seed, synthetic_dir) for seed in DEMO_SYNTH_SEEDS]
        folders += [DEMO_PHOTOS / name for name in DEMO_FOLDERS if (DEMO_PHOTOS / name).is_dir()]
        for folder in folders:
            result = workbench.import_folder(folder)
            print(f"loaded demo scene {folder.name}: {result.job.status if result.job else '-'}")
    finally:
        workbench.close()
    return 0


def _import(args: argparse.Namespace) -> int:
    from .inputs import InputError
    from .workbench import Workbench

    workbench = Workbench(_settings(args))
    failures = 0
    try:
        for folder in args.folders:
            try:
                result = workbench.import_folder(folder)
            except InputError as exc:
                print(f"error: {folder}: {exc}", file=sys.stderr)
                failures += 1
                continue
            job = result.job
            print(f"{folder}: scene {result.scene.id}, pipeline {job.status if job else '-'}")
            if job and job.status == "failed":
                failures += 1
    finally:
        workbench.close()
    return 1 if failures else 0


def _view(args: argparse.Namespace) -> int:
    from .viewer import ViewerInputError
    from .viewer.run import serve_until_interrupted

    if not 0 <= args.port <= 65535:
        raise CliError(f"--port {args.port} is not a port number")
    try:
        return serve_until_interrupted(args.scene, _settings(args), args.port, args.photo)
    except ViewerInputError as exc:
        raise CliError(str(exc)) from exc


if __name__ == "__main__":
    raise SystemExit(main())
