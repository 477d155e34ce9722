"""The schema as it is now (SQLAlchemy Core tables), for the queries and the schema test.

It changes only through a migration in `migrations/versions/` (Alembic, one set for SQLite
and PostgreSQL); `tests/store` checks the migrated database matches these tables. JSON
columns hold text written by `server.codec.encode`: floats as Python writes them (`repr`),
which read back bit for bit on both backends. Times are float8 (`Double`), exact too.
"""

from __future__ import annotations

from sqlalchemy import (
    BigInteger,
    Column,
    Double,
    ForeignKey,
    Index,
    Integer,
    LargeBinary,
    MetaData,
    PrimaryKeyConstraint,
    Table,
    Text,
    UniqueConstraint,
)

metadata = MetaData()

matches = Table(
    "matches",
    metadata,
    Column("id", Integer, primary_key=True, autoincrement=False),
    Column("room_id", Text, nullable=False),
    Column("kind", Text, nullable=False),
    Column("players", Text, nullable=False),  # JSON list of names, seat order
    Column("race_to", Integer, nullable=False),
    Column("status", Text, nullable=False),  # playing | finished | abandoned
    Column("score", Text, nullable=False),  # JSON list, games won per seat
    Column("winner", Integer),  # seat
    Column("reason", Text),
    Column("started_at", Double, nullable=False),
    Column("finished_at", Double),
    Index("matches_recent", "started_at", "id"),
    Index("matches_room", "room_id"),
)

games = Table(  # players call a game a frame
    "games",
    metadata,
    Column("match_id", Integer, ForeignKey("matches.id"), nullable=False),
    Column("n", Integer, nullable=False),  # 1, 2, ... within the match
    Column("winner", Integer),
    Column("reason", Text),
    Column("cause", Text, nullable=False),  # shot | timeout | concede | forfeit
    Column("score", Text, nullable=False),  # JSON, after this game
    Column("finished_at", Double, nullable=False),
    PrimaryKeyConstraint("match_id", "n"),
)

shots = Table(
    "shots",
    metadata,
    Column("match_id", Integer, ForeignKey("matches.id"), nullable=False),
    Column("n", Integer, nullable=False),  # 1, 2, ... within the match
    Column("room_shot", Integer, nullable=False),  # the room's shot id (live `shot` field)
    Column("game", Integer, nullable=False),  # game number within the match
    Column("seat", Integer, nullable=False),
    Column("shot", Text, nullable=False),  # JSON {angle, speed, tip}
    Column("table_geom", Text, nullable=False),  # JSON Table constructor arguments
    Column("balls", Text, nullable=False),  # JSON BallSet.to_dict() before the shot
    Column("outcome", Text, nullable=False),  # JSON Outcome.to_dict()
    Column("played_at", Double, nullable=False),
    Column("engine", Text),  # ENGINE_VERSION that played it (older rows: none)
    Column("motion", LargeBinary),  # zlib of protocol.plan.motion_text (bytea on PostgreSQL)
    PrimaryKeyConstraint("match_id", "n"),
    UniqueConstraint("match_id", "room_shot", name="shots_room_shot"),
)

rooms = Table(  # live rooms, for restart recovery and failover
    "rooms",
    metadata,
    Column("room_id", Text, primary_key=True),
    Column("snapshot", Text, nullable=False),  # JSON, see server/rooms/snapshot.py
    Column("updated_at", Double, nullable=False),
)

room_owners = Table(  # fencing: the highest ownership epoch each room has seen
    "room_owners",
    metadata,
    Column("room_id", Text, primary_key=True),
    Column("epoch", BigInteger, nullable=False),
    Column("owner", Text, nullable=False),  # who claimed it (a process address), for people
    Column("claimed_at", Double, nullable=False),
)

counters = Table(  # ids handed out in blocks to several processes (`reserve_match_ids`)
    "counters",
    metadata,
    Column("name", Text, primary_key=True),
    Column("value", BigInteger, nullable=False),
)

players = Table(  # profiles: guests (a secret in a cookie) and accounts (server.accounts)
    "players",
    metadata,
    Column("id", Text, primary_key=True),
    Column("name", Text, nullable=False),
    Column("secret_hash", Text, nullable=False, unique=True),  # SHA-256 of the cookie
    Column("created_at", Double, nullable=False),
    # Accounts only (NULL for a guest): the name's NFKC casefold, unique among accounts;
    # the argon2id hash string of the password, if one was set; when the guest claimed it.
    Column("name_key", Text),
    Column("password_hash", Text),
    Column("account_at", Double),
    Index("players_name_key", "name_key", unique=True),
)

player_ratings = Table(  # Glicko-2, one row per player and game kind
    "player_ratings",
    metadata,
    Column("player_id", Text, ForeignKey("players.id"), nullable=False),
    Column("kind", Text, nullable=False),
    Column("rating", Double, nullable=False),
    Column("rd", Double, nullable=False),
    Column("volatility", Double, nullable=False),
    Column("games", Integer, nullable=False),
    Column("wins", Integer, nullable=False),
    Column("rated_at", Double),
    PrimaryKeyConstraint("player_id", "kind"),
    Index("player_ratings_kind", "kind", "rating"),
)

ranked_rooms = Table(  # Play now rooms: who sat where, and the rated result
    "ranked_rooms",
    metadata,
    Column("room_id", Text, primary_key=True),
    Column("kind", Text, nullable=False),
    Column("player0", Text, ForeignKey("players.id"), nullable=False),
    Column("player1", Text, ForeignKey("players.id"), nullable=False),
    Column("names", Text, nullable=False),  # JSON, seat order, as seated
    Column("started_at", Double, nullable=False),
    Column("match_id", Integer),
    Column("winner", Integer),  # seat
    Column("before", Text),  # JSON [[rating, rd, volatility], ...] seat order
    Column("after", Text),
    Column("finished_at", Double),
    Index("ranked_rooms_player0", "player0", "finished_at"),
    Index("ranked_rooms_player1", "player1", "finished_at"),
)

player_seats = Table(  # the seats players with a profile took: their matches on the profile
    "player_seats",
    metadata,
    Column("player_id", Text, ForeignKey("players.id"), nullable=False),
    Column("room_id", Text, nullable=False),
    Column("seat", Integer, nullable=False),
    Column("joined_at", Double, nullable=False),
    PrimaryKeyConstraint("player_id", "room_id"),
    Index("player_seats_room", "room_id"),
)

sessions = Table(  # signed-in devices of accounts: the cookie's SHA-256, never the cookie
    "sessions",
    metadata,
    Column("id_hash", Text, primary_key=True),
    Column("player_id", Text, ForeignKey("players.id"), nullable=False),
    Column("label", Text, nullable=False),  # what the browser said it was, for people
    Column("created_at", Double, nullable=False),
    Column("last_seen", Double, nullable=False),  # expires `session_idle` s after this
    Index("sessions_player", "player_id"),
)

passkeys = Table(  # WebAuthn credentials of accounts (discoverable)
    "passkeys",
    metadata,
    Column("credential_id", Text, primary_key=True),  # base64url of the raw id
    Column("player_id", Text, ForeignKey("players.id"), nullable=False),
    Column("public_key", LargeBinary, nullable=False),  # COSE, as the library verified it
    Column("sign_count", BigInteger, nullable=False),
    Column("label", Text, nullable=False),
    Column("created_at", Double, nullable=False),
    Column("last_used", Double),
    Index("passkeys_player", "player_id"),
)

ceremonies = Table(  # WebAuthn challenges waiting for their answer (one use each)
    "ceremonies",
    metadata,
    Column("id_hash", Text, primary_key=True),  # SHA-256 of the ceremony cookie
    Column("challenge", LargeBinary, nullable=False),
    Column("player_id", Text),  # registration: who asked; sign-in: none
    Column("expires_at", Double, nullable=False),
)
