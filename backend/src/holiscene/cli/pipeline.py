"""`holiscene infer`, `synth` and `eval`: the pipeline on input folders, synthetic scenes with
their ground truth, and the scores of one against the other; no store involved, but for
`eval --store`, which scores the stored scenes imported with ground truth."""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from .common import CliError, settings_from, write_atomic


def add_pipeline_commands(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    infer = sub.add_parser("infer", help="run the pipeline on an input folder")
    infer.add_argument(
        "input_dir",
        type=Path,
        help="folder with img.jpg|img.png [cam_K.txt] [detections.json] [depth.png]",
    )
    infer.add_argument(
        "-o", "--out", type=Path, required=True, help="folder for scene.json and scene.glb"
    )
    infer.add_argument("--stages", help="comma-separated stage names (default: the full pipeline)")
    infer.add_argument(
        "--no-depth",
        dest="use_depth",
        action="store_false",
        help="ignore depth.png: the single-photo path on a folder that has depth",
    )
    infer.add_argument(
        "--models", type=Path, help="folder of your own models: <class>/*.obj|glb|ply"
    )
    infer.set_defaults(handler=_infer)

    synth = sub.add_parser("synth", help="generate synthetic scenes with exact ground truth")
    synth.add_argument("--seed", type=int, default=0, help="first seed; scene i uses seed + i")
    synth.add_argument("--count", type=int, default=1)
    synth.add_argument("-o", "--out", type=Path, required=True)
    synth.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    synth.add_argument(
        "--cushion-rows",
        action="store_true",
        help="beds and sofas hold rows of cushions against their back (the detector's rooms); "
        "folders are named synth-SEED-cushion-rows",
    )
    synth.set_defaults(handler=_synth)

    evaluate = sub.add_parser(
        "eval",
        help="score predictions against ground truth",
        usage="holiscene eval PRED_DIR GT_DIR [--out DIR]\n"
        "       holiscene eval --store [--scene ID ...] [--rerun] [--data-dir D] "
        "[--database-url U] [--out DIR]",
    )
    evaluate.add_argument(
        "pred_dir", type=Path, nargs="?", help="folders with scene.json (from infer)"
    )
    evaluate.add_argument("gt_dir", type=Path, nargs="?", help="folders with gt.json (from synth)")
    evaluate.add_argument(
        "--out",
        type=Path,
        help="where to write eval.json and eval.md (default: PRED_DIR; with --store: "
        "<data dir>/eval)",
    )
    evaluate.add_argument(
        "--shapes",
        action="store_true",
        help="also score each object's mesh, and the raw depth points, against the true mesh",
    )
    store = evaluate.add_argument_group("stored scenes imported with ground truth (gt.json)")
    store.add_argument("--store", action="store_true", help="score the stored scenes")
    store.add_argument(
        "--scene", dest="scene_ids", action="append", metavar="ID", help="(repeat; default: all)"
    )
    store.add_argument(
        "--rerun",
        action="store_true",
        help="run the pipeline afresh on each scene's photo and boxes, without people's labels",
    )
    store.add_argument(
        "--no-depth",
        dest="use_depth",
        action="store_false",
        help="with --rerun: the single-photo pipeline, even for scenes stored with depth",
    )
    store.add_argument("--data-dir", type=Path)
    store.add_argument("--database-url")
    evaluate.set_defaults(handler=_eval)


def _is_input_folder(folder: Path) -> bool:
    return any((folder / n).is_file() for n in ("img.jpg", "img.jpeg", "img.png"))


def _infer(args: argparse.Namespace) -> int:
    """One input folder, or a folder of input folders (then OUT/<name>/ for each)."""
    from tqdm import tqdm

    # Without --stages, each folder gets a full run (keeping a layout set by hand).
    stages = [s.strip() for s in args.stages.split(",")] if args.stages else None
    if _is_input_folder(args.input_dir) or not args.input_dir.is_dir():
        _infer_one(args.input_dir, args.out, stages, args, verbose=True)
        print(args.out / "scene.json")
        return 0
    folders = sorted(f for f in args.input_dir.iterdir() if f.is_dir() and _is_input_folder(f))
    if not folders:
        raise CliError(f"{args.input_dir} holds neither img.jpg/img.png nor input folders")
    for folder in tqdm(folders, desc="infer", unit="scene", file=sys.stderr):
        _infer_one(folder, args.out / folder.name, stages, args, verbose=False)
    print(f"{len(folders)} scenes written to {args.out}")
    return 0


def _infer_one(
    folder: Path, out: Path, chosen: list[str] | None, args: argparse.Namespace, verbose: bool
) -> None:
    from tqdm import tqdm

    from ..inputs import InputError, read_input_folder
    from ..pipeline import PipelineBuildError
    from ..services.reconstruction import full_run_stages, imported_scene, reconstruct_scene

    try:
        inputs = read_input_folder(folder, use_depth=args.use_depth)
        name = folder.resolve().name
        # A folder exported from the app (scene.json beside the photo) keeps a room layout
        # set by hand, as a re-run in the app does; --stages runs exactly what it names.
        stages, options = (
            (chosen, None) if chosen else full_run_stages(imported_scene(inputs, name))
        )
        with tqdm(
            total=len(stages), desc="pipeline", unit="stage", file=sys.stderr, disable=not verbose
        ) as bar:

            def progress(stage: str, _fraction: float) -> None:
                bar.set_postfix_str(stage)
                if stage == "done":  # the depth stages are skipped for a photo without depth
                    bar.update(len(stages) - bar.n)
                elif stage != stages[0]:
                    bar.update(1)

            result = reconstruct_scene(
                inputs,
                name=name,
                image_file=f"img{inputs.photo.suffix}",
                # supports.json: people's labels, kept as they are (gt.json is not used here).
                pinned_supports=inputs.supports,
                stages=stages,
                models_dir=args.models,
                stage_options=options,
                progress=progress,
            )
    except (InputError, PipelineBuildError, ValueError) as exc:
        raise CliError(f"{folder}: {exc}" if not verbose else str(exc)) from exc
    out.mkdir(parents=True, exist_ok=True)
    scene_json = json.dumps(result.scene.model_dump(mode="json"), indent=1) + "\n"
    write_atomic(out / "scene.json", scene_json.encode())
    if result.glb is not None:
        write_atomic(out / "scene.glb", result.glb)
    if inputs.depth is not None and result.scene.depth is not None:
        # scene.json's depth reference names the file beside it.
        write_atomic(out / result.scene.depth.file, inputs.depth.png)
    if verbose:
        for run in result.scene.stages:
            note = f"  ({run.note})" if run.note else ""
            print(f"{run.name:28s} {run.seconds:7.3f} s{note}", file=sys.stderr)


def _synth(args: argparse.Namespace) -> int:
    import time
    from concurrent.futures import ProcessPoolExecutor

    from tqdm import tqdm

    from ..synth.generate import synthesize_to
    from ..synth.plan import RoomStyle

    if args.count < 1 or args.workers < 1:
        raise CliError("--count and --workers must be at least 1")
    seeds = range(args.seed, args.seed + args.count)
    style = RoomStyle(cushion_rows=args.cushion_rows)
    start = time.perf_counter()
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        jobs = pool.map(synthesize_to, seeds, [args.out] * len(seeds), [style] * len(seeds))
        for _ in tqdm(jobs, total=len(seeds), desc="synth", unit="scene", file=sys.stderr):
            pass
    seconds = time.perf_counter() - start
    rate = args.count / seconds
    print(f"{args.count} scenes in {seconds:.1f} s ({rate:.2f} scenes/s) -> {args.out}")
    return 0


def _eval(args: argparse.Namespace) -> int:
    from ..evaluation.report import markdown_report
    from ..evaluation.run import EvaluationInputError, evaluate_folders

    if args.store:
        if args.pred_dir is not None:
            raise CliError("--store scores the stored scenes: give no PRED_DIR or GT_DIR")
        return _eval_store(args)
    if args.gt_dir is None:
        raise CliError("give PRED_DIR and GT_DIR, or --store")
    if args.scene_ids or args.rerun or not args.use_depth:
        raise CliError("--scene, --rerun and --no-depth go with --store")
    try:
        run = evaluate_folders(args.pred_dir, args.gt_dir)
    except EvaluationInputError as exc:
        raise CliError(str(exc)) from exc
    summary = run.evaluation.summary()
    summary["missing_predictions"] = run.missing_predictions
    report = markdown_report(summary, f"Evaluation of {args.pred_dir} against {args.gt_dir}")
    if args.shapes:
        from ..evaluation.shape_eval import evaluate_shapes, markdown_shapes

        summary["shapes"] = evaluate_shapes(args.pred_dir, args.gt_dir)
        report += markdown_shapes(summary["shapes"])
    out = args.out or args.pred_dir
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "eval.json", (json.dumps(summary, indent=1) + "\n").encode())
    write_atomic(out / "eval.md", report.encode())
    print(report)
    if run.missing_predictions:
        print(f"missing predictions (scored as empty): {', '.join(run.missing_predictions)}")
    return 0


def _eval_store(args: argparse.Namespace) -> int:
    """The stored scenes that have gt.json, at their current revision or re-run."""
    from tqdm import tqdm

    from ..evaluation.report import markdown_report
    from ..evaluation.stored import active_rerun, evaluate_stored, markdown_scene_list
    from ..store.scenes import SceneNotFoundError
    from .export import scene_store

    settings = settings_from(args)
    with scene_store(settings) as scenes:
        # By name (AP over boxes of equal score depends on the order), as the folder form.
        stored = sorted(scenes.list_summaries(), key=lambda s: (s.name, s.id))
        ids = list(dict.fromkeys(args.scene_ids or [s.id for s in stored]))
        if not ids:
            raise CliError("the store holds no scenes")
        rerun = active_rerun(settings, args.use_depth) if args.rerun else None
        with tqdm(total=len(ids), desc="eval", unit="scene", file=sys.stderr) as bar:
            try:
                run = evaluate_stored(scenes, ids, rerun, progress=lambda _: bar.update())
            except SceneNotFoundError as exc:
                raise CliError(str(exc)) from exc
    if not run.scored:
        errors = "".join(f"; {scene_id}: {why}" for scene_id, why in run.errors.items())
        raise CliError(
            f"none of the {len(ids)} scene(s) could be scored against ground truth{errors}"
        )
    summary = run.summary()
    what = "the pipeline re-run on" if rerun else "the current revisions of"
    report = markdown_report(
        summary, f"Evaluation of {what} the stored scenes against their ground truth"
    ) + markdown_scene_list(run)
    out = args.out or settings.data_dir / "eval"
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "eval.json", (json.dumps(summary, indent=1) + "\n").encode())
    write_atomic(out / "eval.md", report.encode())
    print(report)
    print(f"eval.json and eval.md written to {out}")
    for scene_id, why in run.errors.items():
        print(f"error: {scene_id}: {why}", file=sys.stderr)
    return 1 if run.errors else 0
