"""Password hashing and the rules for new passwords."""

from __future__ import annotations

import pytest
from holiscene.core.passwords import (
    WeakPasswordError,
    check_password,
    hash_password,
    password_problem,
    verify_password,
)


def test_hash_is_argon2id_salted_and_verifies() -> None:
    password = "correct horse battery"
    first, second = hash_password(password), hash_password(password)
    assert first.startswith("$argon2id$")
    assert password not in first
    assert first != second  # a salt of its own
    assert verify_password(first, password) and verify_password(second, password)
    assert not verify_password(first, "correct horse batterY")
    assert not verify_password(None, password)  # unknown user
    assert not verify_password("not a hash", password)


@pytest.mark.parametrize(
    ("password", "message"),
    [
        ("", "empty"),
        ("          ", "empty"),
        ("short-1", "at least 10 characters"),
        ("aaaaabbbbbaaaaa", "5 different characters"),
        ("Password123", "most common"),
        ("xx-annie-2024", "must not contain the user name"),
    ],
)
def test_weak_passwords_are_refused(password: str, message: str) -> None:
    problem = password_problem("annie", password)
    assert problem is not None and message in problem
    with pytest.raises(WeakPasswordError):
        check_password("annie", password)


def test_a_good_password_passes() -> None:
    assert password_problem("annie", "tram-lilac-47-orbit") is None
