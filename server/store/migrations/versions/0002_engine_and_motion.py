"""Which engine played each shot, and the motion every member was shown (zlib of
`protocol.plan.motion_text`): a replay shows that, not a re-simulation by a newer engine.
Older rows have neither. (Was `PRAGMA user_version` 2.)"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0002"
down_revision = "0001"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.add_column("shots", sa.Column("engine", sa.Text))
    op.add_column("shots", sa.Column("motion", sa.LargeBinary))


def downgrade() -> None:
    with op.batch_alter_table("shots") as batch:
        batch.drop_column("motion")
        batch.drop_column("engine")
