"""`python -m server` as a real process of its own (for signals: SIGTERM, kill -9)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import httpx

from tests.support.tiers import needs

from .games import EIGHT_BALL

ROOT = Path(__file__).resolve().parents[2]


@contextmanager
def server_process(port: int, db: Path, **env: str) -> Iterator[subprocess.Popen]:
    """`python -m server` on `port` over the database `db`, every rack of a fixed seed (more
    settings in `env`); waits until it answers. The caller stops it (a signal) before
    leaving; one still running is killed."""
    needs("slow")
    environment = {
        **os.environ,
        "POOL_DB_PATH": str(db),
        "POOL_PACE": "8",
        "POOL_GRACE": "600",
        "POOL_PRESENCE_INTERVAL": "0",
        "POOL_JOIN_RATE": "100000/minute",
        "POOL_ROOM_CREATE_RATE": "100000/minute",
        "POOL_RACK_SEED": str(EIGHT_BALL),
        **env,
    }
    command = [sys.executable, "-m", "server", "--port", str(port), "--log-level", "warning"]
    process = subprocess.Popen(command, cwd=ROOT, env=environment)
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                if httpx.get(f"http://127.0.0.1:{port}/health", timeout=1).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            if process.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError("the server did not start")
            time.sleep(0.05)
        yield process
    finally:
        if process.poll() is None:
            process.kill()
        process.wait(30)
