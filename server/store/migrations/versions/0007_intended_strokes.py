"""The computer's intended stroke beside the one played (its plan before the arm's error),
so the analysis judges what it meant, as it judges a person's stroke as sent; and the
tries a drill room holds (Rerack starts another ghost rack or line-up run in the same
room) and how many were won."""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0007"
down_revision = "0006"
branch_labels = None
depends_on = None


def upgrade() -> None:
    with op.batch_alter_table("shots") as batch:
        batch.add_column(sa.Column("intended", sa.Text))
    with op.batch_alter_table("drills") as batch:
        batch.add_column(sa.Column("tries", sa.Integer))
        batch.add_column(sa.Column("cleared", sa.Integer))


def downgrade() -> None:
    with op.batch_alter_table("drills") as batch:
        batch.drop_column("cleared")
        batch.drop_column("tries")
    with op.batch_alter_table("shots") as batch:
        batch.drop_column("intended")
