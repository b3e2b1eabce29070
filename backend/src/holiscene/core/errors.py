"""What a user may read of an error.

A `DomainError` is a request the domain refuses for a reason the user can act on (a scene
that does not exist, an edit that breaks the support graph, a job already running): it
carries the HTTP status the API answers with and a readable message, and the API turns every
one of them into `{"detail": ...}` in one place (`api/errors.py`).

Anything else is an unexpected failure. Every logged-in user can read any job, so what a
job's `error` shows of one (`user_facing_error`) must not tell how the server is laid out
(its folders, its installed libraries) nor hold a traceback; the full story goes to the
server log, where an admin finds it by the job's id.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import ClassVar


class DomainError(Exception):
    """A refusal with its HTTP status; the message (the exception's text) is for the user."""

    status: int = 422  # a class's own, or one an instance was given
    headers: ClassVar[Mapping[str, str]] = {}  # sent with the answer (e.g. when to try again)

    def detail(self) -> str | dict[str, object]:
        """The answer's `detail`: the message, or an object for a client that reads fields."""
        return str(self)


class NotFoundError(DomainError, LookupError):
    """Something the request names does not exist (HTTP 404)."""

    status = 404

    def detail(self) -> str | dict[str, object]:
        return str(self.args[0]) if self.args else "not found"


# An absolute path: "/" or "C:\" followed by at least one name, not inside a word or a number
# ("1/2", "m/s" stay).
_ABSOLUTE_PATH = re.compile(r"(?<![\w.])(?:[A-Za-z]:)?(?:[\\/][\w.\-+@~]+)+[\\/]?")
MAX_LENGTH = 300


def hide_paths(text: str) -> str:
    return _ABSOLUTE_PATH.sub("<server path>", text)


def user_facing_error(exc: BaseException) -> str:
    """The exception's type and first line, without server paths, cut to MAX_LENGTH."""
    lines = str(exc).strip().splitlines()
    first = hide_paths(lines[0]) if lines else ""
    message = f"{type(exc).__name__}: {first}" if first else type(exc).__name__
    if len(message) > MAX_LENGTH:
        message = message[: MAX_LENGTH - 1] + "…"
    return message
