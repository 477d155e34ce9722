"""Who is asking, as a player: the secret in the `pool_player` cookie (HttpOnly, set on a
first visit by `GET /api/players/me`), and the seat key made from it; or, signed in to an
account, the session id in the `pool_session` cookie (which stands for the secret then:
its hash finds the player, its seat key opens the player's seats). And as a device: the
`pool_device` cookie, set with a browser's first profile and kept when the browser gets
another (one made again after the profile cookie was lost or its guest pruned), so that
Play now can tell two profiles of one browser apart from two people."""

from __future__ import annotations

from starlette.requests import HTTPConnection

from server.players import seat_key, secret_hash

COOKIE = "pool_player"
SESSION_COOKIE = "pool_session"
DEVICE_COOKIE = "pool_device"
SECRET_MIN, SECRET_MAX = 20, 64  # characters of a well-formed secret (43 as made)


def cookie_secret(conn: HTTPConnection, cookie: str = COOKIE) -> str | None:
    """The player's secret from the cookie (or a session id), if it looks like one."""
    secret = conn.cookies.get(cookie)
    if secret is None or not SECRET_MIN <= len(secret) <= SECRET_MAX or not secret.isascii():
        return None
    return secret


def player_seat_key(conn: HTTPConnection) -> str | None:
    """The key of the asking player's seat tokens (None: a client without a profile, which
    gets a random token per seat as before)."""
    secret = cookie_secret(conn)
    return None if secret is None else seat_key(secret)


def device_id(conn: HTTPConnection) -> str | None:
    """The asking browser's device id (a hash of its `pool_device` cookie, so that the
    Play now queue in Redis never holds the cookie itself); None without a well-formed
    one."""
    device = conn.cookies.get(DEVICE_COOKIE)
    if device is None or not SECRET_MIN <= len(device) <= SECRET_MAX or not device.isascii():
        return None
    return secret_hash(device)
