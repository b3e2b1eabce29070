"""Scenes can be archived by an admin (archived_at, archived_by): kept with every revision,
but out of the scene list, "Next scene", reviews, retraining and batch runs, and read only,
until an admin restores them. A junk import (an all-black photo, a duplicate) no longer
waits at the top of "Next scene" with nobody able to remove it.

Revision ID: 0013
Revises: 0012
"""

import sqlalchemy as sa
from alembic import op

revision = "0013"
down_revision = "0012"
branch_labels = None
depends_on = None


# Plain ALTER TABLE, as in 0008: a batch on SQLite would drop and copy `scenes`.
def upgrade() -> None:
    op.add_column("scenes", sa.Column("archived_at", sa.DateTime(timezone=True), nullable=True))
    op.add_column("scenes", sa.Column("archived_by", sa.String(64), nullable=True))


def downgrade() -> None:
    op.drop_column("scenes", "archived_by")
    op.drop_column("scenes", "archived_at")
