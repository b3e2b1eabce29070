"""Scenes record a digest of the files they were imported from (source_digest), so importing
the same photo with the same labels again can be recognised and skipped. Scenes imported
before have none.

Revision ID: 0008
Revises: 0007
"""

import sqlalchemy as sa
from alembic import op

revision = "0008"
down_revision = "0007"
branch_labels = None
depends_on = None


# Plain ALTER TABLE, not a batch: a batch on SQLite copies the table and drops the old one,
# and dropping `scenes` would cascade to every revision.
def upgrade() -> None:
    op.add_column("scenes", sa.Column("source_digest", sa.String(64), nullable=True))
    op.create_index("ix_scenes_source_digest", "scenes", ["source_digest"])


def downgrade() -> None:
    op.drop_index("ix_scenes_source_digest", table_name="scenes")
    op.drop_column("scenes", "source_digest")  # SQLite 3.35 and later (Debian 12: 3.40)
