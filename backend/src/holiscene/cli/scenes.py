"""`holiscene demo` and `import`: scenes into the store, each run through the pipeline."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..core.settings import REPO_ROOT
from .common import settings_from

DEMO_PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"
DEMO_FOLDERS = ("t3d-5", "im3d-6", "mm3d-4", "im3d-3")
DEMO_SYNTH_SEEDS = (12, 15, 14, 11)  # varied rooms that read well at a glance


def add_demo_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    demo = sub.add_parser("demo", help="load demo scenes into an empty database")
    demo.add_argument("--data-dir", type=Path)
    demo.add_argument("--database-url")
    demo.set_defaults(handler=_demo)


def add_import_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    imp = sub.add_parser("import", help="import input folders as scenes and run the pipeline")
    imp.add_argument("folders", type=Path, nargs="+")
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
    from ..inputs import InputError
    from ..services.workbench import Workbench

    workbench = Workbench(settings_from(args))
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
