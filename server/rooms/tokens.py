"""Room ids and seat tokens from `secrets`; only token hashes are kept."""

from __future__ import annotations

import hashlib
import secrets

ROOM_ID_BYTES = 9  # 12 URL-safe characters, 72 bits
TOKEN_BYTES = 32


def new_room_id() -> str:
    return secrets.token_urlsafe(ROOM_ID_BYTES)


def new_token() -> str:
    return secrets.token_urlsafe(TOKEN_BYTES)


def hash_token(token: str) -> str:
    """SHA-256 is enough: tokens are 256 random bits, not passwords."""
    return hashlib.sha256(token.encode("utf-8", "surrogatepass")).hexdigest()


def token_matches(token: str, stored_hash: str) -> bool:
    return secrets.compare_digest(hash_token(token), stored_hash)
