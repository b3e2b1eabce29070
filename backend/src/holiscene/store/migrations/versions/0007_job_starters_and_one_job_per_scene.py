"""Jobs record who started them (started_by); a scene has at most one pipeline or placement
job queued or running, enforced by a partial unique index. Extra waiting jobs of a scene from
before (only the newest would have counted) are marked failed first.

Revision ID: 0007
Revises: 0006
"""

import sqlalchemy as sa
from alembic import op

revision = "0007"
down_revision = "0006"
branch_labels = None
depends_on = None

_WAITING = "status IN ('queued', 'running') AND kind IN ('pipeline', 'placement')"


def upgrade() -> None:
    with op.batch_alter_table("jobs") as batch:
        batch.add_column(sa.Column("started_by", sa.String(64), nullable=True))
    op.execute(
        sa.text(
            "UPDATE jobs SET status = 'failed', finished_at = CURRENT_TIMESTAMP, "
            "error = 'a newer job of this scene was queued; only one runs at a time' "
            f"WHERE {_WAITING} AND EXISTS (SELECT 1 FROM jobs AS newer "
            "WHERE newer.scene_id = jobs.scene_id "
            "AND newer.status IN ('queued', 'running') "
            "AND newer.kind IN ('pipeline', 'placement') "
            "AND (newer.created_at > jobs.created_at "
            "OR (newer.created_at = jobs.created_at AND newer.id > jobs.id)))"
        )
    )
    op.create_index(
        "uq_jobs_one_waiting_per_scene",
        "jobs",
        ["scene_id"],
        unique=True,
        sqlite_where=sa.text(_WAITING),
        postgresql_where=sa.text(_WAITING),
    )


def downgrade() -> None:
    op.drop_index("uq_jobs_one_waiting_per_scene", table_name="jobs")
    with op.batch_alter_table("jobs") as batch:
        batch.drop_column("started_by")
