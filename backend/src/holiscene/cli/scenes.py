"""`holiscene demo` and `import`: scenes into the store, each run through the pipeline."""

from __future__ import annotations

import argparse
import dataclasses
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from ..core.settings import REPO_ROOT
from .batch import add_ray_options, batch_scenes
from .common import CliError, settings_from

if TYPE_CHECKING:
    from ..inputs import InputFiles
    from ..inputs.datasets.uploaded import PhotoSource
    from ..services.workbench import Workbench

DEMO_PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"
DEMO_FOLDERS = ("t3d-5", "im3d-6", "mm3d-4", "im3d-3")
DEMO_SYNTH_SEEDS = (12, 15, 14, 11)  # varied rooms that read well at a glance


def add_demo_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    demo = sub.add_parser("demo", help="load demo scenes into an empty database")
    demo.add_argument("--data-dir", type=Path)
    demo.add_argument("--database-url")
    demo.set_defaults(handler=_demo)


def add_import_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    imp = sub.add_parser(
        "import",
        help="import input folders, COCO or LabelMe files as scenes and run the pipeline",
        description="Each PATH is an input folder (img.jpg, cam_K.txt, detections.json, "
        "depth.png, ...), a COCO instances file (or a folder holding annotations.json or "
        "instances*.json), a LabelMe file (or a folder of them), a SUN RGB-D image folder (or "
        "a folder holding many at any depth), or NYU Depth v2's labelled .mat (or a folder "
        "holding it, support_labels.mat beside it), or a .zip of any of these (the app's "
        '"Download selected" archive, for one); the format is told by the content. A '
        "photo that does not read is reported and left out, the others are imported.",
    )
    imp.add_argument("paths", type=Path, nargs="+", metavar="PATH")
    imp.add_argument("--data-dir", type=Path)
    imp.add_argument("--database-url")
    imp.add_argument(
        "--again",
        action="store_true",
        help="import photos even when the same files were imported before (by default they "
        "are skipped, so a second run adds nothing and an interrupted one resumes)",
    )
    pipeline = imp.add_mutually_exclusive_group()
    pipeline.add_argument(
        "--run-pipeline",
        action="store_true",
        help="store every photo first, then run the pipeline on them on Ray, several at a "
        "time, as `holiscene batch` does (by default each photo is run here after its import)",
    )
    pipeline.add_argument("--no-pipeline", action="store_true", help="store the photos only")
    add_ray_options(imp)
    imp.set_defaults(handler=_import)


def _demo(args: argparse.Namespace) -> int:
    from ..services.workbench import Workbench
    from ..synth.generate import synthesize_to

    settings = settings_from(args)
    workbench = Workbench(settings)
    try:
        if workbench.scenes.list_summaries(archived=None):
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
    from ..inputs import InputError
    from ..services.workbench import Workbench

    if (args.workers or args.ray) and not args.run_pipeline:
        raise CliError("--workers and --ray go with --run-pipeline")
    workbench = Workbench(settings_from(args))
    failures = 0
    number = 0
    scene_ids: list[str] = []  # for --run-pipeline: every photo's scene, new or imported before
    try:
        for path in args.paths:
            try:
                for source in _sources(path, workbench):
                    number += 1
                    try:
                        inputs = source.read()
                    except InputError as exc:
                        print(f"error: {source.label}: {exc}", file=sys.stderr)
                        failures += 1
                        continue
                    failed, scene_id = _import_one(workbench, number, source, inputs, args)
                    failures += failed
                    scene_ids.append(scene_id)
            except InputError as exc:  # a .zip that does not unpack or holds nothing to import
                print(f"error: {path}: {exc}", file=sys.stderr)
                failures += 1
        if args.run_pipeline and scene_ids:
            failures += batch_scenes(workbench, scene_ids, args.workers, args.ray)
    finally:
        workbench.close()
    return 1 if failures else 0


def _sources(path: Path, workbench: Workbench) -> Iterator[PhotoSource]:
    """The photos of a path; a .zip is unpacked into a temporary folder first, with the
    limits an upload has (Settings.max_import_unpacked_mb, max_import_files)."""
    from ..inputs.archive import ArchiveLimits, unpack_zip
    from ..inputs.datasets.items import confined_to
    from ..inputs.datasets.uploaded import photo_sources, upload_contents

    if not (path.is_file() and path.suffix.lower() == ".zip"):
        yield from photo_sources(path)
        return
    settings = workbench.settings
    limits = ArchiveLimits.of_uploads(settings.max_import_unpacked_mb, settings.max_import_files)
    with tempfile.TemporaryDirectory(prefix="holiscene-import-") as folder:
        unpacked = Path(folder) / path.stem
        with path.open("rb") as archive:
            unpack_zip(archive, unpacked, limits)
        with confined_to(unpacked):  # a zip names no file outside itself, as an upload
            for source in upload_contents(unpacked).sources():
                # Named by the zip, not by the temporary folder.
                label = source.label.replace(str(unpacked), str(path))
                yield dataclasses.replace(source, label=label)


def _import_one(
    workbench: Workbench,
    number: int,
    source: PhotoSource,
    inputs: InputFiles,
    args: argparse.Namespace,
) -> tuple[int, str]:
    """Import one photo, printing a line of progress: 1 when its pipeline failed, and its
    scene. The same files imported before are skipped (an interrupted import resumes where it
    stopped), as is a scene downloaded from this store and not changed since. With
    --run-pipeline or --no-pipeline the photo is only stored."""
    from ..services.dataset_import import stored_before

    label, name = source.label, source.name
    earlier = None if args.again else stored_before(workbench.scenes, inputs, source)
    if earlier is not None:
        print(f"[{number}] {label}: imported before as scene {earlier.id}, skipped")
        return 0, earlier.id
    if args.run_pipeline or args.no_pipeline:
        stored = workbench.import_scene(inputs, name, "import", run_pipeline=False).scene
        print(f"[{number}] {label}: scene {stored.id}, stored")
        _print_notes(inputs)
        return 0, stored.id
    result = workbench.import_and_run(inputs, name)
    job = result.job
    print(f"[{number}] {label}: scene {result.scene.id}, pipeline {job.status if job else '-'}")
    _print_notes(inputs)
    return (1 if job and job.status == "failed" else 0), result.scene.id


def _print_notes(inputs: InputFiles) -> None:
    """What the reader left out of the photo's labels, under its line."""
    for note in inputs.notes:
        print(f"    note: {note}")
