"""`superseded_times`: when the frame after each streamed message falls due, so a late room
skips a stale frame instead of sending a burst."""

from __future__ import annotations

import json
import math

from server.engine import Table, rack, simulate
from server.protocol import Timed, plan_shot
from server.rooms.live import superseded_times
from tests.support.games import BREAK, EIGHT_BALL, eight_ball_break_ticks

INF = math.inf


def frame(at: float, index: int) -> Timed:
    return Timed(at, "frame", "{}", True, tick=index * 6, frame=index)


def event(at: float) -> Timed:
    return Timed(at, "event", "{}", False)


def test_each_frame_is_superseded_when_the_next_frame_is_due() -> None:
    plan = [frame(0.05, 0), frame(0.10, 1), frame(0.15, 2)]
    assert superseded_times(plan) == [0.10, 0.15, INF]  # the last frame never is


def test_events_between_frames_wait_for_the_next_frame_not_the_next_event() -> None:
    plan = [event(0.0), frame(0.05, 0), event(0.06), event(0.08), frame(0.10, 1), event(0.12)]
    assert superseded_times(plan) == [0.05, 0.10, 0.10, 0.10, INF, INF]


def test_without_frames_nothing_is_superseded() -> None:
    assert superseded_times([]) == []
    assert superseded_times([event(0.0), event(0.5)]) == [INF, INF]


def test_a_real_break_plan() -> None:
    table = Table.pool("9ft")
    result = simulate(table, rack("eight_ball", table, seed=EIGHT_BALL), BREAK)
    plan = plan_shot(result, 1, 6, 4).messages
    times = superseded_times(plan)
    assert len(times) == len(plan)
    frames = [json.loads(m.body) for m in plan if m.frame is not None]
    ticks = [t for f in frames for t in (f["tick"], *(a["tick"] for a in f.get("ahead", ())))]
    last = eight_ball_break_ticks()
    assert ticks == [*range(6, last, 6), last]  # every 6th tick, and the last
    for i, t in enumerate(times):
        later = [m.at for m in plan[i + 1 :] if m.frame is not None]
        assert t == (later[0] if later else INF)
    assert times == sorted(times) and times[-1] == INF
