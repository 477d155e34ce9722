"""Players: profiles without passwords, Glicko-2 ratings per game kind, ranked rooms and
their results, and the seats players took (server.players, server.store.players)."""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0004"
down_revision = "0003"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "players",
        sa.Column("id", sa.Text, primary_key=True),
        sa.Column("name", sa.Text, nullable=False),
        sa.Column("secret_hash", sa.Text, nullable=False, unique=True),
        sa.Column("created_at", sa.Double, nullable=False),
    )
    op.create_table(
        "player_ratings",
        sa.Column("player_id", sa.Text, sa.ForeignKey("players.id"), nullable=False),
        sa.Column("kind", sa.Text, nullable=False),
        sa.Column("rating", sa.Double, nullable=False),
        sa.Column("rd", sa.Double, nullable=False),
        sa.Column("volatility", sa.Double, nullable=False),
        sa.Column("games", sa.Integer, nullable=False),
        sa.Column("wins", sa.Integer, nullable=False),
        sa.Column("rated_at", sa.Double),
        sa.PrimaryKeyConstraint("player_id", "kind"),
    )
    op.create_index("player_ratings_kind", "player_ratings", ["kind", "rating"])
    op.create_table(
        "ranked_rooms",
        sa.Column("room_id", sa.Text, primary_key=True),
        sa.Column("kind", sa.Text, nullable=False),
        sa.Column("player0", sa.Text, sa.ForeignKey("players.id"), nullable=False),
        sa.Column("player1", sa.Text, sa.ForeignKey("players.id"), nullable=False),
        sa.Column("names", sa.Text, nullable=False),
        sa.Column("started_at", sa.Double, nullable=False),
        sa.Column("match_id", sa.Integer),
        sa.Column("winner", sa.Integer),
        sa.Column("before", sa.Text),
        sa.Column("after", sa.Text),
        sa.Column("finished_at", sa.Double),
    )
    op.create_index("ranked_rooms_player0", "ranked_rooms", ["player0", "finished_at"])
    op.create_index("ranked_rooms_player1", "ranked_rooms", ["player1", "finished_at"])
    op.create_table(
        "player_seats",
        sa.Column("player_id", sa.Text, sa.ForeignKey("players.id"), nullable=False),
        sa.Column("room_id", sa.Text, nullable=False),
        sa.Column("seat", sa.Integer, nullable=False),
        sa.Column("joined_at", sa.Double, nullable=False),
        sa.PrimaryKeyConstraint("player_id", "room_id"),
    )
    op.create_index("player_seats_room", "player_seats", ["room_id"])


def downgrade() -> None:
    op.drop_table("player_seats")
    op.drop_table("ranked_rooms")
    op.drop_table("player_ratings")
    op.drop_table("players")
