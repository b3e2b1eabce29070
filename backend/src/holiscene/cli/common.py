"""What the command groups share: the user-facing error, settings from the common options, and
writing a result file atomically (core.atomic_files)."""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from contextlib import contextmanager

from ..core.atomic_files import write_atomic
from ..core.settings import Settings

__all__ = ["CliError", "needs_pytorch", "settings_from", "write_atomic"]


class CliError(Exception):
    """A message for the user; the command exits with status 2."""


@contextmanager
def needs_pytorch() -> Iterator[None]:
    """Around a training command's imports: without the `train` extra the user is told how to
    install it, not shown a traceback."""
    try:
        yield
    except ImportError as error:
        raise CliError(f"training needs PyTorch: pip install -e '.[train]' ({error})") from error


def settings_from(args: argparse.Namespace) -> Settings:
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
