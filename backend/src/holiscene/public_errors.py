"""What a user may read about an unexpected failure (a job's `error`).

Every logged-in user can read any job, so a failure message must not show how the server is
laid out (its folders, its installed libraries) nor a traceback; the full story goes to the
server log, where an admin finds it by the job's id.
"""

from __future__ import annotations

import re

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
