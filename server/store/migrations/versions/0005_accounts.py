"""Accounts: a guest player claimed with a password or passkeys keeps its row (id, name,
ratings, history); server-side sessions; passkey credentials; WebAuthn challenges."""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None


def upgrade() -> None:
    with op.batch_alter_table("players") as batch:
        batch.add_column(sa.Column("name_key", sa.Text))
        batch.add_column(sa.Column("password_hash", sa.Text))
        batch.add_column(sa.Column("account_at", sa.Double))
    op.create_index("players_name_key", "players", ["name_key"], unique=True)
    op.create_table(
        "sessions",
        sa.Column("id_hash", sa.Text, primary_key=True),
        sa.Column("player_id", sa.Text, sa.ForeignKey("players.id"), nullable=False),
        sa.Column("label", sa.Text, nullable=False),
        sa.Column("created_at", sa.Double, nullable=False),
        sa.Column("last_seen", sa.Double, nullable=False),
    )
    op.create_index("sessions_player", "sessions", ["player_id"])
    op.create_table(
        "passkeys",
        sa.Column("credential_id", sa.Text, primary_key=True),
        sa.Column("player_id", sa.Text, sa.ForeignKey("players.id"), nullable=False),
        sa.Column("public_key", sa.LargeBinary, nullable=False),
        sa.Column("sign_count", sa.BigInteger, nullable=False),
        sa.Column("label", sa.Text, nullable=False),
        sa.Column("created_at", sa.Double, nullable=False),
        sa.Column("last_used", sa.Double),
    )
    op.create_index("passkeys_player", "passkeys", ["player_id"])
    op.create_table(
        "ceremonies",
        sa.Column("id_hash", sa.Text, primary_key=True),
        sa.Column("challenge", sa.LargeBinary, nullable=False),
        sa.Column("player_id", sa.Text),
        sa.Column("expires_at", sa.Double, nullable=False),
    )


def downgrade() -> None:
    op.drop_table("ceremonies")
    op.drop_table("passkeys")
    op.drop_table("sessions")
    op.drop_index("players_name_key", "players")
    with op.batch_alter_table("players") as batch:
        batch.drop_column("account_at")
        batch.drop_column("password_hash")
        batch.drop_column("name_key")
