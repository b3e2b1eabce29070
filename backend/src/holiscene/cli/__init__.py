"""`holiscene`: run the pipeline on a folder, serve the workbench, load demo scenes."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .batch import add_batch_command
from .common import CliError, settings_from
from .completion import add_completion_training_command
from .export import add_export_command
from .learned_3d import add_learned_3d_training_command
from .pipeline import add_pipeline_commands
from .scenes import add_demo_command, add_import_command
from .serve import add_serve_command
from .training import (
    add_detector_training_command,
    add_relation_training_command,
    add_surface_training_command,
)
from .users import UsersCliError, add_user_commands
from .view import add_view_command

__all__ = ["CliError", "main"]


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
    # The order of `holiscene --help`.
    add_pipeline_commands(sub)  # infer, synth, eval
    add_serve_command(sub)
    add_user_commands(sub, settings_from)
    add_demo_command(sub)
    add_import_command(sub)
    add_batch_command(sub)
    add_export_command(sub)
    add_relation_training_command(sub)
    add_surface_training_command(sub)
    add_detector_training_command(sub)
    add_completion_training_command(sub)
    add_learned_3d_training_command(sub)  # LEN + ODN, meshes, box refiner
    add_view_command(sub)
    return parser
