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


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_worker_process_gives_the_same_result_and_messages():
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=11)
    shot = Shot(0.03, 8.5, (0.1, -0.2))

    async def in_worker():
        runner = ShotRunner(1, 6)
        await runner.start()
        try:
            return await runner.prepare(table, balls, shot, 5)
        finally:
            runner.close()

    result, plan = asyncio.run(in_worker())
    here, here_plan = prepare_shot(table, balls, shot, 5, 6)
    assert plan.motion == here_plan.motion and plan.duration == here_plan.duration
    assert result.events == here.events
    assert np.array_equal(result.final.positions, here.final.positions)
    assert np.array_equal(result.frames.positions, here.frames.positions)


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_room_streams_a_break_simulated_in_the_worker(settings):
    with make_client(settings, shot_workers=1, pace=4.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            stream = receive_until(a, "state")
    assert [m["type"] for m in stream] == ["motion", "shot_result", "state"]
    motion = stream[0]
    assert motion["sounds"][0]["kind"] == "strike"
    assert motion["duration"] == pytest.approx(eight_ball_break_ticks() / 120, abs=1e-6)
    assert stream[-2]["outcome"]["pocketed"] == [EIGHT_BALL_BREAK_BALL]


def test_threads_give_the_message_a_worker_process_gives():
    """The default path (the engine and the tracer in a thread) and `prepare_shot` (one
    call, as in a worker process) make the same `motion` message, byte for byte."""
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=12)
    shot = Shot(-0.02, 7.0, (0.0, 0.3))

    async def in_thread():
        runner = ShotRunner(0, 6)
        try:
            return await runner.prepare(table, balls, shot, 9)
        finally:
            runner.close()

    result, plan = asyncio.run(in_thread())
    here, here_plan = prepare_shot(table, balls, shot, 9, 6)
    assert plan.motion == here_plan.motion
    assert np.array_equal(result.frames.positions, here.frames.positions)
