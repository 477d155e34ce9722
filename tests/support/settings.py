"""Settings for the server tests: every clock short, shots streamed 20 times faster."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from server.config import Settings

FAST = Settings(pace=20.0, grace=60.0, min_shot_clock=0.1, send_timeout=0.5, shot_workers=0)

INDEX_HTML = "<!doctype html><title>pool</title><p>lobby</p>"


def settings_in(directory: Path, base: Settings = FAST, **changes: Any) -> Settings:
    """`base` with `changes`, a stand-in web client and a database, all in `directory`."""
    web = directory / "web"
    web.mkdir(exist_ok=True)
    (web / "index.html").write_text(INDEX_HTML)
    (web / "app.js").write_text("export const ok = true;\n")
    return base.replace(web_dir=web, db_path=directory / "billiards.db", **changes)
