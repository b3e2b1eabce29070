"""What an export format refuses to write."""

from __future__ import annotations

from ..core.errors import DomainError


class ExportRefusedError(DomainError, ValueError):
    """The chosen scenes hold nothing this format writes (e.g. no labels to train on); no file
    was written. The API answers 422 with its message."""
