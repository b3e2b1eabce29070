"""Limits on guessing passwords (logins, password changes), in memory of one server process.

An attempt is counted when it starts, not when its password check fails: checking a password
takes tens of milliseconds (argon2), and counting after the check let 50 concurrent wrong
logins through 13 checks before the first failure was recorded. Here, under one lock, an
attempt either takes one of the places left or is refused (429) without any check; a
success gives its place back.

Logins are limited per client address and name (a name is locked only for the addresses that
failed on it, so guessing from one place cannot lock the admin out everywhere) and per client
address over all names (one place cannot try many names). See docs/security.md.
"""

from __future__ import annotations

import threading
import time
from collections import defaultdict, deque
from collections.abc import Hashable, Sequence
from dataclasses import dataclass

WINDOW_S = 300.0
LOGINS_PER_CLIENT_AND_NAME = 5
LOGINS_PER_CLIENT = 20
PASSWORD_CHANGES_PER_ACCOUNT = 5


@dataclass(frozen=True)
class Limit:
    key: Hashable
    most: int  # attempts that may fail in the window


@dataclass(frozen=True)
class Attempt:
    limits: tuple[Limit, ...]
    started: float


class TooManyAttemptsError(Exception):
    pass


class AttemptLimiter:
    def __init__(self, window_s: float = WINDOW_S) -> None:
        self.window_s = window_s
        self._attempts: dict[Hashable, deque[float]] = defaultdict(deque)
        self._lock = threading.Lock()

    def __len__(self) -> int:
        """Keys with attempts held in memory."""
        with self._lock:
            return len(self._attempts)

    def _count(self, key: Hashable, now: float) -> int:
        """Attempts in the window; keys without any are dropped (names sprayed by a guesser
        must not pile up in memory)."""
        attempts = self._attempts.get(key)
        if attempts is None:
            return 0
        while attempts and attempts[0] < now - self.window_s:
            attempts.popleft()
        if not attempts:
            del self._attempts[key]
        return len(attempts)

    def begin(self, limits: Sequence[Limit]) -> Attempt:
        """Count an attempt against every limit, or raise TooManyAttemptsError when one is
        used up (then nothing is counted)."""
        with self._lock:
            now = time.monotonic()
            if any(self._count(limit.key, now) >= limit.most for limit in limits):
                raise TooManyAttemptsError
            for limit in limits:
                self._attempts[limit.key].append(now)
            return Attempt(tuple(limits), now)

    def succeeded(self, attempt: Attempt, forget: Sequence[Hashable] = ()) -> None:
        """The attempt was right: it counts against nothing; the keys in `forget` start over
        (their earlier failures were the same person mistyping)."""
        with self._lock:
            for limit in attempt.limits:
                attempts = self._attempts.get(limit.key)
                if attempts is not None and attempt.started in attempts:
                    attempts.remove(attempt.started)
                    if not attempts:
                        del self._attempts[limit.key]
            for key in forget:
                self._attempts.pop(key, None)


def login_limits(client: str, name: str) -> tuple[Limit, Limit]:
    return (
        Limit(("login", client, name), LOGINS_PER_CLIENT_AND_NAME),
        Limit(("login from", client), LOGINS_PER_CLIENT),
    )


def password_change_limits(name: str) -> tuple[Limit]:
    return (Limit(("password change", name), PASSWORD_CHANGES_PER_ACCOUNT),)
