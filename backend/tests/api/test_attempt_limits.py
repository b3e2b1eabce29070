"""Guessing passwords: limits that hold under concurrent requests, per client address and
name (so guessing from one place cannot lock the admin out everywhere), per client address
over all names, and on changing one's password."""

from __future__ import annotations

import threading
from collections import Counter
from collections.abc import Callable

import httpx
from fastapi.testclient import TestClient
from holiscene.api.attempt_limits import (
    LOGINS_PER_CLIENT,
    LOGINS_PER_CLIENT_AND_NAME,
    PASSWORD_CHANGES_PER_ACCOUNT,
)

from .conftest import PASSWORD, Accounts


def _client_at(accounts: Accounts, address: str) -> TestClient:
    """Another client of the same running app, from another address."""
    return TestClient(accounts.client.app, client=(address, 40000))


def _at_once(count: int, request: Callable[[], httpx.Response]) -> Counter[int]:
    """`count` requests from as many threads, released together; their status codes."""
    start = threading.Barrier(count)
    statuses: list[int] = []
    lock = threading.Lock()

    def one() -> None:
        start.wait()
        status = request().status_code
        with lock:
            statuses.append(status)

    threads = [threading.Thread(target=one) for _ in range(count)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return Counter(statuses)


def test_concurrent_wrong_logins_check_at_most_the_limit(accounts: Accounts) -> None:
    attacker = _client_at(accounts, "203.0.113.7")
    wrong = {"name": "ada", "password": "wrong-password-1"}
    statuses = _at_once(50, lambda: attacker.post("/api/auth/login", json=wrong))
    # A 401 is a password checked; a 429 was refused before any check.
    assert statuses == {401: LOGINS_PER_CLIENT_AND_NAME, 429: 50 - LOGINS_PER_CLIENT_AND_NAME}
    # From there even the right password is refused ...
    right = {"name": "ada", "password": PASSWORD}
    refused = attacker.post("/api/auth/login", json=right)
    assert refused.status_code == 429 and "too many failed logins" in refused.json()["detail"]
    # ... but the admin, elsewhere, still logs in.
    assert _client_at(accounts, "198.51.100.20").post("/api/auth/login", json=right).is_success


def test_one_client_cannot_try_many_names(accounts: Accounts) -> None:
    attacker = _client_at(accounts, "203.0.113.8")
    names = [f"user{i}" for i in range(LOGINS_PER_CLIENT)]
    for name in names:
        body = {"name": name, "password": "wrong-password-1"}
        assert attacker.post("/api/auth/login", json=body).status_code == 401
    # Any further name, even a real one with its password, is refused from this address.
    right = {"name": "ann", "password": PASSWORD}
    assert attacker.post("/api/auth/login", json=right).status_code == 429
    assert _client_at(accounts, "198.51.100.21").post("/api/auth/login", json=right).is_success


def test_a_success_gives_its_place_back(accounts: Accounts) -> None:
    client = _client_at(accounts, "198.51.100.22")
    right = {"name": "bob", "password": PASSWORD}
    for _ in range(3 * LOGINS_PER_CLIENT_AND_NAME):  # logging in often is not guessing
        assert client.post("/api/auth/login", json=right).is_success
    wrong = {"name": "bob", "password": "wrong-password-1"}
    for _ in range(LOGINS_PER_CLIENT_AND_NAME - 1):  # typos, then the right password
        assert client.post("/api/auth/login", json=wrong).status_code == 401
    assert client.post("/api/auth/login", json=right).is_success
    for _ in range(LOGINS_PER_CLIENT_AND_NAME):  # the typos before were forgotten
        assert client.post("/api/auth/login", json=wrong).status_code == 401
    assert client.post("/api/auth/login", json=right).status_code == 429


def test_password_change_is_limited(accounts: Accounts) -> None:
    client, headers = accounts.client, accounts.headers("rex")
    wrong = {"current_password": "wrong-password-1", "new_password": "river-plum-88-comet"}
    statuses = _at_once(20, lambda: client.post("/api/auth/password", json=wrong, headers=headers))
    assert statuses == {403: PASSWORD_CHANGES_PER_ACCOUNT, 429: 20 - PASSWORD_CHANGES_PER_ACCOUNT}
    right = {"current_password": PASSWORD, "new_password": "river-plum-88-comet"}
    refused = client.post("/api/auth/password", json=right, headers=headers)
    assert refused.status_code == 429 and "wait a few minutes" in refused.json()["detail"]
    # Nothing changed: the old password still logs in.
    assert accounts.workbench.users.check_credentials("rex", PASSWORD) is not None


def test_names_sprayed_by_a_refused_client_are_not_kept(accounts: Accounts) -> None:
    limiter = accounts.client.app.state.attempt_limiter  # type: ignore[attr-defined]
    attacker = _client_at(accounts, "203.0.113.9")
    for i in range(LOGINS_PER_CLIENT + 200):
        body = {"name": f"spray{i}", "password": "wrong-password-1"}
        expected = 401 if i < LOGINS_PER_CLIENT else 429
        assert attacker.post("/api/auth/login", json=body).status_code == expected
    # One key per name that was checked, one for the address; none for the refused names.
    assert len(limiter) == LOGINS_PER_CLIENT + 1
