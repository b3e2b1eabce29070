"""Password hashing (argon2id) and the rules a new password must meet."""

from __future__ import annotations

import functools

from argon2 import PasswordHasher
from argon2.exceptions import InvalidHashError, VerificationError

from .errors import DomainError

# argon2id with OWASP's recommended minimum (19 MiB, 2 passes, 1 lane): argon2-cffi's
# defaults (64 MiB, 4 lanes) took about 1 s per login on this 2-core machine under load, which
# would make logins slow and let a few parallel login attempts starve the server. Hashes
# carry their parameters, so raising them later re-hashes at the next login.
_HASHER = PasswordHasher(time_cost=2, memory_cost=19_456, parallelism=1)


@functools.cache
def _dummy_hash() -> str:
    """Verified when the name is unknown, so a wrong name takes as long as a wrong password."""
    return _HASHER.hash("not a password of anyone")


MIN_LENGTH = 10
MIN_DISTINCT = 5
# The most common choices people make, as found in every breach list; refused outright.
_COMMON = frozenset(
    {
        "password",
        "password1",
        "password12",
        "password123",
        "passw0rd",
        "1234567890",
        "0123456789",
        "qwertyuiop",
        "qwerty1234",
        "1q2w3e4r5t",
        "iloveyou12",
        "letmein123",
        "welcome123",
        "admin12345",
        "administrator",
        "changeme123",
        "holiscene1",
        "holiscene123",
    }
)


class WeakPasswordError(DomainError, ValueError):
    pass


def password_problem(name: str, password: str) -> str | None:
    """Why `password` is too weak for user `name`, or None."""
    if not password.strip():
        return "the password is empty"
    if len(password) < MIN_LENGTH:
        return f"the password must have at least {MIN_LENGTH} characters"
    if len(set(password)) < MIN_DISTINCT:
        return f"the password must use at least {MIN_DISTINCT} different characters"
    if password.lower() in _COMMON:
        return "this password is one of the most common ones; choose another"
    if name and name.lower() in password.lower():
        return "the password must not contain the user name"
    return None


def check_password(name: str, password: str) -> None:
    problem = password_problem(name, password)
    if problem:
        raise WeakPasswordError(problem)


def hash_password(password: str) -> str:
    return _HASHER.hash(password)


def verify_password(password_hash: str | None, password: str) -> bool:
    """True when `password` matches; constant work whether or not there is a hash."""
    try:
        matches = _HASHER.verify(password_hash or _dummy_hash(), password)
        return matches and password_hash is not None
    except (VerificationError, InvalidHashError):
        return False


def needs_rehash(password_hash: str) -> bool:
    """The hash was made with weaker parameters than today's."""
    return _HASHER.check_needs_rehash(password_hash)
