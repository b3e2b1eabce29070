"""`holiscene demo` and `import`: scenes into the store, each run through the pipeline."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING

from ..core.settings import REPO_ROOT
from .common import settings_from

if TYPE_CHECKING:
    from holiscene_schema import ImportResult

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
        description="Each PATH is an input folder (img.jpg, cam_K.txt, detections.json), a "
        "COCO instances file (or a folder holding annotations.json or instances*.json), or a "
        "LabelMe file (or a folder of them); the format is told by the content. A photo that "
        "does not read is reported and left out, the others are imported.",
    )
    imp.add_argument("paths", type=Path, nargs="+", metavar="PATH")
    imp.add_argument("--data-dir", type=Path)
    imp.add_argument("--database-url")
    imp.set_defaults(handler=_import)


def _demo(args: argparse.Namespace) -> int:
    from ..services.workbench import Workbench
    from ..synth.generate import synthesize_to

    settings = settings_from(args)
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
    from ..inputs.datasets import dataset_items, is_dataset
    from ..services.workbench import Workbench

    workbench = Workbench(settings_from(args))
    failures = 0
    number = 0
    try:
        for path in args.paths:
            if not is_dataset(path):
                number += 1
                failures += _import_one(number, str(path), partial(workbench.import_folder, path))
                continue
            for item in dataset_items(path):
                number += 1
                if item.inputs is None:
                    print(f"error: {item.name}: {item.error}", file=sys.stderr)
                    failures += 1
                    continue
                run = partial(workbench.import_and_run, item.inputs, Path(item.name).stem)
                failures += _import_one(number, item.name, run)
    finally:
        workbench.close()
    return 1 if failures else 0


def _import_one(number: int, label: str, run: Callable[[], ImportResult]) -> int:
    """Import one photo, printing a line of progress or its error; 1 when it failed."""
    from ..inputs import InputError

    try:
        result = run()
    except InputError as exc:
        print(f"error: {label}: {exc}", file=sys.stderr)
        return 1
    job = result.job
    print(f"[{number}] {label}: scene {result.scene.id}, pipeline {job.status if job else '-'}")
    return 1 if job and job.status == "failed" else 0
