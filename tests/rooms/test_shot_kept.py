"""A shot shown is a shot kept: a struck shot's motion goes out only once the store has its
start (what the next owner replays), and while that waits every member is told the table is
being saved. The store here is an observer whose writes the test lets land."""

from __future__ import annotations

from concurrent.futures import Future
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.app import create_app
from server.engine import Shot
from server.rooms import SeedSource, shots
from server.rooms.observer import NullObserver
from tests.support.games import EIGHT_BALL, shoot_message
from tests.support.messages import greet, receive_until
from tests.support.rooms import connect, create_room, join
from tests.support.settings import settings_in


class HeldStarts(NullObserver):
    """Each shot's start stays unstored until the test sets its future."""

    def __init__(self) -> None:
        self.starts: list[Future[Any]] = []

    def shot_started(self, *_: object) -> Future[Any]:
        self.starts.append(Future())
        return self.starts[-1]


def test_a_shot_is_shown_only_once_its_start_is_stored(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(shots, "SAVING_NOTICE", 0.05)
    held = HeldStarts()
    app = create_app(settings_in(tmp_path), observer=held, seeds=SeedSource.fixed(EIGHT_BALL))
    with TestClient(app) as http:
        room_id = create_room(http, "practice")
        token = join(http, room_id, "Ana")["token"]
        with connect(http, room_id, token) as ana, connect(http, room_id) as watcher:
            greet(ana)
            greet(watcher)
            ana.send_json(shoot_message(Shot(0.3, 3.0)))
            for ws in (ana, watcher):  # told, and shown nothing
                notice = receive_until(ws, ("error", "motion"))[-1]
                assert (notice["type"], notice["code"], notice["ref"]) == ("error", "saving", None)
            assert len(held.starts) == 1
            held.starts[0].set_result(None)  # stored: the shot goes on
            for ws in (ana, watcher):
                seen = receive_until(ws, "shot_result")
                assert [m["shot"] for m in seen if m["type"] in ("motion", "shot_result")] == [1, 1]
