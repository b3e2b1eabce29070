"""What other web pages can make a browser do here: changes only from the server's own pages
(Origin / Referer), answers only to the server's own host names, security headers on every
answer, and the API's description only for logged-in users."""

from __future__ import annotations

from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings

from .conftest import PASSWORD, Accounts


def _browser_of(accounts: Accounts, name: str) -> TestClient:
    """A client holding `name`'s session cookie, as a browser does after logging in."""
    browser = TestClient(accounts.client.app)
    answer = browser.post("/api/auth/login", json={"name": name, "password": PASSWORD})
    assert answer.status_code == 200 and "holiscene_session" in browser.cookies
    return browser


def _bob_disabled(accounts: Accounts) -> bool:
    users = accounts.client.get("/api/users", headers=accounts.headers("ada")).json()
    return bool(next(u for u in users if u["name"] == "bob")["disabled"])


@pytest.mark.parametrize(
    "sender",
    [
        {"Origin": "http://evil.example"},
        # SameSite counts every port of 127.0.0.1 as this site: a viewer's page, say.
        {"Origin": "http://127.0.0.1:8080"},
        {"Origin": "null"},  # a sandboxed frame or a redirect
        {"Referer": "http://evil.example/attack.html"},
        {"Origin": "https://testserver"},  # another scheme is another origin
    ],
)
def test_changes_from_other_pages_are_refused(accounts: Accounts, sender: dict[str, str]) -> None:
    browser = _browser_of(accounts, "ada")
    refused = browser.post("/api/users/bob/disable", headers=sender)
    assert refused.status_code == 403
    assert "cross-site request from" in refused.json()["detail"]
    assert not _bob_disabled(accounts)
    # Reading is not refused (the answer is not readable by the other page anyway).
    assert browser.get("/api/users", headers=sender).status_code == 200


def test_changes_from_the_apps_own_pages_and_from_scripts_pass(accounts: Accounts) -> None:
    browser = _browser_of(accounts, "ada")
    own = browser.post("/api/users/bob/disable", headers={"Origin": "http://testserver"})
    assert own.status_code == 200 and _bob_disabled(accounts)
    referred = browser.post(
        "/api/users/bob/enable", headers={"Referer": "http://testserver/#/users"}
    )
    assert referred.status_code == 200 and not _bob_disabled(accounts)
    # A script sends neither header (and a token, not the cookie).
    script = accounts.client.post("/api/users/bob/disable", headers=accounts.headers("ada"))
    assert script.status_code == 200


def test_allowed_origins_and_hosts_from_the_settings(tmp_path: Path) -> None:
    settings = Settings(
        data_dir=tmp_path / "data",
        web_dir=tmp_path / "no-web",
        allowed_hosts=["lab.example"],
        allowed_origins=["https://lab.example"],
    )
    with TestClient(create_app(settings), base_url="http://lab.example") as client:
        # Local mode: no accounts, so the first admin may be made; from the proxy's origin.
        made = client.post(
            "/api/users",
            json={"name": "ada", "role": "admin", "password": PASSWORD},
            headers={"Origin": "https://lab.example"},
        )
        assert made.status_code == 201, made.text
        other = client.post("/api/auth/login", headers={"Origin": "https://other.example"})
        assert other.status_code == 403


@pytest.mark.parametrize(
    ("host", "status"),
    [
        ("127.0.0.1:8000", 200),
        ("localhost:8000", 200),
        ("[::1]:8000", 200),
        ("LOCALHOST", 200),
        ("evil.example", 400),
        ("evil.example:8000", 400),
        ("127.0.0.1.evil.example", 400),
        ("", 400),
    ],
)
def test_only_the_servers_own_host_names(client: TestClient, host: str, status: int) -> None:
    answer = client.get("/api/health", headers={"Host": host})
    assert answer.status_code == status
    if status == 400:
        assert "does not answer to the host name" in answer.json()["detail"]


def test_security_headers_on_every_answer(client: TestClient, tmp_path: Path) -> None:
    answers = [
        client.get("/api/health"),  # 200
        client.get("/api/scenes/nosuch"),  # 404
        client.get("/api/health", headers={"Host": "evil.example"}),  # 400
        client.post("/api/scenes/nosuch/edits", content=b"x" * (17 * 1024 * 1024)),  # 413
    ]
    assert [a.status_code for a in answers] == [200, 404, 400, 413]
    for answer in answers:
        assert answer.headers["x-content-type-options"] == "nosniff"
        assert answer.headers["x-frame-options"] == "DENY"
        csp = answer.headers["content-security-policy"]
        assert "frame-ancestors 'none'" in csp and "default-src 'self'" in csp
        # The in-browser detector compiles WebAssembly and runs in a worker.
        assert "'wasm-unsafe-eval'" in csp and "worker-src 'self' blob:" in csp


def test_api_docs_need_a_login_with_accounts(accounts: Accounts) -> None:
    anonymous = TestClient(accounts.client.app)
    for path in ("/docs", "/openapi.json", "/redoc"):
        assert anonymous.get(path).status_code in (401, 404), path
    assert anonymous.get("/docs").status_code == 401
    assert anonymous.get("/openapi.json").status_code == 401
    browser = _browser_of(accounts, "ann")
    described = browser.get("/openapi.json")
    assert described.status_code == 200 and "/api/scenes" in described.json()["paths"]
    page = browser.get("/docs")
    assert page.status_code == 200 and "/openapi.json" in page.text
    # The Swagger page has its own policy (its scripts come from a CDN).
    assert "cdn.jsdelivr.net" in page.headers["content-security-policy"]


def test_api_docs_are_open_in_local_mode(client: TestClient) -> None:
    assert client.get("/openapi.json").status_code == 200
    assert client.get("/docs").status_code == 200
