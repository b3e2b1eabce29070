"""Scenes record a digest of their photo's file (photo_digest), so the held-out split keeps
every scene of one photo on one side: a scene downloaded, edited and imported again is a new
scene of the same photo. Scenes stored before get theirs from their file when a split first
needs it (SceneStore.split_keys).

Revision ID: 0011
Revises: 0010
"""

import sqlalchemy as sa
from alembic import op

revision = "0011"
down_revision = "0010"
branch_labels = None
depends_on = None


# Plain ALTER TABLE, as in 0008: a batch on SQLite would drop and copy `scenes`.
def upgrade() -> None:
    op.add_column("scenes", sa.Column("photo_digest", sa.String(64), nullable=True))
    op.create_index("ix_scenes_photo_digest", "scenes", ["photo_digest"])


def downgrade() -> None:
    op.drop_index("ix_scenes_photo_digest", table_name="scenes")
    op.drop_column("scenes", "photo_digest")
