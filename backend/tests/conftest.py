"""Shared fixtures: the real photos beside the repository, and a server on a temporary store."""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import REPO_ROOT, Settings
from holiscene.synth.generate import synthesize_to
from holiscene_schema import FINISHED_JOB_STATUSES

# SQLite, and PostgreSQL for tests marked both_databases (see databases.py).
from .databases import database_url, postgres_server, pytest_configure, pytest_generate_tests

__all__ = ["database_url", "postgres_server", "pytest_configure", "pytest_generate_tests"]

REAL_PHOTOS = REPO_ROOT.parent / "shared" / "data" / "real"
SYNTHETIC_ROOM_SEED = 14


@pytest.fixture(scope="session")
def real_photos() -> Path:
    if not (REAL_PHOTOS / "t3d-5" / "img.jpg").is_file():
        pytest.fail(f"the real test photos are missing: expected them in {REAL_PHOTOS}")
    return REAL_PHOTOS


@pytest.fixture()
def t3d5(real_photos: Path) -> Path:
    return real_photos / "t3d-5"


@pytest.fixture(scope="package")
def synthetic_folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """img.png, cam_K.txt, detections.json and gt.json of one synthetic room (seed 14: a wall
    picture, things on furniture), for the viewer's tests through the API, the command line
    and the viewer itself; read only."""
    return synthesize_to(SYNTHETIC_ROOM_SEED, tmp_path_factory.mktemp("synth"))


@pytest.fixture()
def settings(tmp_path: Path, database_url: str | None) -> Settings:
    return Settings(
        data_dir=tmp_path / "data", web_dir=tmp_path / "no-web", database_url=database_url
    )


@pytest.fixture()
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(create_app(settings)) as test_client:
        yield test_client


def upload(client: TestClient, folder: Path, **form: str) -> dict:  # type: ignore[type-arg]
    files = {"image": ("img.jpg", (folder / "img.jpg").read_bytes(), "image/jpeg")}
    if (folder / "cam_K.txt").is_file():
        files["cam_k"] = ("cam_K.txt", (folder / "cam_K.txt").read_bytes(), "text/plain")
    if (folder / "detections.json").is_file():
        files["detections"] = (
            "detections.json",
            (folder / "detections.json").read_bytes(),
            "application/json",
        )
    response = client.post("/api/scenes", files=files, data=form)
    assert response.status_code == 201, response.text
    return response.json()  # type: ignore[no-any-return]


def wait_for_job(client: TestClient, job_id: str, timeout: float = 30.0) -> dict:  # type: ignore[type-arg]
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        job = client.get(f"/api/jobs/{job_id}").json()
        if job["status"] in FINISHED_JOB_STATUSES:
            return job  # type: ignore[no-any-return]
        time.sleep(0.05)
    raise AssertionError(f"job {job_id} did not finish in {timeout} s")


def imported_scene(
    client: TestClient, folder: Path, name: str, run_pipeline: bool = True
) -> dict[str, Any]:
    """The latest revision of `folder` uploaded as a new scene (after its pipeline job)."""
    result = upload(client, folder, name=name, run_pipeline=str(run_pipeline).lower())
    if run_pipeline:
        job = wait_for_job(client, result["job"]["id"])
        assert job["status"] == "succeeded", job
    doc: dict[str, Any] = client.get(f"/api/scenes/{result['scene']['id']}").json()
    return doc


def post_edits(client: TestClient, doc: dict[str, Any], *edits: dict[str, Any]) -> Any:
    """The response to `edits` made by "ann" on the revision `doc`."""
    body = {"base_revision": doc["revision"], "author": "ann", "edits": list(edits)}
    return client.post(f"/api/scenes/{doc['scene_id']}/edits", json=body)
