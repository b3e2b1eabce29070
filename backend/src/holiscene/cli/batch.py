"""`holiscene batch`: pre-annotate stored scenes, the pipeline on Ray (services.batch)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from .common import CliError, settings_from

if TYPE_CHECKING:
    from ..services.workbench import Workbench


def add_batch_command(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    batch = sub.add_parser(
        "batch",
        help="run the pipeline on the stored scenes that have no result yet, on Ray",
        description="Runs the pipeline on every stored scene (or the ones named) that the "
        "pipeline has not stored a result on yet, several photos at a time on Ray, and "
        "stores the results as pipeline jobs do. Run it again to resume: done scenes are "
        "skipped. Ray is started on this machine (127.0.0.1 only) unless --ray names a "
        "cluster.",
    )
    batch.add_argument("--scene", action="append", default=[], metavar="ID", help="only this")
    add_ray_options(batch)
    batch.add_argument(
        "--again",
        action="store_true",
        help="run the scenes the pipeline has run on before too (people's supports, objects "
        "and hand-set layouts are kept, as in any re-run)",
    )
    batch.add_argument("--data-dir", type=Path)
    batch.add_argument("--database-url")
    batch.set_defaults(handler=_batch)


def add_ray_options(parser: argparse.ArgumentParser) -> None:
    """--workers and --ray, shared with `holiscene import --run-pipeline`."""
    parser.add_argument(
        "--workers",
        type=_positive,
        metavar="N",
        help="photos computed at once (default: the machine's cores, or the cluster's CPUs)",
    )
    parser.add_argument(
        "--ray",
        metavar="ADDRESS",
        help="join the Ray cluster at ADDRESS (host:port of its head) instead of starting Ray "
        "on this machine; its nodes need holiscene installed, not the data directory",
    )


def _positive(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("must be 1 or more")
    return value


def _batch(args: argparse.Namespace) -> int:
    from ..services.workbench import Workbench

    workbench = Workbench(settings_from(args))
    try:
        return batch_scenes(workbench, args.scene, args.workers, args.ray, args.again)
    finally:
        workbench.close()


def batch_scenes(
    workbench: Workbench,
    wanted: Sequence[str],
    workers: int | None,
    address: str | None,
    again: bool = False,
) -> int:
    """Run the batch on the scenes and report it: a bar of photos done and failed, a line
    per failed scene on stderr; 1 when any failed. Unknown scene ids stop it before anything
    runs (CliError)."""
    from tqdm import tqdm

    from ..core.interrupts import stop_signals_interrupt
    from ..services.batch import UnknownScenesError, ray_runtime, run_batch, scenes_to_run

    try:
        todo, skipped = scenes_to_run(workbench.scenes, wanted, again)
    except UnknownScenesError as exc:
        raise CliError(str(exc)) from exc
    if skipped:
        print(f"{len(skipped)} scene(s) already have a pipeline result, skipped")
    if not todo:
        print("nothing to run")
        return 0
    names = {s.id: s.name for s in workbench.scenes.list_summaries(archived=None)}
    with (
        ray_runtime(address, workers) as at_once,
        tqdm(total=len(todo), desc="batch", unit="photo", file=sys.stderr) as bar,
    ):
        failed = 0

        def finished(scene_id: str, error: str | None) -> None:
            nonlocal failed
            if error is not None:
                failed += 1
                bar.write(f"error: scene {scene_id} ({names.get(scene_id)}): {error}", sys.stderr)
            bar.set_postfix(done=bar.n + 1 - failed, failed=failed, refresh=False)
            bar.update()

        # Ctrl+C or SIGTERM: the photos out are marked failed, so a new run takes them.
        try:
            with stop_signals_interrupt():
                report = run_batch(workbench, todo, at_once, finished)
        except KeyboardInterrupt:
            bar.write("interrupted: run the batch again to go on", sys.stderr)
            return 130
    print(f"{len(report.done)} scene(s) pre-annotated, {len(report.failed)} failed")
    return 1 if report.failed else 0
