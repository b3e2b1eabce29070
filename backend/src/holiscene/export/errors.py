"""What an export format refuses to write."""

from __future__ import annotations


class ExportRefusedError(ValueError):
    """The chosen scenes hold nothing this format writes (e.g. no labels to train on); no file
    was written."""
