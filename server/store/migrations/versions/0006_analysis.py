"""Analyses of finished matches (server.ai.analysis): one row a match, claimed by the one
process that analyses it, the result kept once (server.store.analyses); and the drills
set up from analysed shots, one row a practice room (server.store.drills)."""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0006"
down_revision = "0005"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "analyses",
        sa.Column("match_id", sa.Integer, sa.ForeignKey("matches.id"), primary_key=True),
        sa.Column("status", sa.Text, nullable=False),
        sa.Column("requested_at", sa.Double, nullable=False),
        sa.Column("claimed_by", sa.Text),
        sa.Column("claimed_at", sa.Double),
        sa.Column("result", sa.Text),
        sa.Column("finished_at", sa.Double),
    )
    op.create_index("analyses_queue", "analyses", ["status", "requested_at"])
    op.create_table(
        "drills",
        sa.Column("room_id", sa.Text, primary_key=True),
        sa.Column("kind", sa.Text, nullable=False),
        sa.Column("match_id", sa.Integer, sa.ForeignKey("matches.id")),
        sa.Column("n", sa.Integer),
        sa.Column("par", sa.Double),
        sa.Column("created_at", sa.Double, nullable=False),
        sa.Column("score", sa.Integer),
        sa.Column("done", sa.Boolean, nullable=False, server_default=sa.false()),
        sa.Column("won", sa.Boolean, nullable=False, server_default=sa.false()),
    )


def downgrade() -> None:
    op.drop_table("drills")
    op.drop_index("analyses_queue", "analyses")
    op.drop_table("analyses")
