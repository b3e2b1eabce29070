"""Database tables. Every change of a scene is a new row in `revisions`; nothing is overwritten."""

from __future__ import annotations

from datetime import datetime
from typing import Any

from sqlalchemy import (
    JSON,
    Boolean,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    String,
    Text,
    UniqueConstraint,
    text,
)
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column


class Base(DeclarativeBase):
    pass


# The longest scene name (PostgreSQL refuses a longer one); the upload form and the store's
# numbered names keep to it.
SCENE_NAME_LENGTH = 200


class SceneRow(Base):
    __tablename__ = "scenes"

    id: Mapped[str] = mapped_column(String(32), primary_key=True)
    name: Mapped[str] = mapped_column(String(SCENE_NAME_LENGTH))
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    updated_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    current_revision: Mapped[int] = mapped_column(Integer)
    image_file: Mapped[str] = mapped_column(String(64))
    width: Mapped[int] = mapped_column(Integer)
    height: Mapped[int] = mapped_column(Integer)
    object_count: Mapped[int] = mapped_column(Integer)
    glb_revision: Mapped[int | None] = mapped_column(Integer, nullable=True)
    # The annotation workflow (migration 0003); every change is also a row of scene_events.
    state: Mapped[str] = mapped_column(String(16), index=True, default="new")
    assignee: Mapped[str | None] = mapped_column(String(64), nullable=True, index=True)
    annotation_round: Mapped[int] = mapped_column(Integer, default=1)
    # Of the current revision (holiscene.editing.workflow_rules.scene_uncertainty); "Next scene"
    # sorts by it.
    uncertainty: Mapped[float | None] = mapped_column(Float, nullable=True)
    # What it was imported from (InputFiles.digest, migration 0008): a second import of the
    # same photo and labels is skipped. None for scenes imported before.
    source_digest: Mapped[str | None] = mapped_column(String(64), nullable=True, index=True)
    # SHA-256 of the photo's file (migration 0011): scenes of one photo share a side of the
    # held-out split. Filled from the file, when first needed, for scenes stored before.
    photo_digest: Mapped[str | None] = mapped_column(String(64), nullable=True, index=True)
    # Archived by an admin (migration 0013): out of the lists and "Next scene", read only,
    # every revision kept; None while in use.
    archived_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True), nullable=True)
    archived_by: Mapped[str | None] = mapped_column(String(64), nullable=True)


# The scenes in use, not archived: the lists, "Next scene", retraining and batch runs.
SCENE_IN_USE = SceneRow.archived_at.is_(None)


class RevisionRow(Base):
    __tablename__ = "revisions"
    __table_args__ = (UniqueConstraint("scene_id", "number"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    scene_id: Mapped[str] = mapped_column(ForeignKey("scenes.id", ondelete="CASCADE"), index=True)
    number: Mapped[int] = mapped_column(Integer)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    author: Mapped[str] = mapped_column(String(64))
    kind: Mapped[str] = mapped_column(String(16))
    summary: Mapped[str] = mapped_column(Text)
    edits: Mapped[list[dict[str, Any]] | None] = mapped_column(JSON, nullable=True)
    scene: Mapped[dict[str, Any]] = mapped_column(JSON)


# A scene's pipeline or placement job waiting or running (migration 0007): at most one each,
# which the database itself enforces (two requests at once cannot both queue one).
WAITING_SCENE_JOB = text("status IN ('queued', 'running') AND kind IN ('pipeline', 'placement')")


class JobRow(Base):
    __tablename__ = "jobs"
    __table_args__ = (
        Index(
            "uq_jobs_one_waiting_per_scene",
            "scene_id",
            unique=True,
            sqlite_where=WAITING_SCENE_JOB,
            postgresql_where=WAITING_SCENE_JOB,
        ),
    )

    id: Mapped[str] = mapped_column(String(32), primary_key=True)
    # Retrain jobs belong to no scene (migration 0002 made this nullable).
    scene_id: Mapped[str | None] = mapped_column(
        ForeignKey("scenes.id", ondelete="CASCADE"), index=True, nullable=True
    )
    kind: Mapped[str] = mapped_column(String(16))
    status: Mapped[str] = mapped_column(String(16), index=True)
    progress: Mapped[float] = mapped_column(Float)
    stage: Mapped[str | None] = mapped_column(String(64), nullable=True)
    message: Mapped[str | None] = mapped_column(Text, nullable=True)
    error: Mapped[str | None] = mapped_column(Text, nullable=True)
    log: Mapped[str | None] = mapped_column(Text, nullable=True)
    base_revision: Mapped[int | None] = mapped_column(Integer, nullable=True)
    result_revision: Mapped[int | None] = mapped_column(Integer, nullable=True)
    result_model_id: Mapped[str | None] = mapped_column(String(32), nullable=True)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    finished_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True), nullable=True)
    # Who asked for it: an account (or the local user), or "import" (migration 0007; NULL
    # for jobs from before).
    started_by: Mapped[str | None] = mapped_column(String(64), nullable=True)


class ImportJobRow(Base):
    """A dataset uploaded as a .zip and imported in the background (migration 0009): how far
    it got and, per photo, the scene made, the scene imported before, or why not."""

    __tablename__ = "import_jobs"

    id: Mapped[str] = mapped_column(String(32), primary_key=True)
    status: Mapped[str] = mapped_column(String(16), index=True)
    archive: Mapped[str] = mapped_column(String(200))
    format: Mapped[str | None] = mapped_column(String(64), nullable=True)
    total: Mapped[int] = mapped_column(Integer)
    done: Mapped[int] = mapped_column(Integer)
    run_pipeline: Mapped[bool] = mapped_column(Boolean)
    # [{"name", "scene_id"}] and [{"name", "message"}], in the order the photos were read.
    imported: Mapped[list[dict[str, str]]] = mapped_column(JSON)
    skipped: Mapped[list[dict[str, str]]] = mapped_column(JSON)
    errors: Mapped[list[dict[str, str]]] = mapped_column(JSON)
    error: Mapped[str | None] = mapped_column(Text, nullable=True)
    started_by: Mapped[str | None] = mapped_column(String(64), nullable=True)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    finished_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True), nullable=True)


class ModelRow(Base):
    """A registered model: a Relation Network (files in <data_dir>/models/<id>/) or an object
    detector (<data_dir>/detectors/<id>/). Rows are only added once the files are complete,
    and never change afterwards. Versions count per kind (migration 0006)."""

    __tablename__ = "models"
    __table_args__ = (UniqueConstraint("kind", "version", name="uq_models_kind_version"),)

    id: Mapped[str] = mapped_column(String(32), primary_key=True)
    kind: Mapped[str] = mapped_column(String(16), default="relation")
    version: Mapped[int] = mapped_column(Integer)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    status: Mapped[str] = mapped_column(String(16))
    parent_id: Mapped[str | None] = mapped_column(String(32), nullable=True)
    job_id: Mapped[str | None] = mapped_column(String(32), nullable=True)
    heldout_accuracy: Mapped[float | None] = mapped_column(Float, nullable=True)
    parent_heldout_accuracy: Mapped[float | None] = mapped_column(Float, nullable=True)
    validation_accuracy: Mapped[float | None] = mapped_column(Float, nullable=True)
    metrics: Mapped[dict[str, Any]] = mapped_column(JSON)
    # The labelled scenes (id@revision) it was trained and evaluated on, and its config.
    data: Mapped[dict[str, Any]] = mapped_column(JSON)
    note: Mapped[str | None] = mapped_column(Text, nullable=True)


class ModelEventRow(Base):
    """Every change of an active model; the newest row of a kind's models names its active
    one."""

    __tablename__ = "model_events"

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    action: Mapped[str] = mapped_column(String(16))
    actor: Mapped[str] = mapped_column(String(64))
    model_id: Mapped[str] = mapped_column(ForeignKey("models.id"), index=True)
    previous_model_id: Mapped[str | None] = mapped_column(String(32), nullable=True)
    note: Mapped[str | None] = mapped_column(Text, nullable=True)


class UserRow(Base):
    __tablename__ = "users"

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    name: Mapped[str] = mapped_column(String(64), unique=True)
    role: Mapped[str] = mapped_column(String(16))
    password_hash: Mapped[str] = mapped_column(String(255))  # argon2id, never the password
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    # Set while an admin has disabled the account (migration 0004): no login, no session.
    disabled_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True), nullable=True)


class SessionRow(Base):
    """A login. Only the SHA-256 of the token is stored: a copy of the database opens no
    session."""

    __tablename__ = "sessions"

    token_hash: Mapped[str] = mapped_column(String(64), primary_key=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    expires_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    # The session's last request (migration 0004): it ends after Settings.session_idle_hours
    # without one.
    last_seen_at: Mapped[datetime] = mapped_column(DateTime(timezone=True))


class SceneEventRow(Base):
    """Every change of a scene's workflow state or assignee: who, when, on which revision."""

    __tablename__ = "scene_events"

    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    scene_id: Mapped[str] = mapped_column(ForeignKey("scenes.id", ondelete="CASCADE"), index=True)
    at: Mapped[datetime] = mapped_column(DateTime(timezone=True))
    actor: Mapped[str] = mapped_column(String(64))
    action: Mapped[str] = mapped_column(String(32))
    from_state: Mapped[str | None] = mapped_column(String(16), nullable=True)
    to_state: Mapped[str] = mapped_column(String(16))
    assignee: Mapped[str | None] = mapped_column(String(64), nullable=True)
    revision: Mapped[int] = mapped_column(Integer)
    annotation_round: Mapped[int] = mapped_column(Integer)
    comment: Mapped[str | None] = mapped_column(Text, nullable=True)
