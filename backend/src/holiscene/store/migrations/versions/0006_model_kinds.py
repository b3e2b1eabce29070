"""Model kinds: the registry holds Relation Networks and object detectors, each kind with its
own versions. Existing models are Relation Networks.

Revision ID: 0006
Revises: 0005
"""

import sqlalchemy as sa
from alembic import op

revision = "0006"
down_revision = "0005"
branch_labels = None
depends_on = None

# Names for constraints that were created without one (SQLite reflects them unnamed; batch
# mode then calls them by this convention).
_NAMING = {"uq": "uq_%(table_name)s_%(column_0_name)s"}


def _version_constraint_name() -> str:
    """The name of the unique constraint on models.version (PostgreSQL named it itself)."""
    for constraint in sa.inspect(op.get_bind()).get_unique_constraints("models"):
        if constraint["column_names"] == ["version"] and constraint["name"]:
            return str(constraint["name"])
    return "uq_models_version"


_EVENT_COLUMNS = "id, at, action, actor, model_id, previous_model_id, note"


def _set_events_aside() -> bool:
    """SQLite changes a table's constraints by copying it and dropping the old one, which it
    refuses while rows of model_events refer to it (foreign keys are on): the events wait in
    a plain table meanwhile. Other databases alter the table in place."""
    if op.get_bind().dialect.name != "sqlite":
        return False
    op.execute(f"CREATE TABLE _model_events_aside AS SELECT {_EVENT_COLUMNS} FROM model_events")
    op.execute("DELETE FROM model_events")
    return True


def _put_events_back() -> None:
    op.execute(
        f"INSERT INTO model_events ({_EVENT_COLUMNS}) "
        f"SELECT {_EVENT_COLUMNS} FROM _model_events_aside"
    )
    op.execute("DROP TABLE _model_events_aside")


def upgrade() -> None:
    old_name = _version_constraint_name()
    aside = _set_events_aside()
    with op.batch_alter_table("models", naming_convention=_NAMING) as batch:
        batch.add_column(
            sa.Column("kind", sa.String(16), nullable=False, server_default="relation")
        )
        batch.drop_constraint(old_name, type_="unique")
        batch.create_unique_constraint("uq_models_kind_version", ["kind", "version"])
    if aside:
        _put_events_back()


def downgrade() -> None:
    # Before kinds every model was a Relation Network: the detectors go with their history.
    op.execute(
        "DELETE FROM model_events "
        "WHERE model_id IN (SELECT id FROM models WHERE kind != 'relation')"
    )
    op.execute("DELETE FROM models WHERE kind != 'relation'")
    aside = _set_events_aside()
    with op.batch_alter_table("models", naming_convention=_NAMING) as batch:
        batch.drop_constraint("uq_models_kind_version", type_="unique")
        batch.drop_column("kind")
        batch.create_unique_constraint("uq_models_version", ["version"])
    if aside:
        _put_events_back()
