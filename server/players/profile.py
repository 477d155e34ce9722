"""Players without passwords: a secret kept by the browser names the player; the server
keeps only its hash. Seat tokens of a player are derived from the secret, so the same player
gets the same seat back from any tab (and after a restart) without the server storing them.

Pure: `hashlib`, `hmac` and `secrets` only.
"""

from __future__ import annotations

import base64
import hashlib
import hmac
import secrets
from dataclasses import dataclass

SECRET_BYTES = 32
PLAYER_ID_BYTES = 9  # 12 URL-safe characters


class BadName(ValueError):
    """A display name that is empty, too long or not printable."""


@dataclass(frozen=True)
class Player:
    id: str
    name: str
    created_at: float
    account: bool = False  # kept by a password or passkeys, across devices


def new_player_id() -> str:
    return secrets.token_urlsafe(PLAYER_ID_BYTES)


def new_secret() -> str:
    return secrets.token_urlsafe(SECRET_BYTES)


def secret_hash(secret: str) -> str:
    """What the store keeps: the secret is 256 random bits, so one SHA-256 is enough."""
    return hashlib.sha256(secret.encode("utf-8", "surrogatepass")).hexdigest()


def seat_key(secret: str) -> str:
    """The key a player's seat tokens are made from: it opens seats, not the profile, so it
    can wait in the Play now queue without the secret itself."""
    return _mac(secret, "seats")


def seat_token(key: str, room_id: str) -> str:
    """The player's seat token in `room_id` (the room keeps its hash, as for any token)."""
    return _mac(key, f"room:{room_id}")


def _mac(key: str, message: str) -> str:
    digest = hmac.new(key.encode(), message.encode(), hashlib.sha256).digest()
    return base64.urlsafe_b64encode(digest).rstrip(b"=").decode()


def check_name(name: str, max_len: int) -> str:
    """The name as shown: stripped, 1 to `max_len` printable characters (the rule of a
    seat's name); the page escapes it like every name."""
    clean = name.strip()
    if not 1 <= len(clean) <= max_len or not clean.isprintable():
        raise BadName(f"A name is 1 to {max_len} printable characters.")
    return clean


def default_name(player_id: str) -> str:
    return f"Player {player_id[:6]}"
