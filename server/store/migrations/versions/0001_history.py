"""Matches, games, shots and the saved live rooms (was `PRAGMA user_version` 1)."""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0001"
down_revision = None
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "matches",
        sa.Column("id", sa.Integer, primary_key=True, autoincrement=False),
        sa.Column("room_id", sa.Text, nullable=False),
        sa.Column("kind", sa.Text, nullable=False),
        sa.Column("players", sa.Text, nullable=False),
        sa.Column("race_to", sa.Integer, nullable=False),
        sa.Column("status", sa.Text, nullable=False),
        sa.Column("score", sa.Text, nullable=False),
        sa.Column("winner", sa.Integer),
        sa.Column("reason", sa.Text),
        sa.Column("started_at", sa.Double, nullable=False),
        sa.Column("finished_at", sa.Double),
    )
    op.create_index("matches_recent", "matches", ["started_at", "id"])
    op.create_index("matches_room", "matches", ["room_id"])
    op.create_table(
        "games",
        sa.Column("match_id", sa.Integer, sa.ForeignKey("matches.id"), nullable=False),
        sa.Column("n", sa.Integer, nullable=False),
        sa.Column("winner", sa.Integer),
        sa.Column("reason", sa.Text),
        sa.Column("cause", sa.Text, nullable=False),
        sa.Column("score", sa.Text, nullable=False),
        sa.Column("finished_at", sa.Double, nullable=False),
        sa.PrimaryKeyConstraint("match_id", "n"),
    )
    op.create_table(
        "shots",
        sa.Column("match_id", sa.Integer, sa.ForeignKey("matches.id"), nullable=False),
        sa.Column("n", sa.Integer, nullable=False),
        sa.Column("room_shot", sa.Integer, nullable=False),
        sa.Column("game", sa.Integer, nullable=False),
        sa.Column("seat", sa.Integer, nullable=False),
        sa.Column("shot", sa.Text, nullable=False),
        sa.Column("table_geom", sa.Text, nullable=False),
        sa.Column("balls", sa.Text, nullable=False),
        sa.Column("outcome", sa.Text, nullable=False),
        sa.Column("played_at", sa.Double, nullable=False),
        sa.PrimaryKeyConstraint("match_id", "n"),
        sa.UniqueConstraint("match_id", "room_shot", name="shots_room_shot"),
    )
    op.create_table(
        "rooms",
        sa.Column("room_id", sa.Text, primary_key=True),
        sa.Column("snapshot", sa.Text, nullable=False),
        sa.Column("updated_at", sa.Double, nullable=False),
    )


def downgrade() -> None:
    for table in ("rooms", "shots", "games", "matches"):
        op.drop_table(table)
