"""Sessions that end after a while without requests (sliding: each request moves the deadline
on), and accounts an admin disables: no login, and their sessions stop working at once."""

from __future__ import annotations

import threading
import time
from datetime import timedelta
from pathlib import Path

import pytest
from holiscene.core.settings import Settings
from holiscene.store.clock import as_utc, utcnow
from holiscene.store.tables import SessionRow, UserRow
from holiscene.store.users import UserError
from pydantic import ValidationError
from sqlalchemy import select, update
from sqlalchemy.orm import Session

from ..databases import writes_held
from .conftest import PASSWORD, Accounts

# The store, as the server uses it, on SQLite and on PostgreSQL (databases.py).
pytestmark = pytest.mark.both_databases

IDLE_HOURS = 0.5


@pytest.fixture()
def settings(tmp_path: Path, database_url: str | None) -> Settings:
    """A 30-minute idle timeout (the default is 8 hours)."""
    return Settings(
        data_dir=tmp_path / "data",
        web_dir=tmp_path / "no-web",
        database_url=database_url,
        session_idle_hours=IDLE_HOURS,
    )


def _last_seen(accounts: Accounts, name: str) -> list[tuple[str, object]]:
    with Session(accounts.workbench.engine) as session:
        rows = session.execute(
            select(SessionRow.token_hash, SessionRow.last_seen_at)
            .join(UserRow, UserRow.id == SessionRow.user_id)
            .where(UserRow.name == name)
        ).all()
        return [(token_hash, as_utc(seen)) for token_hash, seen in rows]


def _set_session(accounts: Accounts, name: str, **values: object) -> None:
    """Move the stored times of every session of `name` (no sleeping in tests)."""
    with Session(accounts.workbench.engine) as session:
        user_id = session.scalar(select(UserRow.id).where(UserRow.name == name))
        session.execute(update(SessionRow).where(SessionRow.user_id == user_id).values(**values))
        session.commit()


def _me(accounts: Accounts, name: str) -> tuple[int, str]:
    response = accounts.client.get("/api/auth/me", headers=accounts.headers(name))
    detail = response.json().get("detail", "") if response.status_code != 200 else ""
    return response.status_code, detail


def test_a_session_ends_after_the_idle_timeout(accounts: Accounts) -> None:
    assert accounts.workbench.users.idle_timeout == timedelta(minutes=30)
    # Used 29 minutes ago: still open, and the request moves its deadline on.
    _set_session(accounts, "ann", last_seen_at=utcnow() - timedelta(minutes=29))
    assert _me(accounts, "ann") == (200, "")
    [(_, seen)] = _last_seen(accounts, "ann")
    assert utcnow() - seen < timedelta(seconds=30)  # type: ignore[operator]

    # Sliding: 29 more minutes without a request is still within the 30 from the last one.
    _set_session(accounts, "ann", last_seen_at=utcnow() - timedelta(minutes=29))
    assert _me(accounts, "ann") == (200, "")

    # 31 minutes without a request: ended, with the reason.
    _set_session(accounts, "ann", last_seen_at=utcnow() - timedelta(minutes=31))
    status, detail = _me(accounts, "ann")
    assert status == 401
    assert detail == "your session ended after 30 minutes without activity; log in again"
    scenes = accounts.client.get("/api/scenes", headers=accounts.headers("ann"))
    assert scenes.status_code == 401
    # Other people's sessions are not affected; logging in again opens a new one.
    assert _me(accounts, "bob") == (200, "")
    accounts.login("ann")
    assert _me(accounts, "ann") == (200, "")
    # The ended session is cleared away at the next login.
    assert len(_last_seen(accounts, "ann")) == 1


def test_background_polling_does_not_hold_a_session_open(accounts: Accounts) -> None:
    """A forgotten tab polls (job progress, the scene list while a job runs): those requests
    carry `X-Holiscene-Background: 1` and are answered, but do not count as activity."""
    background = {**accounts.headers("ann"), "X-Holiscene-Background": "1"}
    twenty_nine = utcnow() - timedelta(minutes=29)
    _set_session(accounts, "ann", last_seen_at=twenty_nine)
    polled = accounts.client.get("/api/scenes", headers=background)
    assert polled.status_code == 200, polled.text  # authenticated as usual
    [(_, seen)] = _last_seen(accounts, "ann")
    assert seen == twenty_nine  # the deadline did not move
    # So polling past the idle timeout ends the session, polls included.
    _set_session(accounts, "ann", last_seen_at=utcnow() - timedelta(minutes=31))
    ended = accounts.client.get("/api/scenes", headers=background)
    assert ended.status_code == 401
    assert "without activity" in ended.json()["detail"]

    # A request without the header (or with another value) is activity and moves it on.
    for headers in (
        accounts.headers("bob"),
        {**accounts.headers("bob"), "X-Holiscene-Background": "0"},
    ):
        _set_session(accounts, "bob", last_seen_at=twenty_nine)
        assert accounts.client.get("/api/scenes", headers=headers).status_code == 200
        [(_, seen)] = _last_seen(accounts, "bob")
        assert utcnow() - seen < timedelta(seconds=30)  # type: ignore[operator]


def test_a_session_still_ends_at_its_expiry(accounts: Accounts) -> None:
    _set_session(accounts, "bob", expires_at=utcnow() - timedelta(seconds=1))
    assert _me(accounts, "bob") == (401, "your session expired; log in again")


def test_the_idle_timeout_is_a_setting(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert Settings(data_dir=tmp_path).session_idle_hours == 8.0
    monkeypatch.setenv("HOLISCENE_SESSION_IDLE_HOURS", "2.5")
    assert Settings(data_dir=tmp_path).session_idle_hours == 2.5
    for bad in (0, -1):
        with pytest.raises(ValidationError, match="greater than 0"):
            Settings(data_dir=tmp_path, session_idle_hours=bad)


def test_admin_disables_and_enables_an_account(accounts: Accounts) -> None:
    client, ada = accounts.client, accounts.headers("ada")
    assert _me(accounts, "ann") == (200, "")

    disabled = client.post("/api/users/ann/disable", headers=ada)
    assert disabled.status_code == 200, disabled.text
    assert disabled.json()["disabled"] is True and disabled.json()["disabled_at"] is not None
    # Her session stops at once, saying why; login is refused, saying why, but only to
    # someone who knows the password.
    assert _me(accounts, "ann") == (
        401,
        "the account ann was disabled by an admin; your session ended",
    )
    login = client.post("/api/auth/login", json={"name": "ann", "password": PASSWORD})
    assert login.status_code == 403
    assert login.json()["detail"] == "the account ann is disabled; ask an admin to enable it"
    wrong = client.post("/api/auth/login", json={"name": "ann", "password": "wrong-password-1"})
    assert (wrong.status_code, wrong.json()["detail"]) == (401, "wrong user name or password")
    listed = {u["name"]: u["disabled"] for u in client.get("/api/users", headers=ada).json()}
    assert listed == {"ada": False, "ann": True, "bob": False, "rex": False, "rita": False}
    # Disabling twice changes nothing.
    again = client.post("/api/users/ann/disable", headers=ada)
    assert again.status_code == 200 and again.json() == disabled.json()

    enabled = client.post("/api/users/ann/enable", headers=ada)
    assert enabled.status_code == 200
    assert (enabled.json()["disabled"], enabled.json()["disabled_at"]) == (False, None)
    # The old session does not come back; a new login works.
    assert _me(accounts, "ann")[0] == 401
    accounts.login("ann")
    assert _me(accounts, "ann") == (200, "")


def test_the_last_enabled_admin_cannot_be_disabled(accounts: Accounts) -> None:
    client, ada = accounts.client, accounts.headers("ada")
    refused = client.post("/api/users/ada/disable", headers=ada)
    assert refused.status_code == 409
    assert "ada is the only enabled admin" in refused.json()["detail"]
    assert _me(accounts, "ada") == (200, "")  # nothing changed
    assert client.post("/api/users/nobody/disable", headers=ada).status_code == 404

    # With a second admin, an admin may disable themselves; then the other is the last one.
    accounts.add("max", "admin")
    assert client.post("/api/users/ada/disable", headers=ada).status_code == 200
    assert _me(accounts, "ada")[0] == 401
    mx = accounts.headers("max")
    last = client.post("/api/users/max/disable", headers=mx)
    assert last.status_code == 409 and "only enabled admin" in last.json()["detail"]
    # A disabled admin does not count: max cannot stop being admin either.
    demote = client.patch("/api/users/max", json={"role": "reviewer"}, headers=mx)
    assert demote.status_code == 409 and "only admin" in demote.json()["detail"]
    assert client.post("/api/users/ada/enable", headers=mx).status_code == 200
    accounts.login("ada")
    assert _me(accounts, "ada") == (200, "")


def test_the_last_enabled_admin_cannot_be_demoted(accounts: Accounts) -> None:
    client, ada = accounts.client, accounts.headers("ada")
    accounts.add("max", "admin")
    mx = accounts.headers("max")
    # With two admins, one may step down (to any lower role); then the other is the last.
    demoted = client.patch("/api/users/ada", json={"role": "reviewer"}, headers=ada)
    assert demoted.status_code == 200 and demoted.json()["role"] == "reviewer"
    for role in ("reviewer", "annotator"):
        refused = client.patch("/api/users/max", json={"role": role}, headers=mx)
        assert refused.status_code == 409 and "max is the only admin" in refused.json()["detail"]
    assert accounts.workbench.users.roles()["max"] == "admin"
    # Staying admin, promoting, and demoting a disabled admin are always allowed.
    assert client.patch("/api/users/max", json={"role": "admin"}, headers=mx).status_code == 200
    assert client.patch("/api/users/ada", json={"role": "admin"}, headers=mx).status_code == 200
    assert client.post("/api/users/ada/disable", headers=mx).status_code == 200
    gone = client.patch("/api/users/ada", json={"role": "annotator"}, headers=mx)
    assert gone.status_code == 200 and gone.json()["role"] == "annotator"
    assert accounts.workbench.users.count_admins() == 1


@pytest.mark.parametrize("action", ["demote", "disable"])
def test_two_admins_taking_each_others_rights_at_once_leave_one(
    accounts: Accounts, action: str
) -> None:
    """Both requests start while a third writer holds back writes to the users, so a check
    read before the write would see two admins in both and let both through (none left)."""
    accounts.add("max", "admin")
    users = accounts.workbench.users
    outcomes: dict[str, str] = {}

    def take_away(name: str) -> None:
        try:
            if action == "demote":
                users.set_role(name, "reviewer")
            else:
                users.set_disabled(name, True)
            outcomes[name] = "done"
        except UserError as refused:
            outcomes[name] = f"{refused.status}"

    threads = [threading.Thread(target=take_away, args=(name,)) for name in ("ada", "max")]
    with writes_held(accounts.workbench.engine, "users"):
        for thread in threads:
            thread.start()
        time.sleep(0.3)  # both are waiting for the lock (the busy timeout is 30 s)
    for thread in threads:
        thread.join(timeout=30)
    assert sorted(outcomes.values()) == ["409", "done"]
    assert users.count_admins() == 1


@pytest.mark.parametrize("who", ["ann", "rita"])
def test_only_admins_disable_accounts(accounts: Accounts, who: str) -> None:
    for action in ("disable", "enable"):
        response = accounts.client.post(f"/api/users/bob/{action}", headers=accounts.headers(who))
        assert response.status_code == 403
        assert "needs the admin role" in response.json()["detail"]
    assert _me(accounts, "bob") == (200, "")
