"""Settings for the server tests: every clock short, shots streamed 20 times faster."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from server.config import Settings

# Presence at once and no per-client limits: tests of other things open many rooms from
# one address and connect members back to back (tests/hardening checks those limits).
UNLIMITED: dict[str, Any] = {
    "presence_interval": 0.0,
    "max_rooms_per_client": 100_000,
    "room_create_rate": "100000/minute",
    "join_rate": "100000/minute",
    "watch_rate": "100000/minute",
    "player_create_rate": "100000/minute",  # every browser test's page makes a profile
    "queue_rate": "100000/minute",
    "hint_budget": 3600.0,  # s of planning an address may use in a minute
    "playnow_same_address": True,  # every test's players ask from one address
    "player_chat_burst": 1000.0,
    "spectator_chat_burst": 1000.0,
    "crowd_chat_burst": 1000.0,
}
FAST = Settings(
    pace=20.0, grace=60.0, min_shot_clock=0.1, send_timeout=0.5, shot_workers=0, **UNLIMITED
)

INDEX_HTML = "<!doctype html><title>pool</title><p>lobby</p>"


def settings_in(directory: Path, base: Settings = FAST, **changes: Any) -> Settings:
    """`base` with `changes`, a stand-in web client and a database, all in `directory`."""
    web = directory / "web"
    web.mkdir(exist_ok=True)
    (web / "index.html").write_text(INDEX_HTML)
    (web / "js").mkdir(exist_ok=True)
    (web / "js" / "app.js").write_text("export const ok = true;\n")
    return base.replace(web_dir=web, db_path=directory / "billiards.db", **changes)
