"""Accounts over HTTP: local mode, login and logout, the cookie, role changes, and every
route of the app refusing anonymous requests (401) and the wrong role (403)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import PUBLIC_ROUTES, NoAdminError, api_routes, create_app
from holiscene.core.settings import Settings
from holiscene.store.tables import SessionRow, UserRow
from sqlalchemy import select
from sqlalchemy.orm import Session

from ..conftest import PASSWORD, Accounts

# Routes that need more than the lowest role (annotator); every other API route is open to
# any logged-in user. A route added for reviewers or admins must be listed here, or the walk
# below fails.
NEEDS: dict[tuple[str, str], str] = {
    ("POST", "/api/scenes/{scene_id}/accept"): "reviewer",
    ("POST", "/api/scenes/{scene_id}/reject"): "reviewer",
    ("POST", "/api/scenes/{scene_id}/second-annotation"): "reviewer",
    ("GET", "/api/scenes/next-review"): "reviewer",
    ("POST", "/api/scenes/{scene_id}/archive"): "admin",
    ("POST", "/api/scenes/{scene_id}/unarchive"): "admin",
    ("POST", "/api/models/retrain"): "admin",
    ("POST", "/api/models/retrain/{job_id}/cancel"): "admin",
    ("POST", "/api/models/{model_id}/promote"): "admin",
    ("GET", "/api/users"): "admin",
    ("POST", "/api/users"): "admin",
    ("PATCH", "/api/users/{name}"): "admin",
    ("POST", "/api/users/{name}/password"): "admin",
    ("POST", "/api/users/{name}/disable"): "admin",
    ("POST", "/api/users/{name}/enable"): "admin",
}
RANK = {"annotator": 1, "reviewer": 2, "admin": 3}


def _api_routes(client: TestClient) -> list[tuple[str, str]]:
    routes = [
        (method, route.path)
        for route in api_routes(client.app)  # type: ignore[arg-type]
        if route.path.startswith("/api")
        for method in sorted(route.methods)
    ]
    # The walk sees the whole app, the routers of every resource.
    assert len(routes) > 30
    for known in ("/api/scenes/{scene_id}/edits", "/api/models/retrain", "/api/users/{name}"):
        assert any(path == known for _, path in routes), known
    return routes


def _url(path: str) -> str:
    return re.sub(r"\{[^}]+\}", "nosuch", path)


def test_local_mode_without_accounts(client: TestClient) -> None:
    me = client.get("/api/auth/me").json()
    assert me == {"name": "local", "role": "admin", "local_mode": True}
    assert client.get("/api/scenes").status_code == 200
    assert client.get("/api/users").json() == []
    # A page of another site cannot make the browser change anything here.
    refused = client.post("/api/scenes/next", headers={"Origin": "http://evil.example"})
    assert refused.status_code == 403 and "cross-site" in refused.json()["detail"]


def test_the_first_account_must_be_an_admin(client: TestClient) -> None:
    body = {"name": "ann", "role": "annotator", "password": PASSWORD}
    refused = client.post("/api/users", json=body)
    assert refused.status_code == 409 and "first account must be an admin" in refused.text
    assert client.get("/api/auth/me").json()["local_mode"] is True  # nothing was created


def test_every_route_refuses_anonymous_requests(accounts: Accounts) -> None:
    client = accounts.client
    walked = 0
    for method, path in _api_routes(client):
        response = client.request(method, _url(path))
        if path in PUBLIC_ROUTES:
            assert response.status_code != 401, (method, path)
            continue
        assert response.status_code == 401, (method, path, response.status_code)
        assert response.json()["detail"].startswith("log in first")
        walked += 1
    assert walked > 30
    # A made-up or ended session is no session.
    bogus = client.get("/api/scenes", headers={"Authorization": "Bearer not-a-token"})
    assert bogus.status_code == 401


@pytest.mark.parametrize("role", ["annotator", "reviewer", "admin"])
def test_every_route_checks_the_role(accounts: Accounts, role: str) -> None:
    user = {"annotator": "ann", "reviewer": "rita", "admin": "ada"}[role]
    client = accounts.client
    for method, path in _api_routes(client):
        if path in PUBLIC_ROUTES:
            continue
        response = client.request(method, _url(path), headers=accounts.headers(user))
        needed = NEEDS.get((method, path), "annotator")
        if RANK[role] < RANK[needed]:
            assert response.status_code == 403, (method, path, role, response.text)
            assert f"needs the {needed} role" in response.json()["detail"]
        else:
            # Allowed in: the made-up ids or the missing body are what it complains about.
            assert response.status_code not in (401, 403), (method, path, role, response.text)


def test_login_cookie_me_and_logout(accounts: Accounts) -> None:
    client = accounts.client
    wrong = client.post("/api/auth/login", json={"name": "ann", "password": "wrong-password-1"})
    assert wrong.status_code == 401 and wrong.json()["detail"] == "wrong user name or password"
    unknown = client.post("/api/auth/login", json={"name": "nobody", "password": PASSWORD})
    assert unknown.status_code == 401 and unknown.json() == wrong.json()

    response = client.post("/api/auth/login", json={"name": "ann", "password": PASSWORD})
    assert response.status_code == 200 and response.json()["token"] is None
    cookie = response.headers["set-cookie"]
    assert "HttpOnly" in cookie and "SameSite=strict" in cookie and "Path=/" in cookie
    assert client.get("/api/auth/me").json() == {
        "name": "ann",
        "role": "annotator",
        "local_mode": False,
    }
    # The database holds the token's hash only.
    token = client.cookies.get("holiscene_session")
    assert token
    with Session(accounts.workbench.engine) as session:
        hashes = list(session.scalars(select(SessionRow.token_hash)))
        assert token not in hashes and len(hashes[0]) == 64
        stored = session.scalar(select(UserRow.password_hash).where(UserRow.name == "ann"))
        assert stored is not None and stored.startswith("$argon2id$") and PASSWORD not in stored

    assert client.post("/api/auth/logout").status_code == 204
    assert "holiscene_session" not in client.cookies  # the answer cleared it
    client.cookies.set("holiscene_session", token)  # and the old token opens nothing
    assert client.get("/api/auth/me").status_code == 401


def test_login_throttling(accounts: Accounts) -> None:
    client = accounts.client
    for _ in range(5):
        body = {"name": "bob", "password": "wrong-password-1"}
        assert client.post("/api/auth/login", json=body).status_code == 401
    blocked = client.post("/api/auth/login", json={"name": "bob", "password": PASSWORD})
    assert blocked.status_code == 429
    # Other names are not affected.
    assert client.post("/api/auth/login", json={"name": "rex", "password": PASSWORD}).is_success


def test_admin_manages_accounts(accounts: Accounts) -> None:
    client, ada = accounts.client, accounts.headers("ada")
    names = [(u["name"], u["role"]) for u in client.get("/api/users", headers=ada).json()]
    assert names == [
        ("ada", "admin"),
        ("ann", "annotator"),
        ("bob", "annotator"),
        ("rex", "reviewer"),
        ("rita", "reviewer"),
    ]
    # Bad input: 4xx with a message, nothing written.
    for body, status, message in [
        ({"name": "ann", "role": "annotator", "password": PASSWORD}, 409, "already a user"),
        ({"name": "Carl", "role": "annotator", "password": PASSWORD}, 422, "name"),
        ({"name": "carl", "role": "boss", "password": PASSWORD}, 422, "role"),
        ({"name": "carl", "role": "annotator", "password": "short"}, 422, "10 characters"),
        ({"name": "local", "role": "annotator", "password": PASSWORD}, 422, "reserved"),
    ]:
        response = client.post("/api/users", json=body, headers=ada)
        assert response.status_code == status and message in response.json()["detail"], body
    assert len(client.get("/api/users", headers=ada).json()) == 5

    # A role change applies at the next request of the same session.
    ann = accounts.headers("ann")
    assert client.post("/api/scenes/x/accept", json={"revision": 1}, headers=ann).status_code == 403
    changed = client.patch("/api/users/ann", json={"role": "reviewer"}, headers=ada)
    assert changed.status_code == 200 and changed.json()["role"] == "reviewer"
    assert client.post("/api/scenes/x/accept", json={"revision": 1}, headers=ann).status_code == 404
    # The only admin stays admin.
    last = client.patch("/api/users/ada", json={"role": "reviewer"}, headers=ada)
    assert last.status_code == 409 and "only admin" in last.json()["detail"]
    assert client.patch("/api/users/nobody", json={"role": "admin"}, headers=ada).status_code == 404

    # A password reset ends the user's sessions; the new password works, the old does not.
    new = "quartz-meadow-82-lynx"
    reset = client.post("/api/users/bob/password", json={"password": new}, headers=ada)
    assert reset.status_code == 204
    ended = client.get("/api/auth/me", headers=accounts.headers("bob"))
    assert ended.status_code == 401
    assert "your password was changed" in ended.json()["detail"]  # why the page asks again
    bad = client.post("/api/auth/login", json={"name": "bob", "password": PASSWORD})
    assert bad.status_code == 401
    accounts.login("bob", new)

    # Anyone may change their own password, knowing the current one.
    rex = accounts.headers("rex")
    change = {"current_password": "wrong-password-1", "new_password": new}
    assert client.post("/api/auth/password", json=change, headers=rex).status_code == 403
    change["current_password"] = PASSWORD
    assert client.post("/api/auth/password", json=change, headers=rex).status_code == 204
    accounts.login("rex", new)


def test_beyond_loopback_needs_an_admin(tmp_path: Path) -> None:
    settings = Settings(data_dir=tmp_path / "data", web_dir=tmp_path / "web", host="0.0.0.0")
    with pytest.raises(NoAdminError, match="no admin account"), TestClient(create_app(settings)):
        pass
    # With an admin, it serves, and never in local mode: login is required.
    local = Settings(data_dir=tmp_path / "data", web_dir=tmp_path / "web")
    with TestClient(create_app(local)) as client:
        body = {"name": "ada", "role": "admin", "password": PASSWORD}
        assert client.post("/api/users", json=body).status_code == 201
    with TestClient(create_app(settings)) as client:
        assert client.get("/api/auth/me").status_code == 401
        assert client.get("/api/health").json() == {"status": "ok"}
