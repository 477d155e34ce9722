"""Shots prepared in a worker process are the shots prepared here, bit for bit."""

from __future__ import annotations

import asyncio

import numpy as np
import pytest

from server.engine import Shot, Table, rack
from server.rooms.prepare import prepare_shot
from server.rooms.shot_runner import ShotRunner
from tests.support.games import BREAK_MESSAGE, EIGHT_BALL_BREAK_BALL, eight_ball_break_ticks
from tests.support.messages import greet, receive_until
from tests.support.rooms import connect, make_client, seated_room

pytestmark = pytest.mark.timeout(120)


def test_a_worker_process_gives_the_same_result_and_messages():
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=11)
    shot = Shot(0.03, 8.5, (0.1, -0.2))

    async def in_worker():
        runner = ShotRunner(1, 6, 2)
        await runner.start()
        try:
            return await runner.prepare(table, balls, shot, 5)
        finally:
            runner.close()

    result, plan = asyncio.run(in_worker())
    here, here_plan = prepare_shot(table, balls, shot, 5, 6, 2)
    assert [(m.at, m.kind, m.body, m.droppable, m.tick) for m in plan] == [
        (m.at, m.kind, m.body, m.droppable, m.tick) for m in here_plan
    ]
    assert result.events == here.events
    assert np.array_equal(result.final.positions, here.final.positions)
    assert np.array_equal(result.frames.positions, here.frames.positions)


def test_a_room_streams_a_break_simulated_in_the_worker(settings):
    with make_client(settings, shot_workers=1, pace=4.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            stream = receive_until(a, "state")
    frames = [m for m in stream if m["type"] == "frame"]
    assert stream[0]["type"] == "event" and stream[0]["kind"] == "strike"
    assert frames[-1]["tick"] == eight_ball_break_ticks() and frames[-1]["last"] is True
    assert stream[-2]["type"] == "shot_result"
    assert stream[-2]["outcome"]["pocketed"] == [EIGHT_BALL_BREAK_BALL]
