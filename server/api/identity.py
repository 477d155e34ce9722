"""Who is asking, as a player: the secret in the `pool_player` cookie (HttpOnly, set on a
first visit by `GET /api/players/me`), and the seat key made from it."""

from __future__ import annotations

from starlette.requests import HTTPConnection

from server.players import seat_key

COOKIE = "pool_player"
SECRET_MIN, SECRET_MAX = 20, 64  # characters of a well-formed secret (43 as made)


def cookie_secret(conn: HTTPConnection) -> str | None:
    """The player's secret from the cookie, if it looks like one."""
    secret = conn.cookies.get(COOKIE)
    if secret is None or not SECRET_MIN <= len(secret) <= SECRET_MAX or not secret.isascii():
        return None
    return secret


def player_seat_key(conn: HTTPConnection) -> str | None:
    """The key of the asking player's seat tokens (None: a client without a profile, which
    gets a random token per seat as before)."""
    secret = cookie_secret(conn)
    return None if secret is None else seat_key(secret)
