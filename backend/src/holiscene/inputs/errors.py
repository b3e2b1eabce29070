"""The error every input check raises: what is wrong with which file, and the HTTP status."""

from __future__ import annotations

from ..core.errors import DomainError


class InputError(DomainError, ValueError):
    """Bad user input; `status` is the HTTP status the server answers with."""

    def __init__(self, message: str, status: int = 422) -> None:
        super().__init__(message)
        self.status = status
