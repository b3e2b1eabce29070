"""POST /api/scenes/{id}/viewer: a viewer per scene on 127.0.0.1, reused, rebuilt on edits."""

from __future__ import annotations

import urllib.error
import urllib.request
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from holiscene.viewer import ViewerPool

from ..conftest import folder_upload


def _import(client: TestClient, folder: Path) -> str:
    files = folder_upload(folder)
    response = client.post("/api/scenes", files=files, data={"run_pipeline": "false"})
    assert response.status_code == 201, response.text
    scene_id: str = response.json()["scene"]["id"]
    return scene_id


def _get(url: str) -> int:
    with urllib.request.urlopen(url, timeout=10) as response:
        status: int = response.status
        return status


def test_viewer_route_starts_reuses_and_rebuilds(
    settings: Settings, synthetic_folder: Path
) -> None:
    with TestClient(create_app(settings)) as client:
        scene_id = _import(client, synthetic_folder)
        first = client.post(f"/api/scenes/{scene_id}/viewer")
        assert first.status_code == 200, first.text
        info = first.json()
        assert info["scene_id"] == scene_id and info["revision"] == 1
        assert info["url"].startswith("http://127.0.0.1:")
        assert info["command"].startswith(f"holiscene view {scene_id} --data-dir ")
        assert _get(info["url"]) == 200

        pool: ViewerPool = client.app.state.viewers  # type: ignore[attr-defined]
        viewer = pool.get(scene_id)
        assert viewer is not None
        # Imported, not yet run through the pipeline: the given intrinsics, pitch and roll
        # unknown (the frustum drawn level); no 3D, no supports.
        assert viewer.frustum is not None and viewer.objects == {} and viewer.arrows == {}
        assert "camera pitch/roll unknown" in " ".join(viewer.notes)
        assert len(viewer.dropdown.options) == 1 + len(viewer.scene.objects)

        # The same scene again: the same viewer.
        again = client.post(f"/api/scenes/{scene_id}/viewer").json()
        assert again["url"] == info["url"]
        assert pool.get(scene_id) is viewer

        # A new revision: the same viewer shows it.
        child = viewer.scene.objects[0].id
        edit = {"kind": "set_support", "child": child, "parent": "floor", "type": "below"}
        response = client.post(
            f"/api/scenes/{scene_id}/edits",
            json={"base_revision": 1, "author": "reviewer", "edits": [edit]},
        )
        assert response.status_code == 200, response.text
        updated = client.post(f"/api/scenes/{scene_id}/viewer").json()
        assert updated["url"] == info["url"] and updated["revision"] == 2
        assert [(s.child, s.parent) for s in viewer.scene.supports] == [(child, "floor")]
        assert f"| {child} | {viewer.scene.objects[0].cls} | floor | below |" in (
            viewer.table.content
        )

        missing = client.post("/api/scenes/no-such-scene/viewer")
        assert missing.status_code == 404

    # The app stopped: so did its viewers.
    with pytest.raises(urllib.error.URLError):
        _get(info["url"])


def test_pool_keeps_at_most_max_viewers(settings: Settings, synthetic_folder: Path) -> None:
    with TestClient(create_app(settings)) as client:
        ids = [_import(client, synthetic_folder) for _ in range(2)]
        pool: ViewerPool = client.app.state.viewers  # type: ignore[attr-defined]
        pool.max_viewers = 1
        urls = [client.post(f"/api/scenes/{i}/viewer").json()["url"] for i in ids]
        assert pool.keys() == [ids[1]]
        with pytest.raises(urllib.error.URLError):
            _get(urls[0])
        assert _get(urls[1]) == 200
