"""Users and sessions; scene workflow state, assignee, annotation round, uncertainty and the
history of state changes.

Revision ID: 0003
Revises: 0002
"""

import json
from typing import Any

import sqlalchemy as sa
from alembic import op

revision = "0003"
down_revision = "0002"
branch_labels = None
depends_on = None

# Frozen copies of the rules at the time of this migration (the code may change later).
_STRUCTURAL = {"wall", "floor", "ceiling"}


def _uncertainty(scene: dict[str, Any]) -> float:
    ids = [o["id"] for o in scene.get("objects", []) if o.get("class") not in _STRUCTURAL]
    if not ids:
        return 0.0
    supports = {s["child"]: s for s in scene.get("supports", [])}
    total = 0.0
    for object_id in ids:
        support = supports.get(object_id)
        if support is None:
            total += 1.0
        elif support.get("source") == "auto":
            confidence = support.get("confidence")
            total += 1.0 - (0.5 if confidence is None else confidence)
    return round(total / len(ids), 6)


def upgrade() -> None:
    op.create_table(
        "users",
        sa.Column("id", sa.Integer, primary_key=True, autoincrement=True),
        sa.Column("name", sa.String(64), nullable=False, unique=True),
        sa.Column("role", sa.String(16), nullable=False),
        sa.Column("password_hash", sa.String(255), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
    )
    op.create_table(
        "sessions",
        sa.Column("token_hash", sa.String(64), primary_key=True),
        sa.Column(
            "user_id",
            sa.Integer,
            sa.ForeignKey("users.id", ondelete="CASCADE"),
            nullable=False,
        ),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("expires_at", sa.DateTime(timezone=True), nullable=False),
    )
    op.create_index("ix_sessions_user_id", "sessions", ["user_id"])
    op.create_table(
        "scene_events",
        sa.Column("id", sa.Integer, primary_key=True, autoincrement=True),
        sa.Column(
            "scene_id",
            sa.String(32),
            sa.ForeignKey("scenes.id", ondelete="CASCADE"),
            nullable=False,
        ),
        sa.Column("at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("actor", sa.String(64), nullable=False),
        sa.Column("action", sa.String(32), nullable=False),
        sa.Column("from_state", sa.String(16), nullable=True),
        sa.Column("to_state", sa.String(16), nullable=False),
        sa.Column("assignee", sa.String(64), nullable=True),
        sa.Column("revision", sa.Integer, nullable=False),
        sa.Column("annotation_round", sa.Integer, nullable=False),
        sa.Column("comment", sa.Text, nullable=True),
    )
    op.create_index("ix_scene_events_scene_id", "scene_events", ["scene_id"])
    with op.batch_alter_table("scenes") as batch:
        batch.add_column(sa.Column("state", sa.String(16), nullable=False, server_default="new"))
        batch.add_column(sa.Column("assignee", sa.String(64), nullable=True))
        batch.add_column(
            sa.Column("annotation_round", sa.Integer, nullable=False, server_default="1")
        )
        batch.add_column(sa.Column("uncertainty", sa.Float, nullable=True))
        batch.create_index("ix_scenes_state", ["state"])
        batch.create_index("ix_scenes_assignee", ["assignee"])

    # Scenes stored before: predicted once the pipeline ran, in annotation (nobody's) once a
    # person edited them; uncertainty of the current revision.
    bind = op.get_bind()
    rows = bind.execute(
        sa.text(
            "SELECT s.id, r.scene, "
            "EXISTS (SELECT 1 FROM revisions p WHERE p.scene_id = s.id AND p.kind = 'pipeline'),"
            " EXISTS (SELECT 1 FROM revisions e WHERE e.scene_id = s.id AND e.kind = 'edit') "
            "FROM scenes s JOIN revisions r "
            "ON r.scene_id = s.id AND r.number = s.current_revision"
        )
    ).all()
    for scene_id, scene, predicted, edited in rows:
        data = json.loads(scene) if isinstance(scene, str) else scene
        state = "in_annotation" if edited else "predicted" if predicted else "new"
        bind.execute(
            sa.text("UPDATE scenes SET state = :state, uncertainty = :u WHERE id = :id"),
            {"state": state, "u": _uncertainty(data), "id": scene_id},
        )


def downgrade() -> None:
    with op.batch_alter_table("scenes") as batch:
        batch.drop_index("ix_scenes_assignee")
        batch.drop_index("ix_scenes_state")
        batch.drop_column("uncertainty")
        batch.drop_column("annotation_round")
        batch.drop_column("assignee")
        batch.drop_column("state")
    op.drop_table("scene_events")
    op.drop_table("sessions")
    op.drop_table("users")
