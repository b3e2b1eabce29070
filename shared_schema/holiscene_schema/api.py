"""What the app and the server exchange: edits, scene documents, revisions and jobs."""

from __future__ import annotations

from datetime import datetime
from typing import Annotated, Literal

from pydantic import Field

from .scene import Scene, SchemaModel, SupportType


class SetSupport(SchemaModel):
    """Make `parent` the supporter of `child` (replacing any supporter it had)."""

    kind: Literal["set_support"] = "set_support"
    child: str
    parent: str
    type: SupportType


class RemoveSupport(SchemaModel):
    """Leave `child` without a supporter (it is then flagged for labelling)."""

    kind: Literal["remove_support"] = "remove_support"
    child: str


Edit = Annotated[SetSupport | RemoveSupport, Field(discriminator="kind")]


class EditRequest(SchemaModel):
    base_revision: int = Field(ge=1, description="The revision the edits were made on")
    author: str = Field(min_length=1, max_length=64)
    edits: list[Edit] = Field(min_length=1, max_length=500)


class SceneDocument(SchemaModel):
    scene_id: str
    revision: int
    updated_at: datetime
    scene: Scene


RevisionKind = Literal["import", "pipeline", "edit"]


class RevisionInfo(SchemaModel):
    number: int
    created_at: datetime
    author: str
    kind: RevisionKind
    summary: str
    edits: list[Edit] | None = None


JobStatus = Literal["queued", "running", "succeeded", "failed"]


class Job(SchemaModel):
    id: str
    scene_id: str
    kind: Literal["pipeline"]
    status: JobStatus
    progress: float = Field(ge=0.0, le=1.0)
    stage: str | None = None
    message: str | None = None
    error: str | None = None
    base_revision: int
    result_revision: int | None = None
    created_at: datetime
    finished_at: datetime | None = None


class SceneSummary(SchemaModel):
    id: str
    name: str
    revision: int
    created_at: datetime
    updated_at: datetime
    width: int
    height: int
    object_count: int
    latest_job: Job | None = None


class ImportResult(SchemaModel):
    scene: SceneSummary
    job: Job | None


class ConflictDetail(SchemaModel):
    message: str
    current_revision: int


class ErrorMessage(SchemaModel):
    detail: str


class Conflict(SchemaModel):
    detail: ConflictDetail
