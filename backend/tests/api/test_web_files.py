"""How the built workbench is cached: hashed assets for good, index.html checked each time."""

from __future__ import annotations

from pathlib import Path

from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings


def test_hashed_assets_are_kept_for_good_and_the_page_is_checked_every_time(
    tmp_path: Path,
) -> None:
    web = tmp_path / "web"
    (web / "assets").mkdir(parents=True)
    (web / "index.html").write_text('<script src="/assets/main-Ab12.js"></script>')
    (web / "assets" / "main-Ab12.js").write_text("console.log(1)")
    (web / "favicon.svg").write_text("<svg/>")
    settings = Settings(data_dir=tmp_path / "data", web_dir=web)
    with TestClient(
        create_app(settings), base_url=f"http://{settings.host}:{settings.port}"
    ) as client:
        page, script, icon, missing = (
            client.get(path)
            for path in ("/", "/assets/main-Ab12.js", "/favicon.svg", "/assets/gone-Cd34.js")
        )
        assert (page.status_code, script.status_code, icon.status_code) == (200, 200, 200)
        assert page.headers["cache-control"] == "no-cache"
        assert script.headers["cache-control"] == "public, max-age=31536000, immutable"
        assert icon.headers["cache-control"] == "no-cache"
        assert missing.status_code == 404
        assert "immutable" not in missing.headers.get("cache-control", "")
        # The security headers still come with the files.
        assert script.headers["x-content-type-options"] == "nosniff"


def test_an_unknown_address_gets_a_page_in_a_browser_and_json_under_api(tmp_path: Path) -> None:
    web = tmp_path / "web"
    web.mkdir()
    (web / "index.html").write_text("<p>workbench</p>")
    (web / "404.html").write_text("<h1>No such page</h1>")
    settings = Settings(data_dir=tmp_path / "data", web_dir=web)
    with TestClient(
        create_app(settings), base_url=f"http://{settings.host}:{settings.port}"
    ) as client:
        page = client.get("/scenes/abc")  # typed without the app's /#/
        assert page.status_code == 404 and "No such page" in page.text
        api = client.get("/api/no-such-thing")
        assert api.status_code == 404 and api.json() == {"detail": "Not Found"}
