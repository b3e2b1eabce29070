"""All configuration in one place; every field can be set as HOLISCENE_<NAME> in the environment."""

from __future__ import annotations

from datetime import timedelta
from pathlib import Path

from holiscene_schema.api import FEW_HELDOUT_ITEMS
from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict

REPO_ROOT = Path(__file__).resolve().parents[4]


class Settings(BaseSettings):
    model_config = SettingsConfigDict(env_prefix="HOLISCENE_")

    data_dir: Path = REPO_ROOT / "var" / "data"
    database_url: str | None = None  # default: SQLite file inside data_dir
    web_dir: Path = REPO_ROOT / "frontend" / "dist"
    host: str = "127.0.0.1"
    port: int = 8000
    max_upload_mb: int = 50  # a photo import (POST /api/scenes)
    # A dataset uploaded as a .zip (POST /api/imports): the upload, what it may unpack to,
    # and how many files it may hold (a zip bomb is refused before it is unpacked).
    max_import_mb: int = Field(default=1024, gt=0)
    max_import_unpacked_mb: int = Field(default=4096, gt=0)
    max_import_files: int = Field(default=20_000, gt=0)
    # Any other request body; larger ones are refused (413) before they are read.
    max_request_mb: float = Field(default=16.0, gt=0)
    # Host names the server answers to besides the loopback names and `host` (400 for others:
    # a page on another name that resolves here must not reach the server; see
    # docs/security.md). As JSON in the environment: HOLISCENE_ALLOWED_HOSTS='["lab.example"]'.
    allowed_hosts: list[str] = Field(default_factory=list)
    # Origins (scheme://host[:port]) besides the server's own whose pages may change things
    # here (POST, PUT, PATCH, DELETE), e.g. behind a proxy that rewrites the Host header.
    allowed_origins: list[str] = Field(default_factory=list)
    models_dir: Path | None = None  # the user's own models: <class>/*.obj|glb|ply
    # Pipeline and placement jobs queued or running at once, on all scenes (503 beyond): one
    # worker runs them, so a longer queue only means longer waits.
    max_queued_jobs: int = Field(default=20, gt=0)
    # A retrained model better on the held-out scenes is made active by itself only when
    # those scenes hold at least this many labelled items (objects, or boxes for the
    # detector); on fewer it waits as a candidate for an admin to make active.
    promote_min_heldout_items: int = Field(default=FEW_HELDOUT_ITEMS, ge=1)
    # A login session ends after this long without a request (each request moves it on).
    session_idle_hours: float = Field(default=8.0, gt=0)

    @property
    def resolved_database_url(self) -> str:
        return self.database_url or f"sqlite:///{self.data_dir / 'holiscene.db'}"

    @property
    def session_idle_timeout(self) -> timedelta:
        return timedelta(hours=self.session_idle_hours)
