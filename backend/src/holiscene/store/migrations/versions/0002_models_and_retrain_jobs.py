"""Relation Network model registry; jobs without a scene (retraining) and with a log.

Revision ID: 0002
Revises: 0001
"""

import sqlalchemy as sa
from alembic import op

revision = "0002"
down_revision = "0001"
branch_labels = None
depends_on = None


def upgrade() -> None:
    # Batch mode: SQLite cannot alter a column in place, so Alembic copies the table.
    with op.batch_alter_table("jobs") as batch:
        batch.alter_column("scene_id", existing_type=sa.String(32), nullable=True)
        batch.alter_column("base_revision", existing_type=sa.Integer, nullable=True)
        batch.add_column(sa.Column("log", sa.Text, nullable=True))
        batch.add_column(sa.Column("result_model_id", sa.String(32), nullable=True))
    op.create_table(
        "models",
        sa.Column("id", sa.String(32), primary_key=True),
        sa.Column("version", sa.Integer, nullable=False, unique=True),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("status", sa.String(16), nullable=False),
        sa.Column("parent_id", sa.String(32), nullable=True),
        sa.Column("job_id", sa.String(32), nullable=True),
        sa.Column("heldout_accuracy", sa.Float, nullable=True),
        sa.Column("parent_heldout_accuracy", sa.Float, nullable=True),
        sa.Column("validation_accuracy", sa.Float, nullable=True),
        sa.Column("metrics", sa.JSON, nullable=False),
        sa.Column("data", sa.JSON, nullable=False),
        sa.Column("note", sa.Text, nullable=True),
    )
    op.create_table(
        "model_events",
        sa.Column("id", sa.Integer, primary_key=True, autoincrement=True),
        sa.Column("at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("action", sa.String(16), nullable=False),
        sa.Column("actor", sa.String(64), nullable=False),
        sa.Column("model_id", sa.String(32), sa.ForeignKey("models.id"), nullable=False),
        sa.Column("previous_model_id", sa.String(32), nullable=True),
        sa.Column("note", sa.Text, nullable=True),
    )
    op.create_index("ix_model_events_model_id", "model_events", ["model_id"])


def downgrade() -> None:
    op.drop_table("model_events")
    op.drop_table("models")
    op.execute("DELETE FROM jobs WHERE scene_id IS NULL")
    with op.batch_alter_table("jobs") as batch:
        batch.drop_column("result_model_id")
        batch.drop_column("log")
        batch.alter_column("base_revision", existing_type=sa.Integer, nullable=False)
        batch.alter_column("scene_id", existing_type=sa.String(32), nullable=False)
