"""Server-side sessions: the cookie holds 256 random bits, the store its SHA-256 (as for a
guest's secret), so a copy of the database opens no session. A session ends when signed
out, revoked from another device, or after `idle` seconds unused."""

from __future__ import annotations

import secrets

from server.players import secret_hash

SESSION_BYTES = 32
HANDLE_CHARS = 16  # of the hash: names a session in the list, opens nothing
TOUCH_EVERY = 60.0  # s: last-seen is written at most this often per session
LABEL_MAX = 60

_BROWSERS = (
    ("Edg/", "Edge"),
    ("OPR/", "Opera"),
    ("Firefox/", "Firefox"),
    ("Chrome/", "Chrome"),
    ("Safari/", "Safari"),
)
_SYSTEMS = (
    ("Android", "Android"),
    ("iPhone", "iPhone"),
    ("iPad", "iPad"),
    ("Windows", "Windows"),
    ("Mac OS", "macOS"),
    ("CrOS", "ChromeOS"),
    ("Linux", "Linux"),
)


def new_session() -> tuple[str, str]:
    """(the cookie's value, what the store keeps)."""
    secret = secrets.token_urlsafe(SESSION_BYTES)
    return secret, secret_hash(secret)


def handle(id_hash: str) -> str:
    return id_hash[:HANDLE_CHARS]


def expired(last_seen: float, now: float, idle: float) -> bool:
    return now - last_seen > idle


def device_label(user_agent: str | None) -> str:
    """ "Firefox on Linux": what a person recognises in the list of their sessions."""
    agent = user_agent or ""
    browser = next((b for key, b in _BROWSERS if key in agent), "A browser")
    system = next((s for key, s in _SYSTEMS if key in agent), None)
    label = browser if system is None else f"{browser} on {system}"
    return label[:LABEL_MAX]
