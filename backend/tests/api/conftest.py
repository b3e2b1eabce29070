"""A server with accounts: an admin made through the API while the server is still in local
mode (as a person would), then annotators and reviewers made by that admin."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from holiscene.api.app import create_app
from holiscene.core.settings import Settings
from holiscene.services.workbench import Workbench

PASSWORD = "tram-lilac-47-orbit"


@dataclass
class Accounts:
    client: TestClient
    tokens: dict[str, str]

    @property
    def workbench(self) -> Workbench:
        workbench: Workbench = self.client.app.state.workbench  # type: ignore[attr-defined]
        return workbench

    def headers(self, name: str) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.tokens[name]}"}

    def login(self, name: str, password: str = PASSWORD) -> str:
        response = self.client.post(
            "/api/auth/login", json={"name": name, "password": password, "token": True}
        )
        assert response.status_code == 200, response.text
        token: str = response.json()["token"]
        self.tokens[name] = token
        return token

    def add(self, name: str, role: str, by: str = "ada") -> None:
        response = self.client.post(
            "/api/users",
            json={"name": name, "role": role, "password": PASSWORD},
            headers=self.headers(by),
        )
        assert response.status_code == 201, response.text
        self.login(name)


@pytest.fixture()
def accounts(settings: Settings) -> Iterator[Accounts]:
    """ada (admin), ann and bob (annotators), rita and rex (reviewers), each logged in."""
    with TestClient(create_app(settings)) as client:
        first = client.post(
            "/api/users", json={"name": "ada", "role": "admin", "password": PASSWORD}
        )
        assert first.status_code == 201, first.text
        made = Accounts(client, {})
        made.login("ada")
        for name, role in (
            ("ann", "annotator"),
            ("bob", "annotator"),
            ("rita", "reviewer"),
            ("rex", "reviewer"),
        ):
            made.add(name, role)
        yield made


def folder_upload(folder: Path, depth: bool = False) -> dict[str, Any]:
    """The upload form's files for an input folder made by `holiscene synth` (photo, K, boxes,
    and its depth when asked)."""
    files: dict[str, Any] = {
        "image": ("img.png", (folder / "img.png").read_bytes(), "image/png"),
        "cam_k": ("cam_K.txt", (folder / "cam_K.txt").read_bytes(), "text/plain"),
        "detections": (
            "detections.json",
            (folder / "detections.json").read_bytes(),
            "application/json",
        ),
    }
    if depth:
        files["depth"] = ("depth.png", (folder / "depth.png").read_bytes(), "image/png")
    return files
