"""`holiscene users ...` and the refusals of `holiscene serve` beyond loopback."""

from __future__ import annotations

from pathlib import Path

import pytest
from holiscene.cli import main

from ..api.conftest import PASSWORD


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_users_add_list_role_and_reset(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    data = str(tmp_path / "data")
    assert _run(capsys, "users", "list", "--data-dir", data)[1].startswith("no accounts")

    # No password given and no terminal to ask on: refused, nothing written.
    monkeypatch.delenv("HOLISCENE_PASSWORD", raising=False)
    monkeypatch.setattr("sys.stdin.isatty", lambda: False)
    status, _, err = _run(capsys, "users", "add", "ada", "--role", "admin", "--data-dir", data)
    assert status == 2 and "HOLISCENE_PASSWORD" in err
    # Weak and empty passwords are refused.
    for weak, message in (("", "empty"), ("short", "at least 10"), ("ada-is-great1", "name")):
        monkeypatch.setenv("HOLISCENE_PASSWORD", weak)
        status, _, err = _run(capsys, "users", "add", "ada", "--role", "admin", "--data-dir", data)
        assert status == 2 and message in err, err
    assert _run(capsys, "users", "list", "--data-dir", data)[1].startswith("no accounts")

    monkeypatch.setenv("HOLISCENE_PASSWORD", PASSWORD)
    status, _, err = _run(capsys, "users", "add", "ann", "--role", "annotator", "--data-dir", data)
    assert status == 2 and "first account must be an admin" in err
    assert _run(capsys, "users", "add", "ada", "--role", "admin", "--data-dir", data)[:2] == (
        0,
        "added ada\n",
    )
    assert _run(capsys, "users", "add", "ann", "--role", "annotator", "--data-dir", data)[0] == 0
    status, _, err = _run(capsys, "users", "add", "ann", "--role", "reviewer", "--data-dir", data)
    assert status == 2 and "already a user" in err
    listed = _run(capsys, "users", "list", "--data-dir", data)[1].splitlines()
    assert [line.split()[:2] for line in listed] == [["ada", "admin"], ["ann", "annotator"]]
    assert _run(capsys, "users", "set-role", "ann", "reviewer", "--data-dir", data)[0] == 0
    status, _, err = _run(capsys, "users", "set-role", "ada", "reviewer", "--data-dir", data)
    assert status == 2 and "only admin" in err
    monkeypatch.setenv("HOLISCENE_PASSWORD", "quartz-meadow-82-lynx")
    assert _run(capsys, "users", "reset-password", "ann", "--data-dir", data)[0] == 0
    status, _, err = _run(capsys, "users", "reset-password", "nobody", "--data-dir", data)
    assert status == 2 and "no user 'nobody'" in err

    from holiscene.cli.users import user_store
    from holiscene.core.settings import Settings

    with user_store(Settings(data_dir=Path(data))) as users:
        assert users.check_credentials("ann", "quartz-meadow-82-lynx") is not None
        assert users.check_credentials("ann", PASSWORD) is None
        assert users.roles() == {"ada": "admin", "ann": "reviewer"}


def test_serve_beyond_loopback_needs_allow_remote_and_an_admin(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    data = str(tmp_path / "data")
    serve = ("serve", "--host", "0.0.0.0", "--port", "1", "--data-dir", data)
    status, _, err = _run(capsys, *serve)
    assert status == 2 and "--allow-remote" in err
    status, _, err = _run(capsys, *serve, "--allow-remote")
    assert status == 2 and "no admin account" in err and "holiscene users add" in err

    from holiscene.cli.users import check_can_serve
    from holiscene.core.settings import Settings

    monkeypatch.setenv("HOLISCENE_PASSWORD", PASSWORD)
    assert _run(capsys, "users", "add", "ada", "--role", "admin", "--data-dir", data)[0] == 0
    remote = Settings(data_dir=Path(data), host="0.0.0.0")
    check_can_serve(remote, allow_remote=True)  # an admin exists: it may serve
    check_can_serve(Settings(data_dir=Path(data), host="127.0.0.1"), allow_remote=False)


def test_users_disable_and_enable(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    from holiscene.cli.users import user_store
    from holiscene.core.settings import Settings
    from holiscene.store.users import AccountDisabledError, SessionEndedError

    data = str(tmp_path / "data")
    monkeypatch.setenv("HOLISCENE_PASSWORD", PASSWORD)
    for name, role in (("ada", "admin"), ("ann", "annotator")):
        assert _run(capsys, "users", "add", name, "--role", role, "--data-dir", data)[0] == 0
    settings = Settings(data_dir=Path(data))
    with user_store(settings) as users:
        user = users.log_in("ann", PASSWORD)
        assert user is not None
        token = users.open_session(user).token  # as a server on the same store would

    assert _run(capsys, "users", "disable", "ann", "--data-dir", data)[:2] == (
        0,
        "ann is now disabled\n",
    )
    listed = _run(capsys, "users", "list", "--data-dir", data)[1].splitlines()
    assert "disabled since" in listed[1] and "disabled" not in listed[0]
    with user_store(settings) as users:
        with pytest.raises(SessionEndedError, match="ann was disabled"):
            users.user_for_token(token)
        with pytest.raises(AccountDisabledError, match="ask an admin"):
            users.log_in("ann", PASSWORD)

    # The only admin stays enabled; unknown names are refused.
    status, _, err = _run(capsys, "users", "disable", "ada", "--data-dir", data)
    assert status == 2 and "only enabled admin" in err
    status, _, err = _run(capsys, "users", "enable", "nobody", "--data-dir", data)
    assert status == 2 and "no user 'nobody'" in err

    assert _run(capsys, "users", "enable", "ann", "--data-dir", data)[:2] == (
        0,
        "ann is now enabled\n",
    )
    with user_store(settings) as users:
        assert users.user_for_token(token) is None  # the old session stays ended
        assert users.log_in("ann", PASSWORD) is not None
        assert [u.disabled for u in users.list_users()] == [False, False]
