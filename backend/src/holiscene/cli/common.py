"""What the command groups share: the user-facing error, settings from the common options, and
writing a result file atomically (core.atomic_files)."""

from __future__ import annotations

import argparse

from ..core.atomic_files import write_atomic
from ..core.settings import Settings

__all__ = ["CliError", "settings_from", "write_atomic"]


class CliError(Exception):
    """A message for the user; the command exits with status 2."""


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
