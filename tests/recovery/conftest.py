"""Helpers for the storage and recovery tests: apps on a throw-away database, a real uvicorn
that can be stopped and started again on the same port and file, websocket helpers."""

from __future__ import annotations

import asyncio
import json
import socket
from contextlib import AbstractContextManager
from pathlib import Path

import pytest

from server.app import create_app
from server.config import Settings
from server.embedded import bound_socket, serving
from server.store import Database

FAST = Settings(pace=20.0, grace=60.0, min_shot_clock=0.1, send_timeout=2.0,
                shot_workers=0)


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    web = tmp_path / "web"
    web.mkdir()
    (web / "index.html").write_text("<!doctype html><title>pool</title>")
    return FAST.replace(web_dir=web, db_path=tmp_path / "billiards.db")


@pytest.fixture
def db_path(tmp_path: Path) -> Path:
    return tmp_path / "history.db"


def app_on(settings: Settings, db_path: Path):
    return create_app(settings, store=Database(db_path))


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def live_server(settings: Settings, db_path: Path, port: int) -> AbstractContextManager[str]:
    """A real uvicorn on 127.0.0.1:`port` over the database at `db_path`."""
    return serving(app_on(settings, db_path), settings, bound_socket(port))


async def recv(ws, timeout: float = 20) -> dict:
    return json.loads(await asyncio.wait_for(ws.recv(), timeout))


async def until(ws, kind: str, timeout: float = 20) -> list[dict]:
    out = []
    while True:
        out.append(await recv(ws, timeout))
        if out[-1]["type"] == kind:
            return out


async def greet(ws) -> tuple[dict, dict]:
    welcome, state, presence = await recv(ws), await recv(ws), await recv(ws)
    assert (welcome["type"], state["type"], presence["type"]) == ("welcome", "state",
                                                                 "presence")
    return welcome, state


def shot_payload(message: dict) -> dict:
    """A streamed message without its room sequence number."""
    return {k: v for k, v in message.items() if k != "seq"}


async def place_cue_ball(shooter, watcher) -> dict:
    """Ball in hand: try spots behind the head string until one is free; returns the
    `state` the `watcher` socket gets for it."""
    for x, y in ((0.5, 0.4), (0.3, 1.0), (0.45, 0.9), (0.2, 0.2), (0.55, 0.6), (0.1, 0.6)):
        await shooter.send(json.dumps({"type": "place_cue", "x": x, "y": y}))
        while (reply := await recv(shooter))["type"] not in ("state", "error"):
            pass
        if reply["type"] == "state":
            return (await until(watcher, "state"))[-1] if watcher is not shooter else reply
    raise AssertionError("no free spot for the cue ball")
